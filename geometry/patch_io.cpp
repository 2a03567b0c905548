#include "geometry/patch_io.h"

#include <iomanip>
#include <sstream>

#include "util/output_folder.h"  // writeFileAtomically, csvField

namespace radkit {

namespace {
// Enough digits that a double read back is the same double.
constexpr int kDigits = 17;

void writeTriple(std::ostream& o, const Vec3& v) { o << ',' << v.x << ',' << v.y << ',' << v.z; }
}  // namespace

void writePatchesCsv(const std::string& path, const Scene& scene, const PatchMesh& mesh,
                     const std::vector<Vec3>* radiosity) {
  std::ostringstream o;
  o << std::setprecision(kDigits);
  o << "id,surface,area,cx,cy,cz,nx,ny,nz,rho_r,rho_g,rho_b,e_r,e_g,e_b,b_r,b_g,b_b\n";
  for (int i = 0; i < mesh.size(); ++i) {
    const Patch& p = mesh.patches[i];
    const Material& m = scene.materials[scene.surfaces[p.surface].material];
    o << i << ',' << csvField(scene.surfaces[p.surface].name) << ',' << p.area;
    writeTriple(o, p.centroid);
    writeTriple(o, p.normal);
    writeTriple(o, m.diffuseAlbedo());
    writeTriple(o, m.emission);
    writeTriple(o, radiosity ? (*radiosity)[i] : Vec3{});
    o << '\n';
  }
  writeFileAtomically(path, o.str());
}

void writePatchesVtp(const std::string& path, const Scene& scene, const PatchMesh& mesh,
                     const std::vector<Vec3>* radiosity, const std::vector<CellArray>& extra) {
  std::ostringstream o;
  o << std::setprecision(kDigits);
  o << "<?xml version=\"1.0\"?>\n"
    << "<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n<PolyData>\n"
    << "<Piece NumberOfPoints=\"" << mesh.vertices.size() << "\" NumberOfPolys=\"" << mesh.size()
    << "\">\n"
    << "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
  for (const Vec3& v : mesh.vertices) o << v.x << ' ' << v.y << ' ' << v.z << '\n';
  o << "</DataArray></Points>\n<Polys>\n<DataArray type=\"Int64\" Name=\"connectivity\" "
       "format=\"ascii\">\n";
  for (const Patch& p : mesh.patches) {
    for (int k = 0; k < p.vertexCount; ++k) o << p.vertex[k] << ' ';
    o << '\n';
  }
  o << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
  long long offset = 0;
  for (const Patch& p : mesh.patches) o << (offset += p.vertexCount) << '\n';
  o << "</DataArray>\n</Polys>\n<CellData Scalars=\"surface\">\n";
  o << "<DataArray type=\"Int32\" Name=\"surface\" format=\"ascii\">\n";
  for (const Patch& p : mesh.patches) o << p.surface << '\n';
  o << "</DataArray>\n<DataArray type=\"Float64\" Name=\"area\" format=\"ascii\">\n";
  for (const Patch& p : mesh.patches) o << p.area << '\n';
  o << "</DataArray>\n";
  auto triples = [&](const char* name, auto value) {
    o << "<DataArray type=\"Float64\" Name=\"" << name
      << "\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (int i = 0; i < mesh.size(); ++i) {
      Vec3 v = value(i);
      o << v.x << ' ' << v.y << ' ' << v.z << '\n';
    }
    o << "</DataArray>\n";
  };
  auto material = [&](int i) -> const Material& {
    return scene.materials[scene.surfaces[mesh.patches[i].surface].material];
  };
  triples("reflectance", [&](int i) { return material(i).diffuseAlbedo(); });
  triples("emission", [&](int i) { return material(i).emission; });
  if (radiosity) triples("radiosity", [&](int i) { return (*radiosity)[i]; });
  for (const CellArray& a : extra) {
    o << "<DataArray type=\"Float64\" Name=\"" << a.name << "\" format=\"ascii\">\n";
    for (double v : a.values) o << v << '\n';
    o << "</DataArray>\n";
  }
  o << "</CellData>\n</Piece>\n</PolyData>\n</VTKFile>\n";
  writeFileAtomically(path, o.str());
}

}  // namespace radkit
