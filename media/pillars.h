// Light pillars (docs/pillars.md): lamp light reflected once by nearly horizontal hexagonal ice
// plates. Two renderers of the same single-scattering radiance: an exact per-pixel closed form
// (minimum-tilt point and 5° boundary points in closed form, Gauss-Legendre between them) and
// a Monte Carlo reference that samples plates and reflects the view ray into finite lamps.
// Coordinates: x east, y north, z up, metres.
#pragma once

#include <cstdint>
#include <vector>

#include "util/vec3.h"

namespace radkit::media {

/// Half-Gaussian plate tilt (angle between plate normal and vertical) cut at `cut`; plates
/// tilted beyond the cut are ignored (not renormalised), so the density integrates to
/// erf(cut/(σ√2)) (0.99730 for σ = 5/3°, cut = 5°).
struct PillarTilt {
  double sigma = 5.0 / 3.0 * kPi / 180;  ///< radians
  double cut = 5.0 * kPi / 180;          ///< radians
};

/// p(β) = √(2/π)/σ · exp(−β²/(2σ²)) for 0 ≤ β ≤ cut, else 0 (per radian).
double pillarTiltDensity(double beta, const PillarTilt& tilt);
/// ∫₀^cut p dβ = erf(cut/(σ√2)): the fraction of plates the model keeps.
double pillarTiltMass(const PillarTilt& tilt);
/// D(m) = p(β)/(2π sin β) per steradian, β the angle of the line of m from vertical (a plate
/// reflects with both faces, so m and −m are the same plate).
double pillarNormalDensity(const Vec3& m, const PillarTilt& tilt);

/// Inverse-CDF sampler of the cut half-Gaussian: a 4097-node table of the inverse CDF gives
/// the start, one Newton step on erf puts the CDF of the result within 1e-10 of u.
class PillarTiltSampler {
 public:
  explicit PillarTiltSampler(const PillarTilt& tilt);
  /// β with density p(β)/mass on [0, cut] for u uniform in [0, 1).
  double sample(double u) const;

