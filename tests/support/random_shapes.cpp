#include "random_shapes.hpp"

#include <cmath>
#include <initializer_list>

namespace gyro::testing {

ShapeArray RandomShapes::view() const {
  auto p = [&](int k) { return col[k].data(); };
  switch (type) {
    case ShapeType::sphere: return shape_array(SpheresView{p(0), p(1), p(2), p(3)});
    case ShapeType::aabb: return shape_array(AabbsView{p(0), p(1), p(2), p(3), p(4), p(5)});
    case ShapeType::obb:
      return shape_array(
          ObbsView{p(0), p(1), p(2), p(3), p(4), p(5), p(6), p(7), p(8), p(9), p(10), p(11), p(12), p(13), p(14)});
    case ShapeType::plane: return shape_array(PlanesView{p(0), p(1), p(2), p(3)});
    case ShapeType::triangle: return shape_array(TrianglesView{p(0), p(1), p(2), p(3), p(4), p(5), p(6), p(7), p(8)});
  }
  return {};
}

mat3 random_rotation(SplitMix64& rng) {
  double q[4], len = 0;
  do {
    len = 0;
    for (double& v : q) v = rng.u() - 0.5, len += v * v;
  } while (len < 1e-4);
  len = std::sqrt(len);
  const double x = q[0] / len, y = q[1] / len, z = q[2] / len, w = q[3] / len;
  const double r[3][3] = {{1 - 2 * (y * y + z * z), 2 * (x * y + z * w), 2 * (x * z - y * w)},
                          {2 * (x * y - z * w), 1 - 2 * (x * x + z * z), 2 * (y * z + x * w)},
                          {2 * (x * z + y * w), 2 * (y * z - x * w), 1 - 2 * (x * x + y * y)}};
  mat3 m;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) m.m[i][j] = float(r[i][j]);
  return m;
}

RandomShapes random_shapes(ShapeType type, std::size_t n, SplitMix64& rng, float box) {
  RandomShapes s;
  s.type = type;
  auto push = [&](std::initializer_list<float> v) {
    int k = 0;
    for (float f : v) s.col[k++].push_back(f);
  };
  auto offset = [&] { return vec3{float(rng.u() - 0.5), float(rng.u() - 0.5), float(rng.u() - 0.5)} * 2.0f; };
  for (std::size_t i = 0; i < n; ++i) {
    const vec3 c{float(box * rng.u()), float(box * rng.u()), float(box * rng.u())};
    const vec3 e{float(0.1 + rng.u()), float(0.1 + rng.u()), float(0.1 + rng.u())};
    switch (type) {
      case ShapeType::sphere:
        s.spheres.push_back({c, e.x});
        push({c.x, c.y, c.z, e.x});
        break;
      case ShapeType::aabb:
        s.aabbs.push_back({c, e});
        push({c.x, c.y, c.z, e.x, e.y, e.z});
        break;
      case ShapeType::obb: {
        const mat3 r = random_rotation(rng);
        s.obbs.push_back({c, e, r});
        push({c.x, c.y, c.z, e.x, e.y, e.z, r.m[0][0], r.m[0][1], r.m[0][2], r.m[1][0], r.m[1][1], r.m[1][2], r.m[2][0],
              r.m[2][1], r.m[2][2]});
        break;
      }
      case ShapeType::plane: {
        const mat3 r = random_rotation(rng);
        const vec3 nrm{r.m[0][0], r.m[0][1], r.m[0][2]};
        const float d = float(box * rng.u());
        s.planes.push_back({nrm, d});
        push({nrm.x, nrm.y, nrm.z, d});
        break;
      }
      case ShapeType::triangle: {
        const vec3 a = c + offset(), b = c + offset(), d = c + offset();
        s.triangles.push_back({a, b, d});
        push({a.x, a.y, a.z, b.x, b.y, b.z, d.x, d.y, d.z});
        break;
      }
    }
  }
  return s;
}

}  // namespace gyro::testing
