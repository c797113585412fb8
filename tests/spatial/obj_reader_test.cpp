// The OBJ reader (gyro/obj.hpp): every supported statement and corner form, fan
// triangulation, relative indices, ignored keywords, exact float parsing at the edges of
// float's range; each malformed case with its line number, status and message, leaving
// `out` unchanged; bit-exact round trips of seeded random meshes written with
// std::to_chars' shortest form; load_obj from a file; and a seeded fuzz loop of mutated
// texts that must either give a valid mesh or fail cleanly.
#include "gyro/obj.hpp"

#include "core/error.hpp"
#include "workloads.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <bit>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <string>
#include <vector>

#include <unistd.h>

namespace gyro {
namespace {

using testing::SplitMix64;

bool same_bits(const MeshData& a, const MeshData& b) {
  const auto bits = [](const std::vector<float>& v) {
    std::vector<uint32_t> r;
    for (float f : v) r.push_back(std::bit_cast<uint32_t>(f));
    return r;
  };
  return bits(a.x) == bits(b.x) && bits(a.y) == bits(b.y) && bits(a.z) == bits(b.z) && a.indices == b.indices;
}

// A mesh that no parse could produce, to see that a failure leaves `out` alone.
MeshData sentinel() {
  MeshData m;
  m.add_vertex({-7, 8, 9});
  m.add_vertex({std::numeric_limits<float>::quiet_NaN(), 0, 0});
  m.add_triangle(1, 0, 1);
  return m;
}

MeshData parse_ok(const std::string& text) {
  MeshData m;
  ObjError err{99, "stale"};
  const Status s = parse_obj(text, m, &err);
  EXPECT_EQ(s, Status::ok) << err.message << "\n--- text:\n" << text;
  EXPECT_EQ(err.line, 0u);
  EXPECT_EQ(err.message, "");
  if (s == Status::ok) {
    EXPECT_EQ(validate_mesh(m), Status::ok);
  }
  return m;
}

std::string shortest(float f) {
  char buf[64];
  const auto r = std::to_chars(buf, buf + sizeof buf, f);
  return std::string(buf, r.ptr);
}

// ------------------------------------------------------------------ supported syntax

TEST(ObjParse, VerticesAndATriangle) {
  const MeshData m = parse_ok("v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  ASSERT_EQ(m.vertex_count(), 3u);
  EXPECT_EQ(m.vertex(1), (vec3{1, 0, 0}));
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2}));
}

TEST(ObjParse, EveryCornerFormCommentsWhitespaceAndIgnoredKeywords) {
  const std::string text =
      "\xEF\xBB\xBF# exported by hand\r\n"
      "mtllib scene.mtl\r\n"
      "o thing\r\n"
      "g group1 group2\r\n"
      "\r\n"
      "v 1 2 3 1.0\r\n"  // w
      "v\t-1.5\t+2.25e1   3e-2 # trailing comment\r\n"
      "v 0.5 .5 5. 1 0.2 0.3 0.4\r\n"  // w and a colour
      "v 0 0 -0 \r\n"
      "   \t \r\n"
      "vt 0.5 0.5\r\n"
      "vn 0 0 1\r\n"
      "vp 0.1 0.2\r\n"
      "s off\r\n"
      "usemtl red\r\n"
      "l 1 2\r\n"
      "p 1\r\n"
      "cstype bezier\r\n"  // unknown keywords are ignored too
      "f 1/1/1 2/1/1 3/1/1\r\n"
      "f 1//1 2//1 4//1\r\n"
      "f 2/1 3/1 4/1\r\n"
      "f\t1 3 4#comment\r\n"
      "f +1 2 3";  // no final newline
  const MeshData m = parse_ok(text);
  ASSERT_EQ(m.vertex_count(), 4u);
  EXPECT_EQ(m.vertex(0), (vec3{1, 2, 3}));
  EXPECT_EQ(m.vertex(1), (vec3{-1.5f, 22.5f, 0.03f}));
  EXPECT_EQ(m.vertex(2), (vec3{0.5f, 0.5f, 5.0f}));
  EXPECT_TRUE(std::signbit(m.z[3]));
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 1, 3, 1, 2, 3, 0, 2, 3, 0, 1, 2}));
}

