// The one place radkit talks to Embree 3 (see Embree's tutorials/minimal for the pattern).
#include "geometry/ray_scene.h"

#include <embree3/rtcore.h>

#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>

namespace radkit {

namespace {
/// First Embree error reported through the device callback.
struct ErrorLog {
  std::mutex mutex;
  std::string first;
};

// The callback only records: throwing through Embree's C interface is not allowed.
void recordError(void* user, RTCError code, const char* message) {
  auto* log = static_cast<ErrorLog*>(user);
  std::lock_guard<std::mutex> lock(log->mutex);
  if (log->first.empty())
    log->first = "Embree error " + std::to_string(int(code)) + ": " + (message ? message : "");
}
}  // namespace

struct RayScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  // Embree works in float. Coordinates are stored relative to the scene centre so that a
  // scene far from the origin keeps the precision of its own extent.
  Vec3 centre;
  double epsilon = 0;
  ErrorLog errors;
  /// Per patch: its normal where its surface culls back-face hits (both sides of a two-sided
  /// surface, coincident), else zero.
  std::vector<Vec3> cullNormal;

  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }

  void throwIfError(const char* what) {
    std::lock_guard<std::mutex> lock(errors.mutex);
    if (!errors.first.empty()) throw std::runtime_error(std::string(what) + ": " + errors.first);
  }

  RTCRay makeRay(const Vec3& origin, const Vec3& direction, double tNear, double tFar) const {
    RTCRay ray;
    Vec3 o = origin - centre;
    ray.org_x = float(o.x);
    ray.org_y = float(o.y);
    ray.org_z = float(o.z);
    ray.dir_x = float(direction.x);
    ray.dir_y = float(direction.y);
    ray.dir_z = float(direction.z);
    ray.tnear = float(tNear);
    ray.tfar = float(tFar);
    ray.time = 0;
    ray.mask = 0xFFFFFFFFu;
    ray.id = 0;
    ray.flags = 0;
    return ray;
  }

  bool occluded(const Vec3& origin, const Vec3& direction, double tNear, double tFar) const {
    RTCIntersectContext context;
    rtcInitIntersectContext(&context);
    RTCRay ray = makeRay(origin, direction, tNear, tFar);
    rtcOccluded1(scene, &context, &ray);
    return ray.tfar < 0;  // Embree sets tfar to -inf on a hit
  }
};

namespace {

/// Embree filter for meshes with back-culled surfaces: a hit on the back of such a patch is
/// not a hit (its coincident twin, facing the ray, is hit instead).
void cullBackFaces(const RTCFilterFunctionNArguments* args) {
  const auto* normals = static_cast<const std::vector<Vec3>*>(args->geometryUserPtr);
  for (unsigned i = 0; i < args->N; ++i) {
    if (args->valid[i] != -1) continue;
    const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
    const Vec3& n = (*normals)[prim];
    const double facing = n.x * RTCRayN_dir_x(args->ray, args->N, i) +
                          n.y * RTCRayN_dir_y(args->ray, args->N, i) +
                          n.z * RTCRayN_dir_z(args->ray, args->N, i);
    if (facing > 0) args->valid[i] = 0;
  }
}

}  // namespace

