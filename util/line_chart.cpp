#include "util/line_chart.h"

#include <plplot/plplot.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <stdexcept>

namespace radkit {

namespace {

// Colour-blind-safe palette (Okabe & Ito 2008), indices 2.. of PLplot's colour map 0.
constexpr int kPalette[][3] = {{0, 114, 178}, {213, 94, 0},   {0, 158, 115}, {204, 121, 167},
                               {230, 159, 0}, {86, 180, 233}, {0, 0, 0},     {240, 228, 66}};
constexpr int kPaletteSize = sizeof kPalette / sizeof kPalette[0];

struct Range {
  double lo = INFINITY, hi = -INFINITY;
  void add(double v) { lo = std::min(lo, v), hi = std::max(hi, v); }
  void pad(bool log) {
    if (!(lo <= hi)) lo = 0, hi = 1;
    if (hi - lo < 1e-12 * std::max(1.0, std::fabs(hi))) lo -= 0.5, hi += 0.5;
    if (log) lo = std::floor(lo), hi = std::ceil(hi);  // whole decades
  }
};

/// Marker glyphs (UTF-8, drawn by the cairo driver's fonts), one per series.
const char* const kMarkers[] = {"●", "■", "▲", "◆", "▼", "✚", "✖", "★"};
constexpr int kMarkerCount = sizeof kMarkers / sizeof kMarkers[0];

/// Data in axis space: log10 for logarithmic axes, dropping what cannot be shown.
void axisData(const ChartSeries& s, const ChartPanel& p, std::vector<PLFLT>& x,
              std::vector<PLFLT>& y) {
  for (std::size_t k = 0; k < std::min(s.x.size(), s.y.size()); ++k) {
    double a = s.x[k], b = s.y[k];
    if ((p.logX && !(a > 0)) || (p.logY && !(b > 0)) || !std::isfinite(a) || !std::isfinite(b))
      continue;
    x.push_back(p.logX ? std::log10(a) : a);
    y.push_back(p.logY ? std::log10(b) : b);
  }
}

/// Label of a tick on a log10 axis: the power of ten it stands for.
void labelAxis(PLINT axis, PLFLT value, char* label, PLINT length, PLPointer data) {
  const auto* p = static_cast<const ChartPanel*>(data);
  bool log = (axis == PL_X_AXIS && p->logX) || (axis == PL_Y_AXIS && p->logY);
  if (log)
    std::snprintf(label, std::size_t(length), "1e%d", int(std::lround(value)));
  else
    std::snprintf(label, std::size_t(length), "%g", value);
}

void drawPanel(const ChartPanel& given) {
  ChartPanel p = given;
  std::vector<double> allX, allY;
  for (const ChartSeries& s : p.series) {
    allX.insert(allX.end(), s.x.begin(), s.x.end());
    allY.insert(allY.end(), s.y.begin(), s.y.end());
  }
  p.logX = p.logX || needsLogAxis(allX);
  p.logY = p.logY || needsLogAxis(allY);
  pladv(0);
  // The right quarter holds the legend, outside the curves.
  plvpor(0.15, p.series.empty() ? 0.95 : 0.70, 0.14, 0.9);
  Range rx, ry;
  std::vector<std::vector<PLFLT>> xs(p.series.size()), ys(p.series.size());
  for (std::size_t i = 0; i < p.series.size(); ++i) {
    axisData(p.series[i], p, xs[i], ys[i]);
    for (PLFLT v : xs[i]) rx.add(v);
    for (PLFLT v : ys[i]) ry.add(v);
  }
  rx.pad(p.logX);
  ry.pad(p.logY);
  plcol0(1);
  plwind(rx.lo, rx.hi, ry.lo, ry.hi);
  plschr(0, 0.85);
  // Logarithmic axes are drawn in log10 units with "1e-6" labels at every k-th decade
  // (PLplot's own log option labels every decade, which crowds long ranges).
  auto decadeStep = [](const Range& r) { return std::max(1.0, std::ceil((r.hi - r.lo) / 8)); };
  plslabelfunc(labelAxis, const_cast<ChartPanel*>(&p));
  plbox(p.logX ? "bcnstog" : "bcnstg", p.logX ? decadeStep(rx) : 0, p.logX ? 1 : 0,
        p.logY ? "bcnstvog" : "bcnstvg", p.logY ? decadeStep(ry) : 0, p.logY ? 1 : 0);
  plslabelfunc(nullptr, nullptr);
  pllab(p.xLabel.c_str(), p.yLabel.c_str(), p.title.c_str());
  std::vector<const char*> names, symbols;
  std::vector<PLINT> colours, opts;
  std::vector<PLFLT> widths;
  for (std::size_t i = 0; i < p.series.size(); ++i) {
    int colour = 2 + int(i % kPaletteSize);
    const char* marker = kMarkers[i % kMarkerCount];
    plcol0(colour);
    plwidth(2.0);
    if (xs[i].size() > 1) plline(PLINT(xs[i].size()), xs[i].data(), ys[i].data());
    // Evenly spaced markers, shifted per series so coinciding curves still show each one.
    const std::size_t n = xs[i].size();
    std::vector<PLFLT> mx, my;
    const std::size_t step =
        std::max<std::size_t>(1, (n + kMarkersPerSeries - 1) / kMarkersPerSeries);
    for (std::size_t k = (i * step / 3) % step; k < n; k += step)
      mx.push_back(xs[i][k]), my.push_back(ys[i][k]);
    if (n > 0 && (n - 1) % step != (i * step / 3) % step)
      mx.push_back(xs[i][n - 1]), my.push_back(ys[i][n - 1]);
    plschr(0, 0.7);
    if (!mx.empty()) plstring(PLINT(mx.size()), mx.data(), my.data(), marker);
    plschr(0, 0.85);
    names.push_back(p.series[i].name.c_str());
    symbols.push_back(marker);
    colours.push_back(colour);
    opts.push_back(PL_LEGEND_LINE | PL_LEGEND_SYMBOL);
    widths.push_back(2.0);
  }
  plwidth(1.0);
  if (p.series.empty()) {
    plcol0(1);
    plptex(0.5 * (rx.lo + rx.hi), 0.5 * (ry.lo + ry.hi), 1, 0, 0.5, "no data");
  } else {
    PLFLT legendW = 0, legendH = 0;
    std::vector<PLINT> zeros(names.size(), 0), styles(names.size(), 1);
    std::vector<PLFLT> scales(names.size(), 1.0), zeroWidths(names.size(), 0.0),
        symbolScales(names.size(), 0.7);
    std::vector<PLINT> ones(names.size(), 1);
    pllegend(&legendW, &legendH, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX,
             PL_POSITION_RIGHT | PL_POSITION_OUTSIDE, 0.02, 0.0, 0.06, 0, 1, 1, 0, 0,
             PLINT(names.size()), opts.data(), 1.0, 0.8, 2.0, 0, colours.data(), names.data(),
             zeros.data(), zeros.data(), scales.data(), zeroWidths.data(), colours.data(),
             styles.data(), widths.data(), colours.data(), symbolScales.data(), ones.data(),
             symbols.data());
  }
}

}  // namespace

bool needsLogAxis(const std::vector<double>& values) {
  double lo = INFINITY, hi = 0;
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    if (v <= 0) return false;
    lo = std::min(lo, v), hi = std::max(hi, v);
  }
  return hi > 0 && hi > kAutoLogSpan * lo;
}