TEST(ObjParse, FansTriangulateInFileWinding) {
  std::string text;
  for (int v = 0; v < 8; ++v) text += "v " + std::to_string(v) + " " + std::to_string(v * v) + " 1\n";
  text += "f 1 2 3 4\n";                  // quad
  text += "f 8 7 6 5 4\n";                // pentagon
  text += "f 1/1 3/1 5/1 7/1 2/1 4/1\n";  // hexagon, with texture indices
  const MeshData m = parse_ok(text);
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 0, 2, 3,           //
                                              7, 6, 5, 7, 5, 4, 7, 4, 3,  //
                                              0, 2, 4, 0, 4, 6, 0, 6, 1, 0, 1, 3}));
}

TEST(ObjParse, NegativeIndicesCountBackFromTheLastVertexSoFar) {
  const MeshData m = parse_ok(
      "v 0 0 0\nv 1 0 0\nv 0 1 0\n"
      "f -3 -2 -1\n"  // 0 1 2
      "v 0 0 1\n"
      "f -1 -3//2 -4/1/1\n"  // 3 1 0
      "f 1 -1 2\n"           // mixed: 0 3 1
      "v 5 5 5\n");          // defined after the faces: changes none of them
  EXPECT_EQ(m.indices, (std::vector<uint32_t>{0, 1, 2, 3, 1, 0, 0, 3, 1}));
  EXPECT_EQ(m.vertex_count(), 5u);  // unreferenced vertices are kept
}

TEST(ObjParse, FloatsAreCorrectlyRoundedAtTheEdgesOfFloatRange) {
  struct Case {
    const char* text;
    float want;
  };
  const float denorm = std::numeric_limits<float>::denorm_min();
  const Case cases[] = {
      {"0.1", 0.1f},
      {"3.4028235e38", std::numeric_limits<float>::max()},
      {"-3.4028235e38", -std::numeric_limits<float>::max()},
      {"1.17549435e-38", std::numeric_limits<float>::min()},
      {"1e-45", denorm},
      {"8e-46", denorm},          // above half of denorm_min: rounds up
      {"7e-46", 0.0f},            // below half: underflows to zero
      {"-1e-60", -0.0f},          // far below: a signed zero
      {"1e-400", 0.0f},           // below even double's range
      {"16777217", 16777216.0f},  // tie to even
      {"16777219", 16777220.0f},
      {"0.000000059604644775390625", 0x1p-24f},
      {"1.00000005960464477539062500001", 1.0000001f},  // just above the tie: up
      {"1.000000059604644775390625", 1.0f},             // exactly the tie: even
  };
  for (const Case& c : cases) {
    const MeshData m = parse_ok(std::string("v ") + c.text + " 0 0\nf 1 1 1\n");
    ASSERT_EQ(m.vertex_count(), 1u);
    EXPECT_EQ(std::bit_cast<uint32_t>(m.x[0]), std::bit_cast<uint32_t>(c.want)) << c.text << " -> " << m.x[0];
  }
}

// ------------------------------------------------------------------ malformed input

struct Bad {
  const char* text;
  std::size_t line;
  const char* part;  // a piece of the message after "line N: "
};

