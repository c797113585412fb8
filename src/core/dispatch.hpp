// Kernel dispatch: one function per SIMD level, chosen at run time.
//
// A kernel header declares a kernel once, inside namespace gyro:
//
//   using raycast_batch_fn = void(const RaycastArgs&, std::size_t, std::size_t);
//   GYRO_KERNEL(raycast_batch, raycast_batch_fn)
//
// which declares gyro::arch_<level>::raycast_batch for every level the build has and
// gyro::detail::raycast_batch_for(level). The kernel source defines the function in
// namespace gyro::GYRO_ARCH_NS and is listed in the build's kernel sources, so it is
// compiled once per level. Call it as `GYRO_DISPATCH(raycast_batch)(args, b, e)`.
#pragma once

#include "core/arch.hpp"
#include "gyro/runtime.hpp"

#define GYRO_KERNEL_DECLARE_ONE_(level, ns, name, type) \
  namespace ns {                                        \
  extern type name;                                     \
  }
#define GYRO_KERNEL_CASE_ONE_(level, ns, name, type) \
  case ::gyro::SimdLevel::level:                     \
    return &::gyro::ns::name;

#define GYRO_KERNEL(name, type)                                      \
  GYRO_FOR_EACH_ARCH(GYRO_KERNEL_DECLARE_ONE_, name, type)           \
  namespace detail {                                                 \
  inline type* name##_for(::gyro::SimdLevel level) {                 \
    switch (level) {                                                 \
      GYRO_FOR_EACH_ARCH(GYRO_KERNEL_CASE_ONE_, name, type)          \
      default: break;                                                \
    }                                                                \
    return &::gyro::arch_scalar::name;                               \
  }                                                                  \
  }

#define GYRO_DISPATCH(name) (::gyro::detail::name##_for(::gyro::simd_level()))
