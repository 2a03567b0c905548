// Colour maps and text styling shared by the viewer's VTK views.
#pragma once

#include <vtkLookupTable.h>
#include <vtkScalarBarActor.h>
#include <vtkTextProperty.h>

#include <string>

#include "util/format.h"

namespace radkit::viewer {

/// Perceptually uniform maps: inferno (dark to bright, for radiosity) and viridis (for F).
enum class ColourMap { Inferno, Viridis };

/// \brief Fills `lut` with 256 colours of `map` over [lo, hi], log10-scaled when `logScale`;
/// values below the range and NaN show `belowRgb`, values above it `aboveRgb`.
void fillLookupTable(vtkLookupTable* lut, ColourMap map, double lo, double hi, bool logScale,
                     const double belowRgb[3], const double aboveRgb[3]);

/// \brief Light text on a translucent dark panel, `pixels` high, readable on any scene.
void styleText(vtkTextProperty* text, int pixels, bool panel = true);

/// \brief The scalar bar's title, labels and annotations in the viewer's plain text style.
void styleScalarBar(vtkScalarBarActor* bar, int pixels);

/// "%.4g" of a value, and "(r, g, b)" of a triple.
/// Numbers on colour bars and titles: four significant digits.
inline std::string formatShort(double v) { return formatNumber(v, 4); }

}  // namespace radkit::viewer
