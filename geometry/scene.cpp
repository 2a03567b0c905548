#include "geometry/scene.h"

#include "geometry/scene_loader.h"

namespace radkit {

Vec3 Material::diffuseAlbedo() const {
  switch (brdf) {
    case BrdfModel::Lambert:
    case BrdfModel::Phong: return reflectance;
    case BrdfModel::CookTorrance: return reflectance * (1 - metallic);
    default: return {0, 0, 0};
  }
}

const char* brdfName(BrdfModel model) {
  switch (model) {
    case BrdfModel::Lambert: return "lambert";
    case BrdfModel::Phong: return "phong";
    case BrdfModel::CookTorrance: return "cook-torrance";
    case BrdfModel::Mirror: return "mirror";
    default: return "glass";
  }
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

int Scene::findMaterial(const std::string& materialName) const {
  for (std::size_t i = 0; i < materials.size(); ++i)
    if (materials[i].name == materialName) return static_cast<int>(i);
  return -1;
}

}  // namespace radkit