std::size_t chartPoints(const std::vector<ChartPanel>& panels) {
  std::size_t n = 0;
  for (const ChartPanel& p : panels)
    for (const ChartSeries& s : p.series) n += std::min(s.x.size(), s.y.size());
  return n;
}

void writeLineChartPng(const std::string& path, const std::vector<ChartPanel>& panels, int width,
                       int height) {
  if (panels.empty()) throw std::invalid_argument("writeLineChartPng: no panels");
  // PLplot's driver finds the file by name: draw into a temporary and rename when complete.
  std::string tmp = path + ".tmp.png";
  PLINT stream = 0;
  plmkstrm(&stream);  // a fresh stream: nothing shared with other charts
  plsdev("pngcairo");
  plsfnam(tmp.c_str());
  plspage(0, 0, width, height, 0, 0);
  plscolbg(255, 255, 255);
  plscol0(1, 40, 40, 40);
  for (int i = 0; i < kPaletteSize; ++i)
    plscol0(2 + i, kPalette[i][0], kPalette[i][1], kPalette[i][2]);
  plssub(PLINT(panels.size()), 1);
  plinit();
  for (const ChartPanel& p : panels) drawPanel(p);
  plend1();
  std::error_code ec;
  std::filesystem::rename(tmp, path, ec);
  if (ec) throw std::runtime_error("cannot write chart " + path + ": " + ec.message());
}

}  // namespace radkit
