// Canvas: an 8-bit RGB raster with the drawing radkit's images and charts need (rectangles,
// lines, stb_easy_font text), and PNG output through libstb.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace radkit {

struct Rgb8 {
  std::uint8_t r = 0, g = 0, b = 0;
};

class Canvas {
 public:
  Canvas(int width, int height, Rgb8 background = {255, 255, 255});

  int width() const { return m_width; }
  int height() const { return m_height; }
  const std::uint8_t* data() const { return m_pixels.data(); }
  Rgb8 at(int x, int y) const;
  void set(int x, int y, Rgb8 c);

  /// Fills [x0, x1) × [y0, y1), clipped to the canvas.
  void fill(int x0, int y0, int x1, int y1, Rgb8 c);
  /// A line of the given width in pixels (Bresenham steps, square pen).
  void line(double x0, double y0, double x1, double y1, Rgb8 c, int width = 1);
  /// Text with its top-left corner at (x, y), `scale` pixels per font unit; vertical text
  /// runs downwards (rotated 90° clockwise). Any UTF-8 works: characters the font lacks are
  /// drawn as '?'.
  void text(int x, int y, const std::string& s, int scale, Rgb8 c = {0, 0, 0},
            bool vertical = false);
  static int textWidth(const std::string& s, int scale);
  static int textHeight(int scale) { return 7 * scale; }

 private:
  int m_width, m_height;
  std::vector<std::uint8_t> m_pixels;
};

/// Viridis colour map (perceptually uniform), t in [0, 1].
Rgb8 viridis(double t);

/// Encodes the canvas as PNG and writes it atomically (temporary file, then rename).
void writePng(const std::string& path, const Canvas& canvas);

/// Reads a PNG into a canvas (tests and tools); throws on failure.
Canvas readPng(const std::string& path);

}  // namespace radkit
