// docs/extending.md, example 2: a form-factor method. Centroid-to-polygon: F_ij is the exact
// point-to-polygon form factor from patch i's centroid to patch j, times one visibility ray
// between the centroids. Cheap and coarse (wrong for near, large patches). Built and run by
// tests/extending/.
#include <memory>
#include <string>

#include "radiosity/contour.h"
#include "radiosity/form_factor_method.h"

namespace radkit {

namespace {

class CentroidFormFactors final : public FormFactorMethod {
 public:
  CentroidFormFactors(const PatchMesh& mesh, const Visibility& visibility)
      : m_mesh(mesh), m_rays(visibility) {}

  std::string name() const override { return "centroid"; }
  std::string describe() const override { return "centroid-to-polygon, one visibility ray"; }
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
      ++out.raysCast;
      if (f > 0 && !m_rays.occluded(p.centroid, p.normal, q.centroid, q.normal))
        out.entries.push_back({j, f, 0.0});
    }
  }

 private:
  const PatchMesh& m_mesh;
  const Visibility& m_rays;
};

}  // namespace

std::unique_ptr<FormFactorMethod> createCentroid(const PatchMesh& mesh,
                                                 const Visibility& visibility,
                                                 const FormFactorSettings&) {
  return std::make_unique<CentroidFormFactors>(mesh, visibility);
}

}  // namespace radkit
