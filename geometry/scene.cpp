#include "geometry/scene.h"

#include <algorithm>

#include "bsdf/bsdf.h"
#include "geometry/scene_loader.h"

namespace radkit {

void resolveMaterial(Material& m) {
  const std::unique_ptr<Bsdf> bsdf = makeBsdf(m.bsdf, m.params);
  m.albedo = bsdf->diffuseAlbedo();
  m.delta = bsdf->isDelta();
  m.description = bsdf->describe();
}

Material makeMaterial(const std::string& name, const std::string& bsdf, const std::string& params,
                      const Vec3& emission) {
  Material m;
  m.name = name;
  m.bsdf = bsdf;
  m.params = Params::parse(params);
  m.emission = emission;
  resolveMaterial(m);
  return m;
}

Bounds3 Scene::bounds() const {
  Bounds3 b;
  for (const Surface& s : surfaces)
    for (const Vec3& v : s.vertices) b.extend(v);
  return b;
}

double Scene::metresPerUnit() const {
  for (const auto& [name, metres] : knownUnits())
    if (units == name) return metres;
  return 1.0;
}

std::vector<bool> Scene::twoSidedSurfaces() const {
  std::vector<bool> out;
  for (const Surface& s : surfaces) out.push_back(materials[s.material].twoSided);
  return out;
}

int Scene::findMaterial(const std::string& materialName) const {
  for (std::size_t i = 0; i < materials.size(); ++i)
    if (materials[i].name == materialName) return static_cast<int>(i);
  return -1;
}

int addBackSides(Scene& scene) {
  const std::size_t count = scene.surfaces.size();
  for (std::size_t k = 0; k < count; ++k) {
    if (!scene.materials[scene.surfaces[k].material].twoSided) continue;
    Surface back = scene.surfaces[k];
    back.name += " (back)";
    back.source += " (back side)";
    for (Face& f : back.faces) std::reverse(f.vertices.begin(), f.vertices.end());
    back.cullBack = scene.surfaces[k].cullBack = true;
    scene.surfaces.push_back(std::move(back));
  }
  return static_cast<int>(scene.surfaces.size() - count);
}

}  // namespace radkit
