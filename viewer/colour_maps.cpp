#include "viewer/colour_maps.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>

#include "util/canvas.h"

namespace radkit::viewer {

namespace {

/// Inferno (matplotlib) at t = 0, 1/8, ..., 1; linear in between is within a few levels.
std::array<double, 3> inferno(double t) {
  static constexpr unsigned char kStops[9][3] = {{0, 0, 4},      {31, 12, 72},   {85, 15, 109},
                                                 {136, 34, 106}, {186, 54, 85},  {227, 89, 51},
                                                 {249, 140, 10}, {249, 201, 50}, {252, 255, 164}};
  t = std::clamp(t, 0.0, 1.0) * 8;
  const int k = std::min(7, int(t));
  const double f = t - k;
  std::array<double, 3> c{};
  for (int i = 0; i < 3; ++i) c[i] = ((1 - f) * kStops[k][i] + f * kStops[k + 1][i]) / 255.0;
  return c;
}

}  // namespace

void fillLookupTable(vtkLookupTable* lut, ColourMap map, double lo, double hi, bool logScale,
                     const double belowRgb[3], const double aboveRgb[3]) {
  constexpr int kColours = 256;
  lut->SetNumberOfTableValues(kColours);
  for (int k = 0; k < kColours; ++k) {
    const double t = double(k) / (kColours - 1);
    if (map == ColourMap::Inferno) {
      auto c = inferno(t);
      lut->SetTableValue(k, c[0], c[1], c[2], 1.0);
    } else {
      Rgb8 c = viridis(t);
      lut->SetTableValue(k, c.r / 255.0, c.g / 255.0, c.b / 255.0, 1.0);
    }
  }
  if (logScale)
    lut->SetScaleToLog10();
  else
    lut->SetScaleToLinear();
  lut->SetTableRange(lo, hi);
  lut->SetBelowRangeColor(belowRgb[0], belowRgb[1], belowRgb[2], 1.0);
  lut->SetAboveRangeColor(aboveRgb[0], aboveRgb[1], aboveRgb[2], 1.0);
  lut->SetNanColor(belowRgb[0], belowRgb[1], belowRgb[2], 1.0);
  lut->UseBelowRangeColorOn();
  lut->UseAboveRangeColorOn();
  lut->Modified();
}

void styleText(vtkTextProperty* text, int pixels, bool panel) {
  text->SetFontSize(pixels);
  text->SetColor(0.95, 0.95, 0.95);
  text->SetFontFamilyToArial();
  text->SetLineSpacing(1.15);
  if (panel) {
    text->SetBackgroundColor(0.05, 0.05, 0.07);
    text->SetBackgroundOpacity(0.72);
    text->SetFrame(false);
  }
}

void styleScalarBar(vtkScalarBarActor* bar, int pixels) {
  for (vtkTextProperty* t : {bar->GetTitleTextProperty(), bar->GetLabelTextProperty(),
                             bar->GetAnnotationTextProperty()}) {
    styleText(t, pixels, false);
    t->ShadowOff();
    t->ItalicOff();
    t->BoldOff();
  }
  bar->SetUnconstrainedFontSize(true);
}

}  // namespace radkit::viewer
