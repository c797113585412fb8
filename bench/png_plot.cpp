#include "png_plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace gyro::bench {

Image::Image(int width, int height, Rgb bg) : w_(std::max(1, width)), h_(std::max(1, height)) {
  rgb_.resize(std::size_t(w_) * h_ * 3);
  for (std::size_t i = 0; i < rgb_.size(); i += 3) rgb_[i] = bg.r, rgb_[i + 1] = bg.g, rgb_[i + 2] = bg.b;
}

void Image::set(int x, int y, Rgb c) {
  if (x < 0 || y < 0 || x >= w_ || y >= h_) return;
  uint8_t* p = &rgb_[(std::size_t(y) * w_ + x) * 3];
  p[0] = c.r, p[1] = c.g, p[2] = c.b;
}

void Image::fill_rect(int x0, int y0, int x1, int y1, Rgb c) {
  for (int y = std::min(y0, y1); y <= std::max(y0, y1); ++y)
    for (int x = std::min(x0, x1); x <= std::max(x0, x1); ++x) set(x, y, c);
}

// A DDA line, thickness as a square brush.
void Image::line(double x0, double y0, double x1, double y1, Rgb c, int thickness) {
  if (!std::isfinite(x0) || !std::isfinite(y0) || !std::isfinite(x1) || !std::isfinite(y1)) return;
  const double dx = x1 - x0, dy = y1 - y0;
  const int n = int(std::ceil(std::max(std::fabs(dx), std::fabs(dy)))) + 1;
  if (n > 100000) return;
  const int lo = -(thickness - 1) / 2, hi = thickness / 2;
  for (int i = 0; i <= n; ++i) {
    const double t = double(i) / n;
    const int x = int(std::lround(x0 + t * dx)), y = int(std::lround(y0 + t * dy));
    for (int a = lo; a <= hi; ++a)
      for (int b = lo; b <= hi; ++b) set(x + a, y + b, c);
  }
}

void Image::marker(double xf, double yf, Rgb c, int shape, int r) {
  if (!std::isfinite(xf) || !std::isfinite(yf)) return;
  const int x = int(std::lround(xf)), y = int(std::lround(yf));
  switch (shape) {
    case 0:
      for (int b = -r; b <= r; ++b)
        for (int a = -r; a <= r; ++a)
          if (a * a + b * b <= r * r) set(x + a, y + b, c);
      break;
    case 1: fill_rect(x - r, y - r, x + r, y + r, c); break;
    case 2:
      for (int b = -r; b <= r; ++b) {
        const int half = (b + r) / 2;
        for (int a = -half; a <= half; ++a) set(x + a, y + b, c);
      }
      break;
    default:
      line(x - r, y - r, x + r, y + r, c, 2);
      line(x - r, y + r, x + r, y - r, c, 2);
      break;
  }
}

uint32_t crc32(const uint8_t* data, std::size_t n, uint32_t crc) {
  static uint32_t table[256];
  static bool ready = false;
  if (!ready) {
    for (uint32_t i = 0; i < 256; ++i) {
      uint32_t c = i;
      for (int k = 0; k < 8; ++k) c = (c & 1) ? 0xEDB88320u ^ (c >> 1) : c >> 1;
      table[i] = c;
    }
    ready = true;
  }
  crc = ~crc;
  for (std::size_t i = 0; i < n; ++i) crc = table[(crc ^ data[i]) & 0xFF] ^ (crc >> 8);
  return ~crc;
}

uint32_t adler32(const uint8_t* data, std::size_t n, uint32_t adler) {
  uint32_t a = adler & 0xFFFF, b = adler >> 16;
  for (std::size_t i = 0; i < n; ++i) {
    a = (a + data[i]) % 65521u;
    b = (b + a) % 65521u;
  }
  return (b << 16) | a;
}

namespace {
void put32(std::vector<uint8_t>& v, uint32_t x) {
  v.push_back(uint8_t(x >> 24)), v.push_back(uint8_t(x >> 16)), v.push_back(uint8_t(x >> 8)), v.push_back(uint8_t(x));
}
void chunk(std::vector<uint8_t>& out, const char type[4], const std::vector<uint8_t>& data) {
  put32(out, uint32_t(data.size()));
  const std::size_t start = out.size();
  out.insert(out.end(), type, type + 4);
  out.insert(out.end(), data.begin(), data.end());
  put32(out, crc32(&out[start], out.size() - start));
}
}  // namespace

