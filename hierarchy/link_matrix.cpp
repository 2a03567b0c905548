#include "hierarchy/link_matrix.h"

#include <algorithm>
#include <cmath>

#include "radiosity/form_factor_heat_map.h"
#include "util/canvas.h"

namespace radkit {

double linkFormFactor(const Hierarchy& h, const HLink& l) {
  const HNode& R = h[l.receiver];
  if (R.element && h[l.source].element) return l.formFactor * l.visibility;
  // The gather's transfer with B_s = 1: I_s = P_s(−ω)/π, spread over r's projected area.
  const ClusterTransfer t = clusterTransfer(h, l.receiver, l.source);
  return projectedArea(h, l.source, -t.w) / M_PI * l.visibility / t.denominator *
         projectedArea(h, l.receiver, t.w) / R.area;
}

void writeLinkMatrix(const std::string& path, const Hierarchy& h, const std::vector<HLink>& links,
                     const SourceState& state, const LinkMatrixSettings& s) {
  std::vector<std::pair<int, int>> range;
  const int n = std::max<int>(1, static_cast<int>(h.leavesInTreeOrder(&range).size()));
  const int side = std::min(s.pixels, std::max(n, 64));
  const double perPixel = double(side) / n;
  // Largest value per pixel; a block covers at least one pixel each way.
  std::vector<double> value(std::size_t(side) * side, 0.0);
  for (const HLink& l : links) {
    double v = linkFormFactor(h, l);
    if (s.colour == LinkColour::Power) {
      v *= h[l.receiver].area * maxComponent(state.radiosity[l.source]);
    } else {
      // Mean leaf-to-leaf F_ij of the block: F_rs spread over the source's leaves.
      v /= std::max(1, range[l.source].second - range[l.source].first);
    }
    auto [r0, r1] = range[l.receiver];
    auto [c0, c1] = range[l.source];
    int y0 = int(r0 * perPixel), y1 = std::max(y0 + 1, int(std::ceil(r1 * perPixel)));
    int x0 = int(c0 * perPixel), x1 = std::max(x0 + 1, int(std::ceil(c1 * perPixel)));
    for (int y = y0; y < std::min(y1, side); ++y)
      for (int x = x0; x < std::min(x1, side); ++x) {
        double& p = value[std::size_t(y) * side + x];
        p = std::max(p, v);
      }
  }
  const int fs = 2, th = Canvas::textHeight(fs), left = 12,
            top = 12 + (s.title.empty() ? 0 : 2 * th + 12) + 2 * th;
  const std::string legend =
      s.colour == LinkColour::Power ? "power a link carries" : "mean F_ij of a block";
  LogColourScale scale(value, s.decades);
  Canvas canvas(left + side + 30 +
                    std::max(28 + Canvas::textWidth("1e-10", fs), Canvas::textWidth(legend, fs)) +
                    12,
                top + side + 16);
  if (!s.title.empty()) canvas.text(8, 8, s.title, fs);
  for (int y = 0; y < side; ++y)
    for (int x = 0; x < side; ++x)
      canvas.set(left + x, top + y, scale.colour(value[std::size_t(y) * side + x]));
  scale.drawBar(canvas, left + side + 30, top, side, legend, fs);
  writePng(path, canvas);
}

}  // namespace radkit
