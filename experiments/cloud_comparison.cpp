#include "experiments/cloud_comparison.h"

#include <algorithm>
#include <cmath>
#include <memory>

#include "atmosphere/atmosphere.h"
#include "daylight/sky.h"

namespace radkit {

namespace {

double relativeBias(const std::vector<Vec3>& a, const std::vector<Vec3>& reference) {
  double sa = 0, sr = 0;
  for (std::size_t i = 0; i < a.size(); ++i)
    sa += a[i].x + a[i].y + a[i].z, sr += reference[i].x + reference[i].y + reference[i].z;
  return sr > 0 ? (sa - sr) / sr : 0.0;
}

double relativeRmse(const std::vector<Vec3>& a, const std::vector<Vec3>& reference) {
  double sum = 0, mean = 0;
  for (std::size_t i = 0; i < a.size(); ++i) {
    const Vec3 e = a[i] - reference[i];
    sum += dot(e, e) / 3;
    mean += (reference[i].x + reference[i].y + reference[i].z) / 3;
  }
  mean /= double(a.size());
  return mean > 0 ? std::sqrt(sum / double(a.size())) / mean : 0.0;
}

}  // namespace

CloudComparison compareCloudModels(const media::Medium& layer, const CloudComparisonSettings& c) {
  CloudComparison out;
  // Sun and sky from the atmosphere: the sun's irradiance at the medium's middle altitude, the
  // sky tabulated as daylight/ does for scenes. Below the horizon the sky is the ground's glow
  // ρ E_h/π (black by default).
  SkyDescription sd;
  sd.model = "physical", sd.parameters = Params();
  sd.sun = true, sd.sunElevationDeg = c.sunElevationDeg, sd.sunAzimuthDeg = c.sunAzimuthDeg;
  sd.groundReflectance = c.groundAlbedo;
  const auto sky = std::make_shared<const SkyModel>(sd);
  const Bounds3 bounds = layer.bounds();
  const atmosphere::Atmosphere air;
  const Vec3 sunLocal = atmosphere::sunDirection(c.sunElevationDeg, c.sunAzimuthDeg);
  media::Lighting& light = out.light;
  light.sunDirection = sunLocal;
  light.sunIrradiance =
      air.sunIrradiance(air.pointAtAltitude((bounds.lo.z + bounds.hi.z) / 2), sunLocal);
  light.sky = [sky](const Vec3& d) { return sky->radiance(d); };
  // The path tracer bounces paths off a Lambertian ground at z = 0; the real-time model has no
  // ground, so it sees the ground as the sky's glow below the horizon and gets it as its
  // ambient light from below: ρ (E_sky + E_sun)/π, unshadowed by the medium (an overestimate
  // under thick cover).
  light.groundAlbedo = c.groundAlbedo;
  // Next-event estimation to the sky; a ground hides the sky's lower half from the medium.
  if (c.skyNee)
    light.skySampler = std::make_shared<const SkySampler>(light.sky, c.groundAlbedo > 0);
  media::MarchSettings march = c.march;
  march.ambientTop = sky->horizontalSky() / M_PI;  // cosine-weighted mean sky radiance
  march.ambientBottom = (sky->horizontalSky() + sky->horizontalSun()) * (c.groundAlbedo / M_PI);

  const PinholeCamera pinhole(c.camera, c.width, c.height);
  const auto ray = [&](double x, double y) { return pinhole.direction(x, y); };
  out.reference = media::renderVolume(layer, light, c.camera.position, ray, c.width, c.height,
                                      c.samples, c.seed);
  double noise = 0, mean = 0;
  for (std::size_t i = 0; i < out.reference.radiance.size(); ++i) {
    noise += dot(out.reference.standardError[i], out.reference.standardError[i]) / 3;
    const Vec3& r = out.reference.radiance[i];
    mean += (r.x + r.y + r.z) / 3;
  }
  mean /= double(out.reference.radiance.size());
  out.referenceMean = mean;
  out.referenceNoise =
      mean > 0 ? std::sqrt(noise / double(out.reference.radiance.size())) / mean : 0;

  // The features switched on one by one, then the step counts.
  std::vector<std::pair<std::string, media::MarchSettings>> variants;
  media::MarchSettings s = march;
  s.octaves = 1, s.ambient = false, s.jitter = false;
  variants.push_back({"single scattering", s});
  s.ambient = true;
  variants.push_back({"+ ambient", s});
  s.octaves = march.octaves;
  variants.push_back({"+ " + std::to_string(s.octaves) + " octaves", s});
  s.jitter = true;
  variants.push_back({"+ blue-noise jitter (defaults)", s});
  out.defaults = int(variants.size()) - 1;
  media::MarchSettings coarse = s, fine = s;
  coarse.primarySteps = std::max(1, s.primarySteps / 2),
  coarse.lightSteps = std::max(1, s.lightSteps / 2);
  fine.primarySteps = s.primarySteps * 4, fine.lightSteps = s.lightSteps * 4;
  variants.push_back({"defaults, half the steps", coarse});
  variants.push_back({"defaults, 4x the steps", fine});
  for (const auto& [name, settings] : variants) {
    CloudVariant v;
    v.name = name;
    v.settings = settings;
    v.image = media::renderMarched(layer, light, c.camera.position, ray, c.width, c.height,
                                   settings, c.seed);
    v.relativeRmse = relativeRmse(v.image.radiance, out.reference.radiance);
    v.relativeBias = relativeBias(v.image.radiance, out.reference.radiance);
    out.variants.push_back(std::move(v));
  }
  return out;
}

}  // namespace radkit
