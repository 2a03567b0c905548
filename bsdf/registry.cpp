// The one table of BSDFs (as solvers/registry.cpp): the scene loader, the CLI's help, every
// image mode, photon tracing and the tests read it. A new BSDF is one .cpp that defines its
// create function, one line here and one line in bsdf/CMakeLists.txt.
#include "bsdf/bsdf.h"

namespace radkit {

// Defined in each BSDF's own .cpp: reads the BSDF's keys from params (with defaults) and
// checks their ranges, throwing ParamError.
std::unique_ptr<Bsdf> createLambert(Params& params, const BsdfSettings& settings);
std::unique_ptr<Bsdf> createPhong(Params& params, const BsdfSettings& settings);
std::unique_ptr<Bsdf> createCookTorrance(Params& params, const BsdfSettings& settings);
std::unique_ptr<Bsdf> createMirror(Params& params, const BsdfSettings& settings);
std::unique_ptr<Bsdf> createGlass(Params& params, const BsdfSettings& settings);
std::unique_ptr<Bsdf> createOrenNayar(Params& params, const BsdfSettings& settings);

const Registry<Bsdf, const BsdfSettings&>& bsdfRegistry() {
  static const Registry<Bsdf, const BsdfSettings&> registry(
      "BSDF",
      {
          {"lambert", createLambert, "diffuse; reflectance=[r,g,b] (0.5)",
           "reflectance=0.8 0.5 0.2"},
          {"phong", createPhong,
           "energy-normalised Phong; kd|reflectance (0.5), ks (0), shininess (32); kd + ks < 1",
           "kd=0.3 0.3 0.3, ks=0.6 0.6 0.6, shininess=20"},
          {"cook-torrance", createCookTorrance,
           "GGX microfacets; base_color|reflectance (0.5), metallic (0), roughness (0.5), f0 "
           "(0.04) or ior",
           "base_color=0.7 0.4 0.2, metallic=0.3, roughness=0.6"},
          {"mirror", createMirror, "perfect mirror; specular=[r,g,b] (1)", "specular=0.9 0.8 0.7"},
          {"glass", createGlass, "smooth dielectric; ior (1.5)", "ior=1.5"},
          {"oren-nayar", createOrenNayar,
           "rough diffuse (Oren-Nayar 1994); reflectance (0.5), sigma in degrees (20)",
           "reflectance=0.8 0.6 0.4, sigma=30"},
      });
  return registry;
}

std::unique_ptr<Bsdf> makeBsdf(const std::string& name, Params params,
                               const BsdfSettings& settings) {
  return bsdfRegistry().make(name, std::move(params), settings);
}

}  // namespace radkit
