// A tiny PNG writer and plotter for the benchmarks' figures, with no library: the image is
// stored uncompressed (zlib "stored" deflate blocks, CRC32 per chunk, Adler-32 over the
// data), 8-bit RGB. The plotter draws axes with tick marks (decades on log axes), points
// and polylines; the only text is decade labels ("1e-3") on log axes: the caller names the
// axes and series in a comment line.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace gyro::bench {

struct Rgb {
  uint8_t r = 0, g = 0, b = 0;
};

class Image {
 public:
  Image(int width, int height, Rgb background = {255, 255, 255});
  int width() const { return w_; }
  int height() const { return h_; }
  void set(int x, int y, Rgb c);  // outside the image: ignored
  void line(double x0, double y0, double x1, double y1, Rgb c, int thickness = 1);
  void fill_rect(int x0, int y0, int x1, int y1, Rgb c);
  void marker(double x, double y, Rgb c, int shape, int radius = 4);  // shape 0 disc, 1 square, 2 triangle, 3 cross
  /// Writes the image as a PNG file; false (and errno) if the file cannot be written.
  bool write_png(const std::string& path) const;
  /// The PNG file's bytes.
  std::vector<uint8_t> png_bytes() const;

 private:
  int w_, h_;
  std::vector<uint8_t> rgb_;
};

uint32_t crc32(const uint8_t* data, std::size_t n, uint32_t crc = 0);
uint32_t adler32(const uint8_t* data, std::size_t n, uint32_t adler = 1);

struct PlotSeries {
  std::vector<double> x, y;  // points with a non-finite or (log axis) non-positive value are left out
  Rgb color;
  int marker = 0;            // Image::marker shape; -1: none
  bool polyline = true;      // join the points in order
};

struct PlotSpec {
  int width = 800, height = 600;
  bool log_x = true, log_y = true;
  std::vector<PlotSeries> series;
};

/// Draws the series into a frame with ticks (log axes: a long tick per decade, short ticks
/// at 2..9) and writes the PNG. The ranges cover every point (log axes: whole decades).
bool plot_png(const PlotSpec& spec, const std::string& path);

}  // namespace gyro::bench