TEST(ObjParse, MalformedInputNamesTheLineAndLeavesOutUnchanged) {
  const char* tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";  // three vertices on lines 1-3
  const std::string t(tri);
  const Bad cases[] = {
      {"v 1 2 x\nf 1 1 1\n", 1, "bad number 'x'"},
      {"# c\nv 1 2 3x\n", 2, "bad number '3x'"},
      {"v 1 2\n", 1, "v needs x y z, got 2 numbers"},
      {"v\n", 1, "got 0 numbers"},
      {"v 1 2 3 4 5 6 7 8\n", 1, "more than 7"},
      {"\n\nv nan 0 0\n", 3, "non-finite number 'nan'"},
      {"v 1 inf 0\n", 1, "non-finite number 'inf'"},
      {"v 1 2 -infinity\n", 1, "non-finite"},
      {"v 1e39 0 0\n", 1, "beyond float's range"},
      {"v 3.4028236e38 0 0\n", 1, "beyond float's range"},
      {"v 1e400 0 0\n", 1, "beyond float's range"},
      {"v 0x10 0 0\n", 1, "bad number '0x10'"},
      {"v 1,5 0 0\n", 1, "bad number '1,5'"},
      {"v ++1 0 0\n", 1, "bad number '++1'"},
      {"v 1e 0 0\n", 1, "bad number '1e'"},
      {"", 1, "no faces"},
      {"# only a comment\n\n", 2, "no faces"},
      {"v 1 2 3\nv 1 2 3\nv 1 2 3\nvn 0 0 1\n", 4, "no faces in the OBJ text (3 vertices)"},
      {"v 1 2 3\r\nv 1 2 3\r\nv 1 2 3\r\nf 1 2 x\r\n", 4, "bad face corner 'x'"},
  };
  const Bad with_tri[] = {
      {"f 0 1 2\n", 4, "bad face corner '0'"},
      {"f 1 2 4\n", 4, "face index 4 names no vertex (3 defined so far)"},
      {"f 1 2 -4\n", 4, "face index -4 names no vertex"},
      {"f 1 2\n", 4, "face has 2 corners"},
      {"f\n", 4, "face has 0 corners"},
      {"f 1/ 2 3\n", 4, "bad face corner '1/'"},
      {"f 1// 2 3\n", 4, "bad face corner '1//'"},
      {"f //1 2 3\n", 4, "bad face corner '//1'"},
      {"f 1/2/3/4 2 3\n", 4, "more than 3 parts"},
      {"f 1/0/1 2 3\n", 4, "bad face corner '1/0/1'"},
      {"f 1//0 2 3\n", 4, "bad face corner"},
      {"f 1.5 2 3\n", 4, "bad face corner '1.5'"},
      {"f 1 2 99999999999999999999999\n", 4, "bad face corner"},
      {"f 1 2 3\nf 1 2 3 4\n", 5, "face index 4"},
      {"f 1 2 3\nv 1 2 \x01\n", 5, "bad number '\\x01'"},
      {"f 1 2 3\n# ok\nf 1 -0 2\n", 6, "bad face corner '-0'"},
  };
  std::vector<Bad> all(std::begin(cases), std::end(cases));
  std::vector<std::string> texts;
  for (const Bad& b : cases) texts.push_back(b.text);
  for (const Bad& b : with_tri) {
    all.push_back(b);
    texts.push_back(t + b.text);
  }
  for (std::size_t i = 0; i < all.size(); ++i) {
    MeshData out = sentinel();
    ObjError err;
    detail::clear_error();
    EXPECT_EQ(parse_obj(texts[i], out, &err), Status::invalid_argument) << texts[i];
    EXPECT_EQ(err.line, all[i].line) << texts[i] << "\n" << err.message;
    const std::string prefix = "line " + std::to_string(all[i].line) + ": ";
    EXPECT_EQ(err.message.rfind(prefix, 0), 0u) << err.message;
    EXPECT_NE(err.message.find(all[i].part), std::string::npos)
        << "'" << err.message << "' lacks '" << all[i].part << "'";
    EXPECT_EQ("invalid_argument: " + err.message, std::string(last_error()));
    EXPECT_TRUE(same_bits(out, sentinel())) << texts[i];
    // Without an ObjError the status and last_error are the same.
    detail::clear_error();
    EXPECT_EQ(parse_obj(texts[i], out), Status::invalid_argument);
    EXPECT_EQ("invalid_argument: " + err.message, std::string(last_error()));
  }
}

TEST(ObjParse, HostileTokensAreQuotedShortAndPrintable) {
  MeshData out;
  ObjError err;
  const std::string text = "v 1 2 " + std::string(5000, '9') + "q\nf 1 1 1\n";
  EXPECT_EQ(parse_obj(text, out, &err), Status::invalid_argument);
  EXPECT_LT(err.message.size(), 200u) << err.message;
  EXPECT_NE(err.message.find("..."), std::string::npos);
  std::string nul_text = "v 1 2 3\nv 1 2 3\nv 1 2 3\nf 1 2 3";
  nul_text += '\0';
  nul_text += "\xff\n";
  EXPECT_EQ(parse_obj(nul_text, out, &err), Status::invalid_argument);
  EXPECT_EQ(err.line, 4u);
  EXPECT_NE(err.message.find("'3\\x00\\xff'"), std::string::npos) << err.message;
  for (char c : err.message) EXPECT_TRUE(c >= 0x20 && c < 0x7f) << int(c);
}

