// The Wavefront OBJ reader (gyro/obj.hpp): one pass over the text, line by line, into a
// temporary MeshData that replaces `out` only when the whole text is good.
//
// Numbers go through std::from_chars (locale-independent, correctly rounded); nothing here
// depends on the C locale, errno or the allocator. Error messages quote the offending token
// with non-printable bytes escaped and long tokens cut, so hostile input cannot make a
// message unreadable or huge.
#include "gyro/obj.hpp"

#include "core/error.hpp"
#include "core/validate.hpp"

#include <charconv>
#include <cstdarg>
#include <cstdio>
#include <memory>
#include <new>
#include <system_error>
#include <vector>

namespace gyro {
namespace {

constexpr std::size_t kMaxCount = (std::size_t(1) << 31) - 1;  // vertices and triangles, inclusive

bool is_space(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f'; }

// Splits a line (comment already cut) into whitespace-separated tokens.
class Tokens {
 public:
  explicit Tokens(std::string_view line) : rest_(line) {}
  /// The next token, or an empty view at the end of the line.
  std::string_view next() {
    std::size_t i = 0;
    while (i < rest_.size() && is_space(rest_[i])) ++i;
    std::size_t j = i;
    while (j < rest_.size() && !is_space(rest_[j])) ++j;
    const std::string_view token = rest_.substr(i, j - i);
    rest_.remove_prefix(j);
    return token;
  }

 private:
  std::string_view rest_;
};

// A token as it may appear in a message: at most 32 bytes, non-printable bytes as \xNN.
std::string quoted(std::string_view token) {
  std::string q = "'";
  const std::size_t n = token.size() < 32 ? token.size() : 32;
  for (std::size_t i = 0; i < n; ++i) {
    const unsigned char c = static_cast<unsigned char>(token[i]);
    if (c >= 0x20 && c < 0x7f && c != '\'' && c != '\\') {
      q += char(c);
    } else {
      char buf[8];
      std::snprintf(buf, sizeof buf, "\\x%02x", unsigned(c));
      q += buf;
    }
  }
  if (n < token.size()) q += "...";
  return q + "'";
}

// from_chars accepts '-' but not '+'; OBJ writers that print with %+f emit one.
std::string_view skip_plus(std::string_view s) {
  if (s.size() >= 2 && s[0] == '+' && s[1] != '+' && s[1] != '-') s.remove_prefix(1);
  return s;
}

enum class Number { ok, malformed, non_finite, out_of_range };

// For a token that from_chars read whole but found out of float's range: whether it is
// tiny (rather than huge), from its decimal order of magnitude. Float's range ends near
// 10^38 and 10^-45, far from 10^0, so this coarse order decides exactly.
bool is_tiny(std::string_view s) {
  std::size_t i = (!s.empty() && s[0] == '-') ? 1 : 0;
  int64_t order = 0;  // the power of ten of the first non-zero digit, before the exponent
  bool seen = false, point = false;
  for (; i < s.size() && s[i] != 'e' && s[i] != 'E'; ++i) {
    if (s[i] == '.') {
      point = true;
    } else if (!seen && s[i] == '0') {
      if (point) --order;
    } else if (!seen) {
      seen = true;
      if (point) --order;
    } else if (!point) {
      ++order;
    }
  }
  int64_t exponent = 0;
  if (i + 1 < s.size()) {
    const bool negative = s[i + 1] == '-';
    for (std::size_t k = i + 1 + (s[i + 1] == '-' || s[i + 1] == '+'); k < s.size(); ++k)
      exponent = exponent < 1000000000 ? exponent * 10 + (s[k] - '0') : exponent;  // saturates
    if (negative) exponent = -exponent;
  }
  return order + exponent < 0;
}

Number parse_float(std::string_view token, float& value) {
  const std::string_view s = skip_plus(token);
  const char* end = s.data() + s.size();
  float v = 0.0f;
  const auto r = std::from_chars(s.data(), end, v, std::chars_format::general);
  if (r.ptr != end || r.ec == std::errc::invalid_argument) return Number::malformed;
  if (r.ec == std::errc::result_out_of_range) {
    // from_chars reports both overflow and underflow to zero this way. A value that rounds
    // to zero is read as a signed zero, its correct rounding.
    if (!is_tiny(s)) return Number::out_of_range;
    value = s[0] == '-' ? -0.0f : 0.0f;
    return Number::ok;
  }
  if (!detail::is_finite(v)) return Number::non_finite;
  value = v;
  return Number::ok;
}

// A decimal integer, the whole of s (empty is malformed).
bool parse_int(std::string_view token, int64_t& value) {
  const std::string_view s = skip_plus(token);
  const char* end = s.data() + s.size();
  const auto r = std::from_chars(s.data(), end, value, 10);
  return r.ec == std::errc() && r.ptr == end && !s.empty();
}

class Parser {
 public:
  explicit Parser(ObjError* error) : error_(error) {}

  Status run(std::string_view text) {
    if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
    std::size_t pos = 0;
    while (pos < text.size()) {
      std::size_t nl = text.find('\n', pos);
      if (nl == std::string_view::npos) nl = text.size();
      std::string_view line = text.substr(pos, nl - pos);
      pos = nl + 1;
      ++line_;
      if (const std::size_t hash = line.find('#'); hash != std::string_view::npos) line = line.substr(0, hash);
      Tokens tokens(line);
      const std::string_view keyword = tokens.next();
      if (keyword == "v") {
        GYRO_TRY(read_vertex(tokens));
      } else if (keyword == "f") {
        GYRO_TRY(read_face(tokens));
      }
      // Anything else (vn, vt, vp, o, g, s, usemtl, mtllib, l, p, curves, unknown) is ignored.
    }
    if (line_ == 0) line_ = 1;
    if (mesh_.indices.empty()) return fail("no faces in the OBJ text (%zu vertices)", mesh_.vertex_count());
    return Status::ok;
  }

  MeshData& mesh() { return mesh_; }
  std::size_t line() const { return line_; }

  /// Records "line N: <detail>" as the failure of this parse.
  Status fail(const char* format, ...) __attribute__((format(printf, 2, 3))) {
    char detail_text[256];
    va_list args;
    va_start(args, format);
    std::vsnprintf(detail_text, sizeof detail_text, format, args);
    va_end(args);
    return record(Status::invalid_argument, line_, "line " + std::to_string(line_) + ": " + detail_text);
  }

  /// Records a failure with its status, line and full message.
  Status record(Status s, std::size_t line, const std::string& message) {
    if (error_) {
      error_->line = line;
      error_->message = message;
    }
    return detail::fail(s, "%s", message.c_str());
  }

 private:
  Status read_vertex(Tokens& tokens) {
    float c[3] = {0.0f, 0.0f, 0.0f};
    int count = 0;
    for (std::string_view token = tokens.next(); !token.empty(); token = tokens.next(), ++count) {
      if (count == 7) return fail("v has more than 7 numbers (x y z [w] or x y z [w] r g b)");
      float value = 0.0f;
      switch (parse_float(token, value)) {
        case Number::ok:
          break;
        case Number::malformed:
          return fail("bad number %s in v", quoted(token).c_str());
        case Number::non_finite:
          return fail("v has a non-finite number %s", quoted(token).c_str());
        case Number::out_of_range:
          return fail("number %s in v is beyond float's range", quoted(token).c_str());
      }
      if (count < 3) c[count] = value;
    }
    if (count < 3) return fail("v needs x y z, got %d number%s", count, count == 1 ? "" : "s");
    if (mesh_.vertex_count() >= kMaxCount) return fail("more than %zu vertices", kMaxCount);
    mesh_.add_vertex({c[0], c[1], c[2]});
    return Status::ok;
  }

  // One corner `i`, `i/t`, `i//n` or `i/t/n`: its 0-based vertex index.
  Status read_corner(std::string_view token, uint32_t& vertex) {
    std::string_view part[3];
    int parts = 0;
    for (std::size_t start = 0;;) {
      const std::size_t slash = token.find('/', start);
      if (parts == 3) return fail("face corner %s has more than 3 parts", quoted(token).c_str());
      part[parts++] = token.substr(start, slash == std::string_view::npos ? std::string_view::npos : slash - start);
      if (slash == std::string_view::npos) break;
      start = slash + 1;
    }
    // i//n leaves the middle part empty; any other empty part is malformed.
    for (int k = 0; k < parts; ++k) {
      if (part[k].empty() && k == 1 && parts == 3) continue;
      int64_t value = 0;
      if (!parse_int(part[k], value) || value == 0)
        return fail("bad face corner %s (expected i, i/t, i//n or i/t/n with non-zero integers)",
                    quoted(token).c_str());
      if (k == 0) {
        const int64_t n = int64_t(mesh_.vertex_count());
        if (value > n || value < -n)
          return fail("face index %lld names no vertex (%lld defined so far)", static_cast<long long>(value),
                      static_cast<long long>(n));
        vertex = uint32_t(value > 0 ? value - 1 : n + value);
      }
    }
    return Status::ok;
  }

  Status read_face(Tokens& tokens) {
    corners_.clear();
    for (std::string_view token = tokens.next(); !token.empty(); token = tokens.next()) {
      uint32_t v = 0;
      GYRO_TRY(read_corner(token, v));
      corners_.push_back(v);
    }
    if (corners_.size() < 3)
      return fail("face has %zu corner%s; at least 3 are needed", corners_.size(), corners_.size() == 1 ? "" : "s");
    if (mesh_.triangle_count() + (corners_.size() - 2) > kMaxCount) return fail("more than %zu triangles", kMaxCount);
    for (std::size_t k = 1; k + 1 < corners_.size(); ++k) mesh_.add_triangle(corners_[0], corners_[k], corners_[k + 1]);
    return Status::ok;
  }

  MeshData mesh_;
  std::vector<uint32_t> corners_;
  std::size_t line_ = 0;
  ObjError* error_;
};

}  // namespace

Status parse_obj(std::string_view text, MeshData& out, ObjError* error) {
  Parser parser(error);
  try {
    GYRO_TRY(parser.run(text));
    out = std::move(parser.mesh());
  } catch (const std::bad_alloc&) {
    return parser.record(Status::out_of_memory, parser.line(),
                         "line " + std::to_string(parser.line()) + ": out of memory reading the OBJ text");
  }
  if (error) *error = ObjError{};
  return Status::ok;
}

Status load_obj(const char* path, MeshData& out, ObjError* error) {
  Parser reporter(error);
  if (!path) return reporter.record(Status::null_argument, 0, "load_obj: path is null");
  const std::unique_ptr<std::FILE, int (*)(std::FILE*)> file(std::fopen(path, "rb"), &std::fclose);
  if (!file) return reporter.record(Status::invalid_argument, 0, std::string("cannot open OBJ file '") + path + "'");
  std::string text;
  try {
    char buffer[1 << 16];
    for (;;) {
      const std::size_t n = std::fread(buffer, 1, sizeof buffer, file.get());
      text.append(buffer, n);
      if (n < sizeof buffer) break;
    }
  } catch (const std::bad_alloc&) {
    return reporter.record(Status::out_of_memory, 0, std::string("out of memory reading OBJ file '") + path + "'");
  }
  if (std::ferror(file.get()))
    return reporter.record(Status::invalid_argument, 0, std::string("cannot read OBJ file '") + path + "'");
  return parse_obj(text, out, error);
}

}  // namespace gyro
