// A Wavefront OBJ reader for triangle meshes (Cookbook chapter 11 loads its meshes this way).
//
// What is read:
//  - `v x y z [w]`: a vertex; w (and up to three more numbers, the common `v x y z r g b`
//    vertex-colour extension) is checked to be a finite number and otherwise ignored.
//  - `f v1 v2 v3 ...`: a face of 3 or more corners, each `i`, `i/t`, `i//n` or `i/t/n`;
//    only i is used (t and n must be non-zero integers but are not resolved). A face of
//    n corners becomes the fan (v1, v2, v3), (v1, v3, v4), ..., (v1, vn-1, vn), in the
//    file's winding. i > 0 is 1-based and must name a vertex defined above the face;
//    i < 0 counts back from the last vertex defined so far (-1 is the last).
//  - `#` starts a comment anywhere on a line; blank lines, spaces and tabs, CRLF line ends
//    and a UTF-8 byte-order mark at the start are accepted.
//  - Every other keyword (vn, vt, vp, o, g, s, usemtl, mtllib, l, p, and unknown ones such
//    as free-form curve statements) is ignored with its line, so files from any exporter
//    load; a line's keyword is its first token. Line continuation with `\` is not supported.
// Numbers are parsed exactly and independently of the locale: coordinates with
// std::from_chars (correctly rounded to float; a leading '+' is accepted; a value too small
// for float becomes a signed zero; NaN, infinities and values beyond float's range are
// errors), indices as decimal integers.
//
// Errors: malformed input (a bad or missing number, a non-finite coordinate, index 0 or
// one naming no vertex, a face of fewer than 3 corners, more than 2^31 - 1 vertices or
// triangles, no face at all) returns Status::invalid_argument, with a message that starts
// "line N:" (N 1-based; for "no faces" the last line) in ObjError and, after the status
// name, in gyro::last_error(). Out of memory returns Status::out_of_memory. On any failure
// `out` is left unchanged; on success it is replaced by a mesh that passes validate_mesh,
// with the vertices in file order (unreferenced ones kept) and the triangles in file order.
#pragma once

#include "gyro/mesh.hpp"
#include "gyro/status.hpp"

#include <cstddef>
#include <string>
#include <string_view>

namespace gyro {

/// Where and why an OBJ text failed to parse.
struct ObjError {
  std::size_t line = 0;  ///< 1-based line of the error; 0 for a file that could not be read, or on success
  std::string message;   ///< the detail; gyro::last_error() holds "<status name>: " and this ("" on success)
};

/// Parses OBJ text (see the file comment) into `out`. `error`, if given, receives the
/// failure's line and message, or {0, ""} on success.
Status parse_obj(std::string_view text, MeshData& out, ObjError* error = nullptr);

/// Reads the file at `path` and parses it as parse_obj does. A null path is
/// Status::null_argument; a file that cannot be opened or read is Status::invalid_argument
/// (line 0).
Status load_obj(const char* path, MeshData& out, ObjError* error = nullptr);

}  // namespace gyro