std::vector<uint8_t> Image::png_bytes() const {
  std::vector<uint8_t> out = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  std::vector<uint8_t> ihdr;
  put32(ihdr, uint32_t(w_)), put32(ihdr, uint32_t(h_));
  ihdr.insert(ihdr.end(), {8, 2, 0, 0, 0});  // 8 bits, RGB, deflate, filter 0, no interlace
  chunk(out, "IHDR", ihdr);
  // The raw scanlines, each after filter byte 0 (none).
  std::vector<uint8_t> raw;
  raw.reserve(std::size_t(h_) * (1 + std::size_t(w_) * 3));
  for (int y = 0; y < h_; ++y) {
    raw.push_back(0);
    raw.insert(raw.end(), rgb_.begin() + std::size_t(y) * w_ * 3, rgb_.begin() + std::size_t(y + 1) * w_ * 3);
  }
  // zlib: CMF 0x78 (deflate, 32 KiB window), FLG 0x01 ((0x78 * 256 + 1) % 31 == 0), then
  // stored blocks of at most 65,535 bytes (BFINAL on the last), then Adler-32, big-endian.
  std::vector<uint8_t> z = {0x78, 0x01};
  std::size_t pos = 0;
  do {
    const std::size_t len = std::min<std::size_t>(65535, raw.size() - pos);
    const bool last = pos + len == raw.size();
    z.push_back(last ? 1 : 0);
    z.push_back(uint8_t(len)), z.push_back(uint8_t(len >> 8));
    z.push_back(uint8_t(~len)), z.push_back(uint8_t(~len >> 8));
    z.insert(z.end(), raw.begin() + pos, raw.begin() + pos + len);
    pos += len;
  } while (pos < raw.size());
  put32(z, adler32(raw.data(), raw.size()));
  chunk(out, "IDAT", z);
  chunk(out, "IEND", {});
  return out;
}

bool Image::write_png(const std::string& path) const {
  const std::vector<uint8_t> bytes = png_bytes();
  std::FILE* f = std::fopen(path.c_str(), "wb");
  if (!f) return false;
  const bool ok = std::fwrite(bytes.data(), 1, bytes.size(), f) == bytes.size();
  return std::fclose(f) == 0 && ok;
}

namespace {

// A 3 x 5 pixel font for tick labels: digits, 'e', '-', '.'; rows top to bottom, 3 bits each.
const uint16_t* glyph(char c) {
  static const uint16_t digits[10][5] = {{7, 5, 5, 5, 7}, {2, 6, 2, 2, 7}, {7, 1, 7, 4, 7}, {7, 1, 7, 1, 7},
                                         {5, 5, 7, 1, 1}, {7, 4, 7, 1, 7}, {7, 4, 7, 5, 7}, {7, 1, 1, 1, 1},
                                         {7, 5, 7, 5, 7}, {7, 5, 7, 1, 7}};
  static const uint16_t e[5] = {0, 7, 7, 4, 7}, minus[5] = {0, 0, 7, 0, 0}, dot[5] = {0, 0, 0, 0, 2};
  if (c >= '0' && c <= '9') return digits[c - '0'];
  if (c == 'e') return e;
  if (c == '-') return minus;
  if (c == '.') return dot;
  return nullptr;
}

// Draws text with its top-left corner at (x, y), each font pixel a scale x scale square.
void text(Image& img, int x, int y, const char* s, int scale, Rgb c) {
  for (; *s; ++s, x += 4 * scale) {
    const uint16_t* g = glyph(*s);
    if (!g) continue;
    for (int r = 0; r < 5; ++r)
      for (int k = 0; k < 3; ++k)
        if (g[r] & (4 >> k)) img.fill_rect(x + k * scale, y + r * scale, x + k * scale + scale - 1, y + r * scale + scale - 1, c);
  }
}

struct Axis {
  bool log = true;
  double lo = 0, hi = 1;  // in axis units (log10 of the value on a log axis)
  double map(double v) const { return log ? std::log10(v) : v; }
  bool usable(double v) const { return std::isfinite(v) && (!log || v > 0); }
};

Axis make_axis(bool log, const std::vector<PlotSeries>& series, bool x) {
  Axis a;
  a.log = log;
  double lo = INFINITY, hi = -INFINITY;
  for (const PlotSeries& s : series)
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      const double vx = s.x[i], vy = s.y[i];
      if (!a.usable(vx) || !(log ? std::isfinite(vy) : true) || !std::isfinite(vy)) continue;
      const double v = x ? vx : vy;
      if (!a.usable(v)) continue;
      lo = std::min(lo, a.map(v)), hi = std::max(hi, a.map(v));
    }
  if (!(lo <= hi)) lo = 0, hi = 1;
  if (log) {
    lo = std::floor(lo), hi = std::ceil(hi);
    if (hi <= lo) hi = lo + 1;
  } else {
    const double pad = hi > lo ? 0.05 * (hi - lo) : 0.5;
    lo -= pad, hi += pad;
  }
  a.lo = lo, a.hi = hi;
  return a;
}

}  // namespace

