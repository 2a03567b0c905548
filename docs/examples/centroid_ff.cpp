// docs/extending.md, example 2: a form-factor method with a parameter of its own.
// Centroid-to-polygon: F_ij is the exact point-to-polygon form factor from patch i's centroid
// to patch j, times one visibility ray between the centroids (visibility=0 skips the ray: the
// unoccluded form factor, to see what the occluders take). Cheap and coarse (wrong for near,
// large patches). Built and run by tests/extending/.
#include <memory>
#include <string>

#include "radiosity/contour.h"
#include "radiosity/form_factor_method.h"
#include "util/params.h"

namespace radkit {

namespace {

class CentroidFormFactors final : public FormFactorMethod {
 public:
  CentroidFormFactors(const PatchMesh& mesh, const Visibility& visibility, bool visible)
      : m_mesh(mesh), m_rays(visibility), m_visibility(visible) {}

  std::string name() const override { return "centroid"; }
  std::string describe() const override {
    return m_visibility ? "centroid-to-polygon, one visibility ray"
                        : "centroid-to-polygon, unoccluded (visibility=0)";
  }
  RowCoverage coverage() const override { return RowCoverage::FullRow; }

  void computeRow(int i, RowResult& out) const override {
    out.clear();
    const Patch& p = m_mesh.patches[i];
    for (int j = 0; j < m_mesh.size(); ++j) {
      if (j == i) continue;
      const Patch& q = m_mesh.patches[j];
      const Vec3 d = q.centroid - p.centroid;
      if (dot(d, p.normal) <= 0 || dot(d, q.normal) >= 0) continue;  // not facing each other
      Vec3 polygon[4];
      for (int k = 0; k < q.vertexCount; ++k) polygon[k] = m_mesh.vertices[q.vertex[k]];
      const double f = pointToPolygonFormFactor(p.centroid, p.normal, polygon, q.vertexCount);
      if (!(f > 0)) continue;
      if (m_visibility) {
        ++out.raysCast;
        if (m_rays.occluded(p.centroid, p.normal, q.centroid, q.normal)) continue;
      }
      out.entries.push_back({j, f, 0.0});
    }
  }

 private:
  const PatchMesh& m_mesh;
  const Visibility& m_rays;
  bool m_visibility;
};

}  // namespace

// The registry calls this with the method's parameters (--ff centroid:visibility=0) and
// refuses any key it did not read.
std::unique_ptr<FormFactorMethod> createCentroid(Params& params, const PatchMesh& mesh,
                                                 const Visibility& visibility,
                                                 const FormFactorSettings&) {
  const bool visible = params.integer("visibility", 1, 0, 1) == 1;
  return std::make_unique<CentroidFormFactors>(mesh, visibility, visible);
}

}  // namespace radkit
