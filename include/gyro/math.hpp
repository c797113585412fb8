// gyro's math library in one include: scalars, vectors, matrices, quaternions, transforms
// and the deterministic trigonometry they are built on (Cookbook chapters 1-3).
#pragma once

#include "gyro/math_mat.hpp"
#include "gyro/math_quat.hpp"
#include "gyro/math_scalar.hpp"
#include "gyro/math_transform.hpp"
#include "gyro/math_trig.hpp"
#include "gyro/math_vec.hpp"
