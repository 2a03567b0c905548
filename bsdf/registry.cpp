// The one table of BSDFs (as solvers/registry.cpp): the scene loader, the CLI's help, every
// image mode, photon tracing and the tests read it. A new BSDF is one .cpp that defines its
// create function, one line here and one line in bsdf/CMakeLists.txt.
#include <stdexcept>

#include "bsdf/bsdf.h"

namespace radkit {

// Defined in each BSDF's own .cpp: reads the BSDF's keys from params (with defaults) and
// checks their ranges, throwing BsdfParamError.
std::unique_ptr<Bsdf> createLambert(BsdfParams& params, const BsdfSettings& settings);
std::unique_ptr<Bsdf> createPhong(BsdfParams& params, const BsdfSettings& settings);
std::unique_ptr<Bsdf> createCookTorrance(BsdfParams& params, const BsdfSettings& settings);
std::unique_ptr<Bsdf> createMirror(BsdfParams& params, const BsdfSettings& settings);
std::unique_ptr<Bsdf> createGlass(BsdfParams& params, const BsdfSettings& settings);
std::unique_ptr<Bsdf> createOrenNayar(BsdfParams& params, const BsdfSettings& settings);

namespace {

struct BsdfEntry {
  const char* name;
  std::unique_ptr<Bsdf> (*create)(BsdfParams&, const BsdfSettings&);
  const char* help;
  const char* example;  ///< parameters of the registry-driven tests (χ², reciprocity, energy)
};

constexpr BsdfEntry kBsdfs[] = {
    {"lambert", createLambert, "diffuse; reflectance=[r,g,b] (0.5)", "reflectance=0.8 0.5 0.2"},
    {"phong", createPhong,
     "energy-normalised Phong; kd|reflectance (0.5), ks (0), shininess (32); kd + ks < 1",
     "kd=0.3 0.3 0.3, ks=0.6 0.6 0.6, shininess=20"},
    {"cook-torrance", createCookTorrance,
     "GGX microfacets; base_color|reflectance (0.5), metallic (0), roughness (0.5), f0 (0.04) or "
     "ior",
     "base_color=0.7 0.4 0.2, metallic=0.3, roughness=0.6"},
    {"mirror", createMirror, "perfect mirror; specular=[r,g,b] (1)", "specular=0.9 0.8 0.7"},
    {"glass", createGlass, "smooth dielectric; ior (1.5)", "ior=1.5"},
    {"oren-nayar", createOrenNayar,
     "rough diffuse (Oren-Nayar 1994); reflectance (0.5), sigma in degrees (20)",
     "reflectance=0.8 0.6 0.4, sigma=30"},
};

}  // namespace

std::unique_ptr<Bsdf> makeBsdf(const std::string& name, BsdfParams params,
                               const BsdfSettings& settings) {
  for (const BsdfEntry& entry : kBsdfs)
    if (name == entry.name) {
      std::unique_ptr<Bsdf> bsdf = entry.create(params, settings);
      params.rejectUnused(name);
      return bsdf;
    }
  std::string known;
  for (const BsdfEntry& entry : kBsdfs)
    known += (known.empty() ? "" : ", ") + std::string(entry.name);
  throw BsdfParamError("has unknown \"brdf\" \"" + name + "\". Fix: use one of " + known);
}

std::vector<BsdfInfo> bsdfTable() {
  std::vector<BsdfInfo> table;
  for (const BsdfEntry& entry : kBsdfs) table.push_back({entry.name, entry.help, entry.example});
  return table;
}

}  // namespace radkit