// ------------------------------------------------------------------ round trip

// An OBJ text for m: shortest round-trip floats, each corner in a random form and sign.
std::string write_obj(const MeshData& m, SplitMix64& rng) {
  std::string s = "# gyro round trip\n";
  for (std::size_t v = 0; v < m.vertex_count(); ++v)
    s += "v " + shortest(m.x[v]) + " " + shortest(m.y[v]) + " " + shortest(m.z[v]) + (v % 5 == 0 ? " 1\n" : "\n");
  s += "vt 0 0\nvn 0 1 0\n";
  const long long n = static_cast<long long>(m.vertex_count());
  for (std::size_t t = 0; t < m.triangle_count(); ++t) {
    s += "f";
    for (int k = 0; k < 3; ++k) {
      const long long i = m.indices[3 * t + k];
      const std::string index = rng.next() % 2 ? std::to_string(i + 1) : std::to_string(i - n);
      switch (rng.next() % 4) {
        case 0:
          s += " " + index;
          break;
        case 1:
          s += " " + index + "/1";
          break;
        case 2:
          s += " " + index + "//1";
          break;
        default:
          s += " " + index + "/1/1";
          break;
      }
    }
    s += rng.next() % 2 ? "\n" : "\r\n";
  }
  return s;
}

float random_float(SplitMix64& rng) {
  switch (rng.next() % 6) {
    case 0:
      return float(rng.u() * 2 - 1);
    case 1:
      return std::ldexp(float(rng.u() * 2 - 1), int(rng.next() % 250) - 125);  // any exponent
    case 2: {
      // Any finite bit pattern, subnormals and the largest values included.
      uint32_t bits;
      do bits = uint32_t(rng.next());
      while ((bits & 0x7f800000u) == 0x7f800000u);
      return std::bit_cast<float>(bits);
    }
    case 3:
      return rng.next() % 2 ? 0.0f : -0.0f;
    case 4:
      return float(int(rng.next() % 2001) - 1000);
    default:
      return float(rng.u() * 1e4);
  }
}

TEST(ObjParse, RoundTripsRandomMeshesBitExactly) {
  SplitMix64 rng(0x0B1);
  for (int trial = 0; trial < 300; ++trial) {
    MeshData m;
    const uint32_t nv = 3 + uint32_t(rng.next() % 60);
    for (uint32_t v = 0; v < nv; ++v) m.add_vertex({random_float(rng), random_float(rng), random_float(rng)});
    const int nt = 1 + int(rng.next() % 80);
    for (int t = 0; t < nt; ++t)
      m.add_triangle(uint32_t(rng.next() % nv), uint32_t(rng.next() % nv), uint32_t(rng.next() % nv));
    const std::string text = write_obj(m, rng);
    MeshData back;
    ASSERT_EQ(parse_obj(text, back), Status::ok) << last_error();
    ASSERT_TRUE(same_bits(back, m)) << trial << "\n" << text;
  }
  const MeshData sphere = make_sphere_mesh(3.0f, 20, 30);
  MeshData back;
  ASSERT_EQ(parse_obj(write_obj(sphere, rng), back), Status::ok);
  EXPECT_TRUE(same_bits(back, sphere));
  EXPECT_TRUE(is_closed(back));
}

// ------------------------------------------------------------------ files

TEST(ObjLoad, ReadsAFileAndReportsMissingOnes) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path();
  const std::string path = (dir / ("gyro_obj_test_" + std::to_string(::getpid()) + ".obj")).string();
  SplitMix64 rng(5);
  const MeshData box = make_box_mesh({1, 2, 3});
  const std::string text = write_obj(box, rng);
  {
    std::FILE* f = std::fopen(path.c_str(), "wb");
    ASSERT_NE(f, nullptr);
    ASSERT_EQ(std::fwrite(text.data(), 1, text.size(), f), text.size());
    std::fclose(f);
  }
  MeshData out;
  ObjError err{7, "x"};
  EXPECT_EQ(load_obj(path.c_str(), out, &err), Status::ok) << err.message;
  EXPECT_TRUE(same_bits(out, box));
  EXPECT_EQ(err.line, 0u);
  EXPECT_TRUE(err.message.empty());
  std::filesystem::remove(path);

  out = sentinel();
  EXPECT_EQ(load_obj(path.c_str(), out, &err), Status::invalid_argument);
  EXPECT_EQ(err.line, 0u);
  EXPECT_NE(err.message.find(path), std::string::npos) << err.message;
  EXPECT_EQ("invalid_argument: " + err.message, std::string(last_error()));
  EXPECT_TRUE(same_bits(out, sentinel()));

  EXPECT_EQ(load_obj(dir.string().c_str(), out, &err), Status::invalid_argument);  // a directory
  EXPECT_TRUE(same_bits(out, sentinel()));
  EXPECT_EQ(load_obj(nullptr, out, &err), Status::null_argument);
  EXPECT_TRUE(same_bits(out, sentinel()));
}

