// gyro-dethash: runs every determinism scene at every SIMD level x thread count and prints
//   scene <name> <level> <threads> <hash>
// then one summary line per scene:
//   hash <name> <hash>            (or "MISMATCH <name>")
// --check also compares with the pinned golden hashes. Exit 1 on any difference. Built
// for every compiler and target `make determinism` compares (no GoogleTest needed).
// --threads N,M,... replaces the thread counts (1, 2, 3, 8): the emulated aarch64 run uses
// fewer, since every thread count is compared natively by two compilers already and
// emulation is what makes that stage slow.
#include "determinism.hpp"

#include <cinttypes>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <vector>

namespace {
// "1,2,8" -> {1, 2, 8}; empty on a malformed list.
std::vector<uint32_t> parse_threads(const char* s) {
  std::vector<uint32_t> out;
  while (*s) {
    char* end = nullptr;
    const unsigned long v = std::strtoul(s, &end, 10);
    if (end == s || v == 0 || v > 256) return {};
    out.push_back(uint32_t(v));
    s = *end == ',' ? end + 1 : end;
    if (*end != ',' && *end != '\0') return {};
  }
  return out;
}
}  // namespace

int main(int argc, char** argv) {
  using namespace gyro::testing;
  bool check = false, quiet = false;
  std::vector<uint32_t> threads(std::begin(kDetThreadCounts), std::end(kDetThreadCounts));
  for (int i = 1; i < argc; ++i) {
    if (!std::strcmp(argv[i], "--check")) check = true;
    else if (!std::strcmp(argv[i], "--quiet")) quiet = true;
    else if (!std::strcmp(argv[i], "--threads") && i + 1 < argc && !(threads = parse_threads(argv[i + 1])).empty()) ++i;
    else {
      std::fprintf(stderr, "usage: gyro-dethash [--check] [--quiet] [--threads N,M,...]\n");
      return 2;
    }
  }
  int failures = 0;
  for (const DetScene& scene : determinism_scenes()) {
    const auto runs = run_matrix(scene, threads);
    bool same = true;
    for (const DetRun& r : runs) {
      if (!quiet)
        std::printf("scene %-18s %-7s %u 0x%016" PRIx64 "\n", scene.name, gyro::simd_level_name(r.level), r.threads, r.hash);
      same = same && r.hash == runs.front().hash;
    }
    if (!same) {
      std::printf("MISMATCH %s (levels or thread counts disagree)\n", scene.name);
      ++failures;
      continue;
    }
    std::printf("hash %-18s 0x%016" PRIx64 "\n", scene.name, runs.front().hash);
    if (check && runs.front().hash != scene.golden) {
      std::printf("GOLDEN %s expected 0x%016" PRIx64 "\n", scene.name, scene.golden);
      ++failures;
    }
  }
  return failures ? 1 : 0;
}
