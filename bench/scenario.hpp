// The scenario runner's shared pieces: options, timing (median of reps), JSON lines.
// Output format: BENCHMARKS.md ("one JSON object per line and measurement").
#pragma once

#include "gyro/runtime.hpp"

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <string>
#include <vector>

namespace gyro::bench {

struct Options {
  std::string workload;             // empty: all
  std::vector<uint32_t> threads;    // empty: {1, 2}
  std::vector<SimdLevel> levels;    // empty: every available level
  int reps = 5;
  bool peers = false;
};

/// One JSON object on one line; keys in insertion order.
class JsonLine {
 public:
  JsonLine& str(const char* key, const std::string& v);
  JsonLine& num(const char* key, double v, int precision = 6);
  JsonLine& integer(const char* key, int64_t v);
  JsonLine& hex(const char* key, uint64_t v);
  void print() const;

 private:
  std::string body_;
  void key(const char* k);
};

/// The median of the values (the mean of the middle two for an even count; NaN for none).
double median(std::vector<double> v);
/// Median wall time in milliseconds of `reps` runs of fn (after one warm-up run).
double median_ms(int reps, const std::function<void()>& fn);
/// The same, with `untimed` called after each run of fn outside the clock: where a run's
/// result replaces the last one, its release (a peer's is never timed) goes there.
double median_ms(int reps, const std::function<void()>& fn, const std::function<void()>& untimed);

/// The levels to run: the requested ones that are available, or all available.
std::vector<SimdLevel> levels_to_run(const Options& o);
std::vector<uint32_t> threads_to_run(const Options& o);

struct Workload {
  const char* name;
  const char* description;
  void (*run)(const Options&);
};

}  // namespace gyro::bench
