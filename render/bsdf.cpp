// The BSDF factory: one table from Material::brdf to the model's constructor.
#include "render/bsdf.h"

namespace radkit {

std::unique_ptr<Bsdf> makeBsdf(const Material& m, const BsdfSettings& settings) {
  switch (m.brdf) {
    case BrdfModel::Lambert: return makeLambertBsdf(m.reflectance);
    case BrdfModel::Phong: return makePhongBsdf(m.reflectance, m.specular, m.shininess);
    case BrdfModel::CookTorrance:
      return makeCookTorranceBsdf(m.reflectance, m.metallic, m.roughness, m.f0, settings);
    case BrdfModel::Mirror: return makeMirrorBsdf(m.specular);
    case BrdfModel::Glass: return makeGlassBsdf(m.ior);
  }
  return makeLambertBsdf(m.reflectance);
}

}  // namespace radkit
