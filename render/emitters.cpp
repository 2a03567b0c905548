#include "render/emitters.h"

#include <algorithm>
#include <stdexcept>

#include "render/spherical_rectangle.h"
#include "util/sampling.h"

namespace radkit {

EmitterSampler::EmitterSampler(const Scene& scene, const PatchMesh& mesh)
    : m_mesh(mesh),
      m_probability(mesh.size(), 0.0),
      m_emission(mesh.size()),
      m_slot(mesh.size(), -1) {
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
    m_slot[i] = int(m_patches.size());
    m_patches.push_back(i);
    weight.push_back(w);
    Vec3 v[4];
    for (int c = 0; c < p.vertexCount; ++c) v[c] = mesh.vertex(p, c);
    Rectangle r;
    r.valid = patchRectangle(v, p.vertexCount, r.corner, r.ex, r.ey);
    m_rectangle.push_back(r);
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
  const int i = pick(u0);
  const Patch& p = m_mesh.patches[i];
  EmitterSample s;
  s.patch = i;
  if (const Rectangle& r = m_rectangle[m_slot[i]]; r.valid) {
    // corner + u·ex + v·ey is uniform by area and keeps (u1, u2)'s strata whole, where the
    // split into two triangles and the triangle warp cut and stretch them (and cost more).
    s.point = r.corner + r.ex * u1 + r.ey * u2;
  } else {
    Vec3 v[4];
    for (int c = 0; c < p.vertexCount; ++c) v[c] = m_mesh.vertex(p, c);
    s.point = samplePatchUniform(v, p.vertexCount, u1, u2);
  }
  s.normal = p.normal;
  s.emission = m_emission[i];
  s.pdfArea = pdfArea(i);
  return s;
}

int EmitterSampler::pick(double u0) const {
  const auto k = std::size_t(std::upper_bound(m_cdf.begin(), m_cdf.end(), u0) - m_cdf.begin());
  return m_patches[std::min(m_cdf.size() - 1, k)];
}

bool EmitterSampler::rectangle(int patch, Vec3& corner, Vec3& ex, Vec3& ey) const {
  if (m_slot[patch] < 0 || !m_rectangle[m_slot[patch]].valid) return false;
  const Rectangle& r = m_rectangle[m_slot[patch]];
  corner = r.corner, ex = r.ex, ey = r.ey;
  return true;
}

double EmitterSampler::pdfArea(int patch) const {
  return m_probability[patch] / m_mesh.patches[patch].area;
}

}  // namespace radkit
