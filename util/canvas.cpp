#include "util/canvas.h"

#include <stb/stb_easy_font.h>
#include <stb/stb_image.h>
#include <stb/stb_image_write.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "util/output_folder.h"

namespace radkit {

Canvas::Canvas(int width, int height, Rgb8 background)
    : m_width(width), m_height(height), m_pixels(std::size_t(width) * height * 3) {
  if (width <= 0 || height <= 0) throw std::invalid_argument("Canvas: empty size");
  fill(0, 0, width, height, background);
}

Rgb8 Canvas::at(int x, int y) const {
  const std::uint8_t* p = &m_pixels[(std::size_t(y) * m_width + x) * 3];
  return {p[0], p[1], p[2]};
}

void Canvas::set(int x, int y, Rgb8 c) {
  if (x < 0 || y < 0 || x >= m_width || y >= m_height) return;
  std::uint8_t* p = &m_pixels[(std::size_t(y) * m_width + x) * 3];
  p[0] = c.r;
  p[1] = c.g;
  p[2] = c.b;
}

void Canvas::fill(int x0, int y0, int x1, int y1, Rgb8 c) {
  for (int y = std::max(0, y0); y < std::min(m_height, y1); ++y)
    for (int x = std::max(0, x0); x < std::min(m_width, x1); ++x) set(x, y, c);
}

void Canvas::line(double x0, double y0, double x1, double y1, Rgb8 c, int width) {
  int steps = int(std::ceil(std::max(std::fabs(x1 - x0), std::fabs(y1 - y0)))) + 1;
  int lo = -(width - 1) / 2, hi = width / 2;
  for (int k = 0; k <= steps; ++k) {
    double t = double(k) / steps;
    int x = int(std::lround(x0 + (x1 - x0) * t)), y = int(std::lround(y0 + (y1 - y0) * t));
    fill(x + lo, y + lo, x + hi + 1, y + hi + 1, c);
  }
}

namespace {

/// The text as stb_easy_font can draw it: its glyph table covers ' ' to '~' only, and indexes
/// out of bounds with anything else. Each other UTF-8 code point (or stray byte) becomes '?'.
std::vector<char> fontChars(const std::string& s) {
  std::vector<char> out;
  for (std::size_t k = 0; k < s.size();) {
    const unsigned char b = static_cast<unsigned char>(s[k]);
    const int length = b < 0x80           ? 1
                       : (b >> 5) == 0x6  ? 2
                       : (b >> 4) == 0xE  ? 3
                       : (b >> 3) == 0x1E ? 4
                                          : 1;
    int taken = 1;  // a lead byte with missing continuation bytes counts alone
    while (taken < length && k + taken < s.size() &&
           (static_cast<unsigned char>(s[k + taken]) >> 6) == 0x2)
      ++taken;
    out.push_back((b >= 32 && b <= 126) || b == '\n' ? char(b) : '?');
    k += taken;
  }
  out.push_back('\0');
  return out;
}

}  // namespace

void Canvas::text(int x, int y, const std::string& s, int scale, Rgb8 c, bool vertical) {
  std::vector<char> chars = fontChars(s);
  // stb_easy_font emits quads of 4 vertices × 16 bytes; ~270 bytes per character is enough.
  std::vector<char> quads(chars.size() * 300);
  int n = stb_easy_font_print(0, 0, chars.data(), nullptr, quads.data(), int(quads.size()));
  for (int q = 0; q < n; ++q) {
    const float* v0 = reinterpret_cast<const float*>(&quads[std::size_t(q) * 64]);
    const float* v2 = reinterpret_cast<const float*>(&quads[std::size_t(q) * 64 + 32]);
    int ax = int(v0[0]) * scale, ay = int(v0[1]) * scale;
    int bx = int(v2[0]) * scale, by = int(v2[1]) * scale;
    if (vertical)  // (u, v) -> (x + h - v, y + u): reads top to bottom
      fill(x + textHeight(scale) - by, y + ax, x + textHeight(scale) - ay, y + bx, c);
    else
      fill(x + ax, y + ay, x + bx, y + by, c);
  }
}

int Canvas::textWidth(const std::string& s, int scale) {
  std::vector<char> chars = fontChars(s);
  return stb_easy_font_width(chars.data()) * scale;
}

Rgb8 viridis(double t) {
  // Nine evenly spaced samples of matplotlib's viridis; linear in between.
  static constexpr std::uint8_t kViridis[9][3] = {{68, 1, 84},    {71, 44, 122},  {59, 81, 139},
                                                  {44, 113, 142}, {33, 144, 141}, {39, 173, 129},
                                                  {92, 200, 99},  {170, 220, 50}, {253, 231, 37}};
  t = std::clamp(std::isfinite(t) ? t : 0.0, 0.0, 1.0) * 8;
  int k = std::min(7, int(t));
  double w = t - k;
  auto mix = [&](int ch) {
    return static_cast<std::uint8_t>(
        std::lround(kViridis[k][ch] * (1 - w) + kViridis[k + 1][ch] * w));
  };
  return {mix(0), mix(1), mix(2)};
}

void writePng(const std::string& path, const Canvas& c) {
  std::string bytes;
  auto append = [](void* context, void* data, int size) {
    static_cast<std::string*>(context)->append(static_cast<const char*>(data), std::size_t(size));
  };
  if (!stbi_write_png_to_func(append, &bytes, c.width(), c.height(), 3, c.data(), c.width() * 3))
    throw std::runtime_error("cannot encode PNG for " + path);
  writeFileAtomically(path, bytes);
}

Canvas readPng(const std::string& path) {
  int w = 0, h = 0, channels = 0;
  unsigned char* data = stbi_load(path.c_str(), &w, &h, &channels, 3);
  if (!data) throw std::runtime_error("cannot read PNG " + path);
  Canvas c(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      const unsigned char* p = data + (std::size_t(y) * w + x) * 3;
      c.set(x, y, {p[0], p[1], p[2]});
    }
  stbi_image_free(data);
  return c;
}

}  // namespace radkit