 private:
  PillarTilt m_tilt;
  double m_scale;  ///< σ√2
  double m_mass;
  std::vector<double> m_table;  ///< erf⁻¹(i/4096 · mass) for i = 0..4096
};

/// ρ0 = ((n − 1)/(n + 1))² (normal incidence, Fresnel); 0.018009 for ice, n = 1.31.
double pillarRho0(double n);
/// Schlick's R(θ) = ρ0 + (1 − ρ0)(1 − cos θ)⁵ from cos θ.
double pillarSchlick(double cosTheta, double rho0);
/// Antiderivative of R(θ) in θ: ρ0θ + (1 − ρ0)[63θ/8 − 16 sin θ + 15/4 sin 2θ + 4 sin³θ
/// + 5/32 sin 4θ − 1/5 sin⁵θ] (θ coefficient 7.751 for ice; ∫₀^{π/2} R = 0.19525).
double pillarSchlickAntiderivative(double theta, double rho0);

/// Unit half vector normalize(ωi + ωo) of two unit vectors pointing away from the plate.
Vec3 pillarHalfVector(const Vec3& wi, const Vec3& wo);
/// Tilt a plate needs to reflect ωi into ωo: the angle of the line of the half vector from
/// vertical, in [0, π/2].
double pillarRequiredTilt(const Vec3& wi, const Vec3& wo);
/// Mirror reflection of w about the plane with normal m (either orientation): 2(w·m)m − w.
Vec3 pillarReflect(const Vec3& w, const Vec3& m);
/// dσ/dωo of one plate of area `area` with normals distributed as D: A·D(h)·R(θd)/4,
/// θd = angle(ωi, h) (m² sr⁻¹).
double pillarCrossSection(const Vec3& wi, const Vec3& wo, double area, const PillarTilt& tilt,
                          double rho0);

/// Tilt required at the point eye + t·d to reflect light of a point lamp at `lamp` to the eye.
double pillarTiltAlongRay(const Vec3& eye, const Vec3& d, const Vec3& lamp, double t);

/// A point on the view ray and the tilt it requires.
struct PillarRayPoint {
  double t = 0;     ///< distance along the view ray (m)
  double tilt = 0;  ///< radians
};

/// \brief Exact minimum of the required tilt over eye + t·d, t ∈ [tMin, tMax] (d unit).
/// With ψ the angle the ray subtends at the lamp from the closest-approach point C (distance
/// b), P = C + b tan ψ·d and the half vector is sin γ·u − cos γ·d, γ = π/4 − ψ/2, so
/// cos(tilt) = |R sin(γ − δ)| and the minimum is at γ = δ + π/2 (mod π) or an end.
PillarRayPoint pillarMinimumTilt(const Vec3& eye, const Vec3& d, const Vec3& lamp, double tMin,
                                 double tMax);
/// \brief The original real-time model's closed form as reconstructed in docs/pillars.md (a known
/// defect, kept for the tests): the vertical-plane mirror point z* = (z_eye + z_lamp + D tan α)/2
/// and half the half-vector's tilt there. Right only in the eye–lamp vertical plane (where it
/// gives 0); off it about half the true minimum. Needs d.z > 0.
PillarRayPoint pillarFoundingMinimumTilt(const Vec3& eye, const Vec3& d, const Vec3& lamp);
/// The segments of [tMin, tMax] where the required tilt is ≤ `cut` (at most two; each between
/// two boundary points where it equals `cut`, or an end), in closed form.
std::vector<PillarRayPoint> pillarTiltSegments(const Vec3& eye, const Vec3& d, const Vec3& lamp,
                                               double tMin, double tMax, double cut);

/// Axis-aligned occluder (a building, a lamp housing).
struct PillarBox {
  Vec3 lo, hi;
};

/// Entry distance of the ray o + s·w into the box for s in (sMin, sMax), or +∞.
double pillarRayBox(const Vec3& o, const Vec3& w, const PillarBox& box, double sMin, double sMax);
/// \brief The t ∈ [0, tMax] for which the segment lamp → eye + t·d meets the box, exactly:
/// points lamp + a(eye − lamp) + b·d are linear in (a, b) (a = s, b = s·t), so the box is a
/// convex polygon in (a, b); clipped to 0 ≤ b ≤ tMax·a ≤ tMax, its vertices' b/a bound the
/// interval. Returns false when the segment never meets it. The lamp must be outside the box.
bool pillarShadowInterval(const Vec3& lamp, const Vec3& eye, const Vec3& d, double tMax,
                          const PillarBox& box, double& t0, double& t1);

/// A lamp: point source of intensity I (W sr⁻¹ per RGB channel) for the closed form; for Monte
/// Carlo a sphere of radius r and uniform radiance I/(πr²), the same intensity from afar.
struct PillarLamp {
  Vec3 position;
  Vec3 intensity;
  double radius = 0.3;
};

/// Everything the two renderers share.
struct PillarScene {
  std::vector<PillarLamp> lamps;
  std::vector<PillarBox> boxes;
  double plateDensity = 1e-4;          ///< n_p·A, plate area per volume (m⁻¹)
  double extinction = 2e-4;            ///< σ_t of the air and ice (m⁻¹), uniform
  double slabTop = 300;                ///< plates float between the ground (z = 0) and here (m)
  double maxDistance = 20000;          ///< a horizontal view ray stops here (m)
  double rho0 = 0.018009407619797232;  ///< ((1.31 − 1)/(1.31 + 1))²
  PillarTilt tilt;
};

/// Throws std::invalid_argument for a scene the renderers cannot handle (a lamp inside a box
/// or outside the slab, non-positive radius, negative densities).
void pillarValidate(const PillarScene& scene);

/// Where the view ray's plates end: the slab top or the ground, maxDistance, or the first box.
double pillarViewRayEnd(const PillarScene& scene, const Vec3& eye, const Vec3& d);

/// Gauss-Legendre settings of the closed form.
struct PillarQuadrature {
  int points = 8;           ///< nodes per panel
  double panelWidth = 0.5;  ///< widest panel in the asinh variable v
};

/// \brief Closed-form radiance of the view ray eye + t·d (d unit), point lamps: per lamp
/// n_pA·I/(2b) ∫ D R T V dγ over the ≤ cut segments minus the exact shadow intervals,
/// integrated in v = asinh(R sin(γ − γ*)/sin β_min), where D dγ = p(β) dv/(2πR cos(γ − γ*)) is
/// smooth however small β_min is.
Vec3 pillarRadianceClosed(const PillarScene& scene, const Vec3& eye, const Vec3& d,
                          const PillarQuadrature& quadrature = {});
/// The same integral by brute force in t (composite Simpson with `intervals`, straight from
/// the D(h) integrand): an oracle for rays not too close to a lamp's vertical plane.
Vec3 pillarRadianceBruteForce(const PillarScene& scene, const Vec3& eye, const Vec3& d,
                              int intervals);

/// One pixel of Monte Carlo.
struct PillarEstimate {
  Vec3 mean;               ///< radiance
  double luminanceSe = 0;  ///< standard error of the luminance of `mean`
  long long hits = 0;      ///< samples whose reflected ray reached a lamp
};

/// \brief Monte Carlo radiance of one view ray: t uniform on the plate segment, plate normal
/// m from the cut tilt distribution (inverse CDF, uniform azimuth), the view direction
/// reflected about m; a reflected ray that reaches a lamp sphere unoccluded scores
/// length·n_pA·mass·|ωo·m|·R·L_lamp·T(eye↔P)·T(P↔lamp). Sample k uses Rng(seed, pixel, k).
PillarEstimate pillarRadianceMonteCarlo(const PillarScene& scene, const PillarTiltSampler& sampler,
                                        const Vec3& eye, const Vec3& d, long long samples,
                                        std::uint64_t seed, std::uint64_t pixel);

/// Pinhole camera: eye, view azimuth (degrees clockwise from north) and elevation, horizontal
/// field of view, image size; pixel centres are (x + ½, y + ½), row 0 at the top.
struct PillarCamera {
  Vec3 eye{0, 0, 1.7};
  double azimuthDeg = 0, elevationDeg = 12, fovDeg = 40;
  int width = 160, height = 96;
  /// Unit direction through the centre of pixel (x, y).
  Vec3 direction(int x, int y) const;
};

/// An image of each kind; `standardError` and `hits` only for Monte Carlo.
struct PillarImage {
  int width = 0, height = 0;
  std::vector<Vec3> radiance;  ///< row-major, top row first
  std::vector<double> standardError;
  std::vector<long long> hits;
  double seconds = 0;
};

/// Closed-form image, TBB-parallel over rows.
PillarImage pillarRenderClosed(const PillarScene& scene, const PillarCamera& camera,
                               const PillarQuadrature& quadrature = {});
/// Monte Carlo image, TBB-parallel over rows, deterministic (pixel index = y·width + x).
PillarImage pillarRenderMonteCarlo(const PillarScene& scene, const PillarCamera& camera,
                                   long long samples, std::uint64_t seed);

/// Closed form against Monte Carlo over the pixels with signal (closed-form luminance above
/// `signalFraction` of its maximum, or any Monte Carlo hit).
struct PillarComparison {
  int signalPixels = 0;
  double relativeRmse = 0;  ///< √mean((Y_mc − Y_cf)²) / mean(Y_cf), luminance
  double within3Se = 0;     ///< fraction with |Y_cf − Y_mc| < 3 SE
  double meanZ2 = 0;        ///< mean of ((Y_mc − Y_cf)/SE)² over pixels with SE > 0
  double maxAbsZ = 0;
  int zPixels = 0;  ///< pixels that entered meanZ2
};
PillarComparison pillarCompare(const PillarImage& closed, const PillarImage& mc,
                               double signalFraction = 1e-3, long long minHits = 1);

/// The command's night scene: five lamps 200–1500 m away, 5–10 m high, sodium and LED, and a
/// building that hides part of one pillar.
PillarScene pillarNightScene();

}  // namespace radkit::media