bool plot_png(const PlotSpec& spec, const std::string& path) {
  Image img(spec.width, spec.height);
  const int left = 80, right = spec.width - 20, top = 20, bottom = spec.height - 50;
  const Axis ax = make_axis(spec.log_x, spec.series, true), ay = make_axis(spec.log_y, spec.series, false);
  auto px = [&](double v) { return left + (ax.map(v) - ax.lo) / (ax.hi - ax.lo) * (right - left); };
  auto py = [&](double v) { return bottom - (ay.map(v) - ay.lo) / (ay.hi - ay.lo) * (bottom - top); };
  const Rgb black{0, 0, 0}, grid{225, 225, 225};
  // Grid lines and ticks: decades (long) and 2..9 (short) on log axes, tenths on linear ones.
  auto ticks = [&](const Axis& a, auto&& draw) {
    if (a.log) {
      for (double d = a.lo; d <= a.hi + 1e-9; d += 1.0) {
        draw(d, true);
        if (d < a.hi - 1e-9)
          for (int k = 2; k <= 9; ++k) draw(d + std::log10(double(k)), false);
      }
    } else {
      for (int k = 0; k <= 10; ++k) draw(a.lo + (a.hi - a.lo) * k / 10.0, k % 5 == 0);
    }
  };
  ticks(ax, [&](double u, bool major) {
    const double x = left + (u - ax.lo) / (ax.hi - ax.lo) * (right - left);
    if (major) img.line(x, top, x, bottom, grid);
    img.line(x, bottom, x, bottom + (major ? 10 : 5), black);
    if (major && ax.log) {
      char buf[16];
      std::snprintf(buf, sizeof buf, "1e%d", int(std::lround(u)));
      text(img, int(x) - 12, bottom + 16, buf, 2, black);
    }
  });
  ticks(ay, [&](double u, bool major) {
    const double y = bottom - (u - ay.lo) / (ay.hi - ay.lo) * (bottom - top);
    if (major) img.line(left, y, right, y, grid);
    img.line(left - (major ? 10 : 5), y, left, y, black);
    if (major && ay.log) {
      char buf[16];
      std::snprintf(buf, sizeof buf, "1e%d", int(std::lround(u)));
      text(img, 4, int(y) - 5, buf, 2, black);
    }
  });
  img.line(left, top, left, bottom, black, 2);
  img.line(left, bottom, right, bottom, black, 2);
  for (const PlotSeries& s : spec.series) {
    bool have_prev = false;
    double qx = 0, qy = 0;
    for (std::size_t i = 0; i < s.x.size() && i < s.y.size(); ++i) {
      if (!ax.usable(s.x[i]) || !ay.usable(s.y[i])) {
        have_prev = false;
        continue;
      }
      const double x = px(s.x[i]), y = py(s.y[i]);
      if (s.polyline && have_prev) img.line(qx, qy, x, y, s.color, 2);
      if (s.marker >= 0) img.marker(x, y, s.color, s.marker);
      have_prev = true, qx = x, qy = y;
    }
  }
  return img.write_png(path);
}

}  // namespace gyro::bench
