// EmitterSampler: picks points on emitting patches in proportion to emitted power, the
// light source of photon emission and of next-event estimation.
#pragma once

#include <vector>

#include "geometry/patch_mesh.h"
#include "geometry/scene.h"

namespace radkit {

/// A point on an emitter: where, facing where, what it emits, and the density of choosing it.
struct EmitterSample {
  int patch = -1;
  Vec3 point, normal;
  Vec3 emission;       ///< exitance E of the patch, W/m² per channel
  double pdfArea = 0;  ///< density per unit area (scene units⁻²) over all emitters
};

class EmitterSampler {
 public:
  /// Emitting patches weighted by power A·Y(E) (Rec. 709 luminance of E).
  EmitterSampler(const Scene& scene, const PatchMesh& mesh);

  bool empty() const { return m_patches.empty(); }
  /// How many patches emit: with one, pick() needs no number.
  int count() const { return int(m_patches.size()); }
  /// Total emitted power per channel, Σ A_i E_i (scene units² · W/m²).
  Vec3 totalPower() const { return m_power; }

  /// \brief A point: u0 chooses the patch (power-proportional), (u1, u2) the point on it
  /// (uniform by area: the bilinear map of a rectangle, else samplePatchUniform). Requires
  /// !empty().
  EmitterSample sample(double u0, double u1, double u2) const;
  /// The patch sample() chooses with u0.
  int pick(double u0) const;
  /// Density per unit area of sample() producing a point on `patch`: P(patch) / A_patch.
  double pdfArea(int patch) const;
  /// Chance that sample() picks `patch` (0 if it does not emit).
  double probability(int patch) const { return m_probability[patch]; }
  /// \brief Whether `patch` is a rectangle, and if so its corner and orthogonal edges (for
  /// sampling it by solid angle).
  bool rectangle(int patch, Vec3& corner, Vec3& ex, Vec3& ey) const;

 private:
  const PatchMesh& m_mesh;
  std::vector<int> m_patches;         ///< emitting patch ids
  std::vector<double> m_cdf;          ///< cumulative power fraction, m_cdf.back() == 1
  std::vector<double> m_probability;  ///< per mesh patch: chance of being chosen (0 if dark)
  std::vector<Vec3> m_emission;       ///< per mesh patch
  struct Rectangle {
    bool valid = false;
    Vec3 corner, ex, ey;
  };
  std::vector<Rectangle> m_rectangle;  ///< per emitting patch (index k of m_patches)
  std::vector<int> m_slot;             ///< per mesh patch: its k in m_patches, or −1
  Vec3 m_power;
};

}  // namespace radkit
