#include "render/emitters.h"

#include <algorithm>
#include <stdexcept>

#include "geometry/sampling.h"

namespace radkit {

EmitterSampler::EmitterSampler(const Scene& scene, const PatchMesh& mesh)
    : m_mesh(mesh), m_probability(mesh.size(), 0.0), m_emission(mesh.size()) {
  double total = 0;
  std::vector<double> weight;
  for (int i = 0; i < mesh.size(); ++i) {
    const Patch& p = mesh.patches[i];
    const Material& m = scene.materials[scene.surfaces[p.surface].material];
    m_emission[i] = m.emission;
    // Weight by luminous power; an emitter with zero luminance (pure blue, say) still gets
    // its share through the channel maximum so no emitted light is unreachable.
    double w = p.area * std::max(luminance(m.emission), 1e-3 * maxComponent(m.emission));
    if (!(w > 0)) continue;
    m_patches.push_back(i);
    weight.push_back(w);
    total += w;
    m_power += m.emission * p.area;
  }
  double running = 0;
  for (std::size_t k = 0; k < weight.size(); ++k) {
    running += weight[k];
    m_cdf.push_back(running / total);
    m_probability[m_patches[k]] = weight[k] / total;
  }
  if (!m_cdf.empty()) m_cdf.back() = 1;
}

EmitterSample EmitterSampler::sample(double u0, double u1, double u2) const {
  if (empty()) throw std::logic_error("EmitterSampler::sample: the scene has no emitters");
  std::size_t k = std::min(m_cdf.size() - 1, std::size_t(std::upper_bound(m_cdf.begin(), m_cdf.end(), u0) - m_cdf.begin()));
  const int i = m_patches[k];
  const Patch& p = m_mesh.patches[i];
  Vec3 v[4];
  for (int c = 0; c < p.vertexCount; ++c) v[c] = m_mesh.vertex(p, c);
  EmitterSample s;
  s.patch = i;
  s.point = samplePatchUniform(v, p.vertexCount, u1, u2);
  s.normal = p.normal;
  s.emission = m_emission[i];
  s.pdfArea = pdfArea(i);
  return s;
}

double EmitterSampler::pdfArea(int patch) const {
  return m_probability[patch] / m_mesh.patches[patch].area;
}

}  // namespace radkit