RayScene::RayScene(const PatchMesh& mesh, int threads, RayRobustness robustness)
    : m_impl(std::make_unique<Impl>()) {
  Impl& im = *m_impl;
  std::string config = threads > 0 ? "threads=" + std::to_string(threads) : "";
  im.device = rtcNewDevice(config.empty() ? nullptr : config.c_str());
  if (!im.device) throw std::runtime_error("Embree: could not create a device");
  rtcSetDeviceErrorFunction(im.device, recordError, &im.errors);

  Bounds3 bounds = mesh.bounds();
  im.centre = bounds.empty() ? Vec3{} : (bounds.lo + bounds.hi) * 0.5;
  im.epsilon = rayEpsilon(bounds);

  im.scene = rtcNewScene(im.device);
  // Robust mode makes the triangle test watertight, so rays through shared edges of
  // neighbouring patches cannot slip through.
  rtcSetSceneFlags(
      im.scene, robustness == RayRobustness::Robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
  rtcSetSceneBuildQuality(im.scene, RTC_BUILD_QUALITY_HIGH);

  // One quad geometry: Embree reads a quad whose last two indices repeat as a triangle, so
  // the primitive id is the patch index for triangles and quads alike.
  RTCGeometry geom = rtcNewGeometry(im.device, RTC_GEOMETRY_TYPE_QUAD);
  // Embree-managed buffers are padded for its 16-byte loads and live as long as the geometry.
  auto* v = static_cast<float*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 3 * sizeof(float), mesh.vertices.size()));
  for (std::size_t k = 0; k < mesh.vertices.size(); ++k) {
    Vec3 p = mesh.vertices[k] - im.centre;
    v[3 * k] = float(p.x);
    v[3 * k + 1] = float(p.y);
    v[3 * k + 2] = float(p.z);
  }
  auto* q = static_cast<unsigned*>(rtcSetNewGeometryBuffer(
      geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT4, 4 * sizeof(unsigned), mesh.patches.size()));
  for (std::size_t i = 0; i < mesh.patches.size(); ++i) {
    const Patch& p = mesh.patches[i];
    for (int k = 0; k < 4; ++k) q[4 * i + k] = unsigned(p.vertex[k < p.vertexCount ? k : 2]);
  }
  if (!mesh.cullBack.empty()) {
    im.cullNormal.assign(mesh.patches.size(), Vec3{});
    bool any = false;
    for (std::size_t i = 0; i < mesh.patches.size(); ++i)
      if (mesh.cullBack[mesh.patches[i].surface])
        im.cullNormal[i] = mesh.patches[i].normal, any = true;
    if (any) {
      rtcSetGeometryUserData(geom, &im.cullNormal);
      rtcSetGeometryIntersectFilterFunction(geom, cullBackFaces);
      rtcSetGeometryOccludedFilterFunction(geom, cullBackFaces);
    }
  }
  rtcCommitGeometry(geom);
  rtcAttachGeometry(im.scene, geom);
  rtcReleaseGeometry(geom);
  rtcCommitScene(im.scene);
  im.throwIfError("building the ray scene");
}

RayScene::~RayScene() = default;
RayScene::RayScene(RayScene&&) noexcept = default;
RayScene& RayScene::operator=(RayScene&&) noexcept = default;

double RayScene::epsilon() const { return m_impl->epsilon; }

bool RayScene::occluded(const Vec3& from, const Vec3& nFrom, const Vec3& to,
                        const Vec3& nTo) const {
  // Each end is lifted off its own plane toward the other, so its own patch lies behind the
  // ray (t < 0) and the target's plane beyond t = 1, by a margin of eps in both cases.
  const double eps = m_impl->epsilon;
  Vec3 p = liftToward(from, nFrom, to, eps);
  // Toward the lifted p: coplanar ends then go to the same side instead of by rounding.
  Vec3 q = liftToward(to, nTo, p, eps);
  return m_impl->occluded(p, q - p, 0.0, 1.0);
}

bool RayScene::occluded(const Vec3& from, const Vec3& to) const {
  Vec3 d = to - from;
  double len = length(d);
  double eps = m_impl->epsilon;
  if (len <= 2 * eps) return false;
  return m_impl->occluded(from, d, eps / len, 1.0 - eps / len);
}

std::optional<RayHit> RayScene::closestHit(const Vec3& origin, const Vec3& direction, double tMin,
                                           double tMax) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh;
  rh.ray = m_impl->makeRay(origin, direction, tMin, std::isfinite(tMax) ? tMax : INFINITY);
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(m_impl->scene, &context, &rh);
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return std::nullopt;
  return RayHit{int(rh.hit.primID), double(rh.ray.tfar)};
}

bool RayScene::occludedRaw(const Vec3& origin, const Vec3& direction, double tNear,
                           double tFar) const {
  return m_impl->occluded(origin, direction, tNear, tFar);
}

}  // namespace radkit
