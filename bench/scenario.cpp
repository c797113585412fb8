#include "scenario.hpp"

#include <algorithm>
#include <cinttypes>
#include <cmath>

namespace gyro::bench {

void JsonLine::key(const char* k) {
  body_ += body_.empty() ? "{" : ",";
  body_ += "\"";
  body_ += k;
  body_ += "\":";
}
JsonLine& JsonLine::str(const char* k, const std::string& v) {
  key(k);
  body_ += "\"" + v + "\"";
  return *this;
}
JsonLine& JsonLine::num(const char* k, double v, int precision) {
  key(k);
  if (!std::isfinite(v)) {
    body_ += "null";
    return *this;
  }
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", precision, v);
  body_ += buf;
  return *this;
}
JsonLine& JsonLine::integer(const char* k, int64_t v) {
  key(k);
  body_ += std::to_string(v);
  return *this;
}
JsonLine& JsonLine::hex(const char* k, uint64_t v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "0x%016" PRIx64, v);
  return str(k, buf);
}
void JsonLine::print() const {
  std::printf("%s}\n", body_.c_str());
  std::fflush(stdout);
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

double median_ms(int reps, const std::function<void()>& fn) { return median_ms(reps, fn, [] {}); }

double median_ms(int reps, const std::function<void()>& fn, const std::function<void()>& untimed) {
  fn();  // warm-up: page faults, thread pool start
  untimed();
  std::vector<double> t;
  for (int i = 0; i < std::max(1, reps); ++i) {
    const auto a = std::chrono::steady_clock::now();
    fn();
    const auto b = std::chrono::steady_clock::now();
    untimed();
    t.push_back(std::chrono::duration<double, std::milli>(b - a).count());
  }
  return median(std::move(t));
}

std::vector<SimdLevel> levels_to_run(const Options& o) {
  std::vector<SimdLevel> out;
  if (o.levels.empty()) {
    for (uint32_t v = 1; v <= 5; ++v)
      if (simd_level_available(SimdLevel(v))) out.push_back(SimdLevel(v));
  } else {
    for (SimdLevel l : o.levels)
      if (simd_level_available(l)) out.push_back(l);
      else std::printf("# %s is not available on this CPU/build: skipped\n", simd_level_name(l));
  }
  return out;
}

std::vector<uint32_t> threads_to_run(const Options& o) {
  return o.threads.empty() ? std::vector<uint32_t>{1, 2} : o.threads;
}

}  // namespace gyro::bench
