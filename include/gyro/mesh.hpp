// Indexed triangle meshes (Cookbook chapter 11): vertex positions as structure of arrays and
// three vertex indices per triangle. This is the plain data a mesh is made of; the BVH and
// the queries over it live in gyro/triangle_mesh.hpp, the OBJ reader in gyro/obj.hpp.
//
// Conventions:
//  - Triangle i has corners (x, y, z)[indices[3i]], [indices[3i + 1]], [indices[3i + 2]];
//    its geometric normal is (b - a) x (c - a) (counter-clockwise seen from the front).
//    Queries are double-sided.
//  - A valid mesh has at least one triangle, every index below the vertex count, and finite
//    coordinates. Degenerate (zero-area) triangles are valid: see gyro/triangle.hpp.
//  - The free functions below the struct check, measure, weld and generate meshes. Every
//    one is deterministic (sorts on integer keys with explicit tie-breaks, no hash maps,
//    nothing that depends on pointer values); the generators use gyro's own sin/cos, so
//    they give the same bits everywhere.
//  - A function that returns a MeshData reports bad input by returning an empty MeshData
//    (which validate_mesh rejects) and recording the reason in gyro::last_error().
#pragma once

#include "gyro/shapes.hpp"
#include "gyro/status.hpp"

#include <cstddef>
#include <cstdint>
#include <vector>

namespace gyro {

struct MeshData {
  std::vector<float> x, y, z;     ///< vertex positions, one entry per vertex
  std::vector<uint32_t> indices;  ///< 3 per triangle

  std::size_t vertex_count() const { return x.size(); }
  std::size_t triangle_count() const { return indices.size() / 3; }
  vec3 vertex(std::size_t v) const { return {x[v], y[v], z[v]}; }
  /// Corners of triangle i (no bounds check: validate the mesh first).
  Triangle triangle(std::size_t i) const {
    return {vertex(indices[3 * i]), vertex(indices[3 * i + 1]), vertex(indices[3 * i + 2])};
  }
  void add_vertex(const vec3& p) { x.push_back(p.x), y.push_back(p.y), z.push_back(p.z); }
  void add_triangle(uint32_t a, uint32_t b, uint32_t c) { indices.insert(indices.end(), {a, b, c}); }
};

/// Checks the invariants of a valid mesh, in this order, and names the first offence in
/// gyro::last_error(): x, y and z have equal sizes, indices.size() is a multiple of 3,
/// there is at least one triangle, fewer than 2^31 vertices and 2^31 triangles
/// (all Status::invalid_count); every index is below the vertex count (invalid_argument,
/// naming the first bad triangle); every coordinate, referenced or not, is finite
/// (non_finite, naming the first bad vertex).
Status validate_mesh(const MeshData& mesh);

/// The AABB of the vertices that some triangle references (the union of the triangles'
/// bounds; unreferenced vertices are ignored, and out-of-range indices are skipped). The
/// box is conservative in float arithmetic: aabb_min(b) <= v <= aabb_max(b) holds exactly
/// for every referenced vertex v, within an ulp or two of the tightest such box. A mesh
/// with no in-range index (or with x, y, z of different sizes) gives the zero box {0, 0}.
AABB mesh_bounds(const MeshData& mesh);

/// True when every undirected edge is used by exactly two triangles, once in each
/// direction: a closed, consistently oriented surface (what a watertight solid needs). The
/// test is on edges only, so two closed surfaces that share only a vertex also pass. A
/// triangle with a repeated index (a zero-length edge) and an invalid mesh give false.
/// Deterministic: sorts packed edge keys. O(T log T).
bool is_closed(const MeshData& mesh);

/// The mesh with coincident vertices merged and unreferenced vertices removed; the
/// triangles keep their order and corner order (a triangle whose corners merge stays, as a
/// degenerate one). tolerance == 0 merges only bit-identical positions (so -0 and +0 stay
/// apart). tolerance > 0 clusters greedily in vertex-index order: each referenced vertex
/// joins the lowest-index representative within tolerance on every axis
/// (|dx|, |dy|, |dz| <= tolerance in float), or becomes a representative itself. Either way
/// a representative keeps its position, the output vertices are the representatives in
/// their original order, and no two output vertices would merge again (none bit-identical
/// for tolerance 0, none within tolerance on every axis otherwise). O(V log V) typical.
/// An invalid mesh or a negative or non-finite tolerance gives an empty mesh (see above).
MeshData weld_vertices(const MeshData& mesh, float tolerance = 0.0f);

/// A box centred on the origin: 8 vertices, 12 triangles, closed, counter-clockwise seen
/// from outside (normals point outward). Zero half extents are allowed (a flat box);
/// negative or non-finite ones give an empty mesh.
MeshData make_box_mesh(const vec3& half_extents);

/// A UV sphere centred on the origin with y as its axis: a vertex at each pole (shared by
/// the pole's triangles), stacks - 1 rings of `slices` vertices, and 2 * slices * (stacks - 1)
/// triangles, closed and counter-clockwise seen from outside. Vertices are
/// radius * (sin t cos p, cos t, sin t sin p) with t = pi i / stacks, p = 2 pi j / slices.
/// Needs stacks in [2, 4096], slices in [3, 4096] and a finite radius >= 0 (0 gives a
/// point-sized sphere of degenerate triangles); otherwise an empty mesh.
MeshData make_sphere_mesh(float radius, int stacks, int slices);

/// Height callback of make_grid_mesh: the y of the vertex at (x, z).
using GridHeightFn = float (*)(float x, float z, void* context);

/// A grid of cells_x by cells_z square cells of side cell_size on the x-z plane, centred on
/// the origin: vertex (i, j) for i in [0, cells_x], j in [0, cells_z] is at index
/// j * (cells_x + 1) + i, x = (i - cells_x / 2) * cell_size, z = (j - cells_z / 2) * cell_size
/// (symmetric to the bit), y = height(x, z, context), or 0 without a callback. Each cell is
/// two triangles, split along its diagonal from (i + 1, j) to (i, j + 1), counter-clockwise
/// seen from +y (normals up for a flat grid). An open surface: is_closed() is false. Needs
/// cells_x and cells_z in [1, 16384] and a finite cell_size > 0, and every height finite;
/// otherwise an empty mesh.
MeshData make_grid_mesh(int cells_x, int cells_z, float cell_size, GridHeightFn height = nullptr,
                        void* context = nullptr);

}  // namespace gyro
