// links.png: how the hierarchy approximates F. Leaves are put in tree order, so every node
// stands for a contiguous range of rows and columns; each link r ← s is drawn as the block
// (rows of r) × (columns of s), coloured by the mean leaf-to-leaf form factor it stands for or by
// the power it carries. Links partition the leaf pairs that exchange light, so blocks never
// overlap; where many small blocks share a pixel, the pixel shows the largest.
#pragma once

#include <string>

#include "hierarchy/gather.h"

namespace radkit {

enum class LinkColour { FormFactor, Power };

struct LinkMatrixSettings {
  int pixels = 800;  ///< side of the matrix area
  double decades = 6;
  LinkColour colour = LinkColour::FormFactor;
  std::string title;
};

/// Node-to-node form factor F_rs a link stands for (with its visibility): the irradiance at r
/// per unit radiosity of s.
double linkFormFactor(const Hierarchy& h, const HLink& link);

/// \brief Writes the block matrix as PNG. `state` gives the sources' radiosity (for Power).
void writeLinkMatrix(const std::string& path, const Hierarchy& h, const std::vector<HLink>& links,
                     const SourceState& state, const LinkMatrixSettings& settings);

}  // namespace radkit
