// Heat-map rendering on util's Canvas (text by stb_easy_font, PNG by libstb).
#include "radiosity/form_factor_heat_map.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "radiosity/form_factor_storage.h"
#include "radiosity/surface_form_factors.h"
#include "util/canvas.h"

namespace radkit {

namespace {

/// Mean of F over each block×block tile: the downsampled matrix, row-major.
std::vector<double> blockMeans(const FormFactorMatrix& f, int n, int block, int cells) {
  std::vector<double> sum(std::size_t(cells) * cells, 0.0);
  forEachNonZero(
      f, [&](int i, int j, double v) { sum[std::size_t(i / block) * cells + j / block] += v; });
  for (int a = 0; a < cells; ++a)
    for (int b = 0; b < cells; ++b) {
      int rows = std::min(n, (a + 1) * block) - a * block;
      int cols = std::min(n, (b + 1) * block) - b * block;
      sum[std::size_t(a) * cells + b] /= double(rows) * cols;
    }
  return sum;
}

}  // namespace

void writeFormFactorHeatMap(const std::string& path, const PatchMesh& mesh,
                            const std::vector<std::string>& names, const FormFactorMatrix& f,
                            const HeatMapSettings& s) {
  const int n = std::max(1, matrixSize(f));
  const int block = (n + s.matrixPixels - 1) / s.matrixPixels;  // patches per pixel
  const int cells = (n + block - 1) / block;                    // matrix cells per side
  const int cellPx = std::max(1, s.matrixPixels / cells);       // pixels per cell
  const int side = cells * cellPx, fs = s.fontScale, th = Canvas::textHeight(fs);
  std::vector<double> value = blockMeans(f, matrixSize(f), block, cells);

  int nameWidth = 0;
  for (const std::string& name : names)
    nameWidth = std::max(nameWidth, Canvas::textWidth(name, fs));
  const int left = nameWidth + 12, top = nameWidth + 12 + (s.title.empty() ? 0 : th + 12);
  const std::string legend = block > 1 ? "block mean of F" : "F_ij";
  const int barArea = std::max(28 + Canvas::textWidth("1e-10", fs), Canvas::textWidth(legend, fs));
  Canvas canvas(left + side + 30 + barArea + 12, top + side + 16);
  if (!s.title.empty()) canvas.text(8, 8, s.title, fs);

  const LogColourScale scale(value, s.decades);
  for (int a = 0; a < cells; ++a)
    for (int b = 0; b < cells; ++b)
      canvas.fill(left + b * cellPx, top + a * cellPx, left + (b + 1) * cellPx,
                  top + (a + 1) * cellPx, scale.colour(value[std::size_t(a) * cells + b]));

  // Surface boundaries and names: rows on the left, columns on top (vertical text).
  int lastLabel = -2 * th;
  for (std::size_t surf = 0; surf + 1 < mesh.surfaceBegin.size(); ++surf) {
    int p0 = mesh.surfaceBegin[surf] / block * cellPx,
        p1 = mesh.surfaceBegin[surf + 1] / block * cellPx;
    if (surf > 0) {
      canvas.fill(left + p0, top, left + p0 + 1, top + side, {220, 50, 47});
      canvas.fill(left, top + p0, left + side, top + p0 + 1, {220, 50, 47});
    }
    int mid = (p0 + p1) / 2 - th / 2;
    if (surf >= names.size() || p1 <= p0 || mid < lastLabel + th + 2) continue;
    canvas.text(left - 6 - Canvas::textWidth(names[surf], fs), top + mid, names[surf], fs);
    canvas.text(left + mid, top - 6 - Canvas::textWidth(names[surf], fs), names[surf], fs,
                {0, 0, 0}, true);
    lastLabel = mid;
  }

  scale.drawBar(canvas, left + side + 30, top, side, legend, fs);
  writePng(path, canvas);
}

LogColourScale::LogColourScale(const std::vector<double>& values, double decades) {
  double maxValue = 0, minPositive = INFINITY;
  for (double v : values)
    if (v > 0) maxValue = std::max(maxValue, v), minPositive = std::min(minPositive, v);
  hi = maxValue > 0 ? int(std::ceil(std::log10(maxValue) - 1e-12)) : 0;
  lo = maxValue > 0 ? std::max(int(std::floor(std::log10(minPositive))), hi - int(decades)) : -1;
  if (lo >= hi) lo = hi - 1;
}

Rgb8 LogColourScale::colour(double v) const {
  return v > 0 ? viridis((std::log10(v) - lo) / (hi - lo)) : Rgb8{225, 225, 225};
}

void LogColourScale::drawBar(Canvas& canvas, int x, int top, int side, const std::string& legend,
                             int fs) const {
  const int th = Canvas::textHeight(fs);
  for (int y = 0; y < side; ++y)
    canvas.fill(x, top + y, x + 24, top + y + 1, viridis(1.0 - double(y) / std::max(1, side - 1)));
  for (int d = lo; d <= hi; ++d) {
    int y = top + int(std::lround(double(hi - d) / (hi - lo) * (side - 1)));
    canvas.fill(x - 4, y, x, y + 1, {0, 0, 0});
    canvas.text(x + 28, std::clamp(y - th / 2, 0, canvas.height() - th), "1e" + std::to_string(d),
                fs);
  }
  canvas.text(x, top - 2 * th - 6, legend, fs);
}

}  // namespace radkit
