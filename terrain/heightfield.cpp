#include "terrain/heightfield.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "util/output_folder.h"

namespace radkit::terrain {

Heightfield makeHeightfield(const TerrainSettings& s) {
  if (s.resolution < 2) throw std::invalid_argument("terrain: resolution must be at least 2");
  Heightfield f;
  f.n = s.resolution;
  f.size = s.size;
  f.z.assign(std::size_t(f.n) * f.n, 0.0);
  tbb::parallel_for(tbb::blocked_range<int>(0, f.n), [&](const tbb::blocked_range<int>& rows) {
    for (int j = rows.begin(); j < rows.end(); ++j)
      for (int i = 0; i < f.n; ++i) {
        const Vec3 p = f.vertex(i, j);  // z is still 0
        const double x = p.x / s.featureSize, y = p.y / s.featureSize;
        f.z[std::size_t(j) * f.n + i] = s.type == NoiseType::Ridged
                                            ? ridgedMultifractal(x, y, s.fractal)
                                            : fbm(x, y, s.fractal);
      }
  });
  const auto [lo, hi] = std::minmax_element(f.z.begin(), f.z.end());
  const double zmin = *lo, range = *hi - *lo;
  for (double& z : f.z) z = range > 0 ? (z - zmin) / range * s.height : 0.0;
  return f;
}

TerrainMesh triangulate(const Heightfield& f, const TerrainSettings& s) {
  TerrainMesh m;
  const int n = f.n;
  m.vertices.reserve(std::size_t(n) * n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) m.vertices.push_back(f.vertex(i, j));
  const double cosRock = std::cos(s.rockSlopeDeg * M_PI / 180);
  const double cosSnow = std::cos(s.snowSlopeDeg * M_PI / 180);
  const double top = s.height > 0 ? s.height : 1;
  auto add = [&](int a, int b, int c) {
    const Vec3& pa = m.vertices[a];
    const Vec3& pb = m.vertices[b];
    const Vec3& pc = m.vertices[c];
    const Vec3 normal = normalize(cross(pb - pa, pc - pa));
    const double h = (pa.z + pb.z + pc.z) / 3 / top;
    TerrainMaterial t = TerrainMaterial::Grass;
    if (h > s.snowLine && normal.z >= cosSnow)
      t = TerrainMaterial::Snow;
    else if (normal.z < cosRock)
      t = TerrainMaterial::Rock;
    m.triangles.push_back({a, b, c});
    m.material.push_back(t);
  };
  for (int j = 0; j + 1 < n; ++j)
    for (int i = 0; i + 1 < n; ++i) {
      const int v00 = j * n + i, v10 = v00 + 1, v01 = v00 + n, v11 = v01 + 1;
      add(v00, v10, v11);  // counter-clockwise seen from +z
      add(v00, v11, v01);
    }
  return m;
}

std::size_t writeTerrainPart(const std::string& path, const TerrainMesh& mesh,
                             TerrainMaterial material) {
  const bool ply = path.size() >= 4 && path.compare(path.size() - 4, 4, ".ply") == 0;
  std::vector<int> index(mesh.vertices.size(), -1);
  std::vector<int> used;
  std::vector<std::array<int, 3>> faces;
  for (std::size_t t = 0; t < mesh.triangles.size(); ++t) {
    if (mesh.material[t] != material) continue;
    std::array<int, 3> f{};
    for (int k = 0; k < 3; ++k) {
      int& v = index[mesh.triangles[t][k]];
      if (v < 0) v = int(used.size()), used.push_back(mesh.triangles[t][k]);
      f[k] = v;
    }
    faces.push_back(f);
  }
  writeFileStreaming(path, [&](std::ostream& o) {
    o.precision(9);  // 1e-9 of a kilometre: far below the ray offset
    if (ply)
      o << "ply\nformat ascii 1.0\ncomment radkit terrain: " << kTerrainMaterialNames[int(material)]
        << "\nelement vertex " << used.size()
        << "\nproperty double x\nproperty double y\nproperty double z\nelement face "
        << faces.size() << "\nproperty list uchar int vertex_indices\nend_header\n";
    else
      o << "# radkit terrain: " << kTerrainMaterialNames[int(material)] << "\n";
    for (int v : used) {
      const Vec3& p = mesh.vertices[v];
      o << (ply ? "" : "v ") << p.x << ' ' << p.y << ' ' << p.z << '\n';
    }
    for (const auto& f : faces)
      if (ply)
        o << "3 " << f[0] << ' ' << f[1] << ' ' << f[2] << '\n';
      else
        o << "f " << f[0] + 1 << ' ' << f[1] + 1 << ' ' << f[2] + 1 << '\n';
  });
  return faces.size();
}

}  // namespace radkit::terrain