// ------------------------------------------------------------------ fuzz

TEST(ObjParse, MutatedTextsNeverCrashAndEitherParseValidOrFailCleanly) {
  SplitMix64 rng(0xF022);
  const std::string seeds[] = {
      "v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\nf 1 2 3\nf 1 3 4\nf -4/1/1 -2/1/1 -3/1/1\nf 2//1 3//1 4//1\n",
      "# box\r\no box\r\nv -1 -1 -1\r\nv 1 -1 -1\r\nv 1 1 -1\r\nv -1 1 -1\r\nvt 0 0\r\nvn 0 0 -1\r\n"
      "f 1/1/1 2/1/1 3/1/1 4/1/1\r\ng side\r\nusemtl m\r\nf 4 3 2 1\r\n",
      "v 1.5e-3 -2.25E+2 .5 1\nv +3 4. 5\nv 6 7 8 0.1 0.2 0.3\ns 1\nf 1 2 3 # c\nl 1 2\np 3\n",
  };
  const char alphabet[] = "0123456789-+./ \t\r\n#vfeEn/";
  int ok = 0, failed = 0;
  for (int trial = 0; trial < 4000; ++trial) {
    std::string text = seeds[rng.next() % 3];
    const int mutations = 1 + int(rng.next() % 6);
    for (int k = 0; k < mutations; ++k) {
      const std::size_t at = text.empty() ? 0 : rng.next() % text.size();
      switch (rng.next() % 6) {
        case 0:
          if (!text.empty()) text[at] = char(rng.next());
          break;  // any byte
        case 1:
          if (!text.empty()) text[at] = alphabet[rng.next() % (sizeof alphabet - 1)];
          break;
        case 2:
          text.insert(at, 1, alphabet[rng.next() % (sizeof alphabet - 1)]);
          break;
        case 3:
          text.erase(at, rng.next() % 8);
          break;
        case 4:
          text.insert(at, text.substr(rng.next() % (text.size() + 1), rng.next() % 24));
          break;  // duplicate
        default:
          text.insert(at, rng.next() % 2 ? "f -1 -2 -3\n" : "v 1e38 -1e-38 nan\n");
          break;
      }
    }
    MeshData out = sentinel();
    ObjError err;
    const Status s = parse_obj(text, out, &err);
    if (s == Status::ok) {
      ASSERT_EQ(validate_mesh(out), Status::ok) << text;
      ASSERT_EQ(err.line, 0u);
      ++ok;
    } else {
      ASSERT_EQ(s, Status::invalid_argument) << text;
      ASSERT_TRUE(same_bits(out, sentinel())) << text;
      const std::size_t lines = std::size_t(std::count(text.begin(), text.end(), '\n')) + 1;
      ASSERT_GE(err.line, 1u);
      ASSERT_LE(err.line, lines) << text;
      ASSERT_EQ(err.message.rfind("line " + std::to_string(err.line) + ": ", 0), 0u) << err.message;
      ASSERT_EQ("invalid_argument: " + err.message, std::string(last_error()));
      ++failed;
    }
    // The same text gives the same answer.
    MeshData again;
    ASSERT_EQ(parse_obj(text, again), s);
    if (s == Status::ok) {
      ASSERT_TRUE(same_bits(again, out));
    }
  }
  std::printf("  fuzz: %d parsed, %d rejected cleanly\n", ok, failed);
  EXPECT_GT(ok, 250);
  EXPECT_GT(failed, 400);
}

}  // namespace
}  // namespace gyro
