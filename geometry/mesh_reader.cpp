// Mesh and OBJ scene reading. PLY/OFF/STL of the common layouts go through the streaming
// reader (mesh_stream.cpp), the rest through OpenMesh's readers; OBJ through tinyobjloader
// (double build) because it keeps groups and MTL materials.
#include "geometry/mesh_reader.h"
#include "util/format.h"

#include <stb/stb_image.h>
#include <tiny_obj_loader.h>
#include <OpenMesh/Core/IO/MeshIO.hh>
#include <OpenMesh/Core/Mesh/PolyMesh_ArrayKernelT.hh>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <optional>
#include <sstream>
#include <unordered_map>

#include "geometry/mesh_stream.h"
#include "geometry/mesh_structure.h"
#include "geometry/openmesh_errors.h"
#include "geometry/scene_loader.h"
#include "geometry/structure_text.h"
#include "geometry/text_numbers.h"
#include "util/setting_names.h"

namespace radkit {

namespace fs = std::filesystem;

namespace {

struct DoubleTraits : public OpenMesh::DefaultTraits {
  typedef OpenMesh::Vec3d Point;
  typedef OpenMesh::Vec3d Normal;
};
using PolyMesh = OpenMesh::PolyMesh_ArrayKernelT<DoubleTraits>;

std::string lowerExtension(const std::string& path) {
  std::string ext = fs::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(),
                 [](unsigned char c) { return std::tolower(c); });
  return ext;
}

/// OpenMesh gives a face that cannot join the surface manifoldly (wound against a neighbour,
/// or a third face on an edge) its own copies of the vertices and marks it. Such faces get the
/// file's vertices back (the first vertex at each copy's position) and the copies are dropped,
/// so that validation can reverse a wrongly wound face or name a non-manifold edge. The file's
/// vertices keep their order.
void restoreFileVertices(RawMesh& raw, const std::vector<std::size_t>& refused) {
  const std::size_t n = raw.vertices.size();
  std::map<std::array<double, 3>, int> firstAt;
  for (std::size_t v = 0; v < n; ++v) {
    const Vec3& p = raw.vertices[v];
    firstAt.emplace(std::array<double, 3>{p.x, p.y, p.z}, int(v));
  }
  std::vector<char> copy(n, 0), used(n, 0);
  for (std::size_t f : refused)
    for (int& v : raw.faces[f].vertices) {
      copy[v] = 1;
      const Vec3& p = raw.vertices[v];
      v = firstAt.at({p.x, p.y, p.z});
    }
  for (const Face& face : raw.faces)
    for (int v : face.vertices) used[v] = 1;
  std::vector<int> renumber(n, -1);
  std::vector<Vec3> kept;
  for (std::size_t v = 0; v < n; ++v)
    if (!copy[v] || used[v]) {
      renumber[v] = int(kept.size());
      kept.push_back(raw.vertices[v]);
    }
  raw.vertices = std::move(kept);
  for (Face& face : raw.faces)
    for (int& v : face.vertices) v = renumber[v];
}

/// `declaredFaces`: the count the file's header declares, or -1 when it does not say.
/// `offText`: checkMeshStructure's rewrite of an OFF file, read in its place when not empty.
RawMesh readWithOpenMesh(const std::string& path, long long declaredFaces, bool repair,
                         const std::string& offText) {
  PolyMesh mesh;
  mesh.request_face_status();
  mesh.request_edge_status();
  mesh.request_vertex_status();
  CapturedOpenMeshErrors errors;
  OpenMesh::IO::Options options;
  std::istringstream offStream(offText);
  if (!(!offText.empty() ? OpenMesh::IO::read_mesh(mesh, offStream, ".off", options)
                         : OpenMesh::IO::read_mesh(mesh, path, options))) {
    throw InputError(path + ": the mesh reader could not parse this file" +
                     (errors.text().empty() ? "" : " (" + errors.text() + ")") +
                     ". Fix: check that it is a valid PLY, OFF or STL file.");
  }
  const bool repeatedVertex = errors.text().find("equal vertices") != std::string::npos;
  if (repeatedVertex && !repair)
    throw InputError(path +
                     ": a face repeats a vertex (degenerate face). Fix: remove the "
                     "repeated index from the face, or give " +
                     setting("repair") + " to drop such faces.");
  // A safety net behind checkMeshStructure: OpenMesh drops faces it cannot add without a word.
  if (declaredFaces >= 0 && (long long)mesh.n_faces() != declaredFaces && !repeatedVertex)
    throw InputError(path + ": the file declares " + std::to_string(declaredFaces) +
                     " faces, but only " + std::to_string(mesh.n_faces()) + " could be read" +
                     (errors.text().empty() ? "" : " (" + errors.text() + ")") +
                     ". Fix: correct the faces the reader refused.");
  RawMesh raw;
  for (auto v : mesh.vertices()) {
    const auto p = mesh.point(v);
    raw.vertices.push_back({p[0], p[1], p[2]});
  }
  std::vector<std::size_t> refused;  // faces OpenMesh gave copies of their vertices
  for (auto f : mesh.faces()) {
    Face face;
    for (auto v : mesh.fv_range(f)) face.vertices.push_back(v.idx());
    if (mesh.status(f).fixed_nonmanifold()) refused.push_back(raw.faces.size());
    raw.faces.push_back(std::move(face));
  }
  if (!refused.empty()) restoreFileVertices(raw, refused);
  if (lowerExtension(path) == ".ply" && raw.faces.empty())
    for (std::vector<int>& t : plyStripTriangles(path)) raw.faces.push_back(Face{t});
  if (repeatedVertex && declaredFaces > (long long)raw.faces.size())
    raw.droppedFaces = declaredFaces - raw.faces.size();
  return raw;
}

/// The "mtllib" lines of an OBJ whose name only reads whole (a file name with a space, which
/// tinyobjloader splits), with the MTL files they name; empty when tinyobjloader reads them all.
std::vector<std::string> mtlFilesTinyobjWouldSplit(const std::string& path, bool& needed) {
  std::ifstream in(path, std::ios::binary);
  std::vector<std::string> files;
  needed = false;
  const std::string dir = fs::path(path).parent_path().string();
  for (std::string line; std::getline(in, line);) {
    const auto t = structure::tokens(structure::uncommented(line));
    if (t.empty() || t[0] != "mtllib") continue;
    const auto named = mtllibFiles(dir, t);
    if (t.size() > 2 && named.size() == 1) needed = true;
    files.insert(files.end(), named.begin(), named.end());
  }
  return files;
}

tinyobj::ObjReader parseObj(const std::string& path) {
  tinyobj::ObjReaderConfig config;
  config.triangulate = false;
  config.mtl_search_path = fs::path(path).parent_path().string();
  tinyobj::ObjReader reader;
  bool whole = false;
  const std::vector<std::string> mtls = mtlFilesTinyobjWouldSplit(path, whole);
  bool ok;
  if (whole) {
    // tinyobjloader would split "mtllib 247_House 15_obj.mtl" at the space: the MTLs are read
    // here and given to it as text, in the order the OBJ names them.
    std::string mtlText;
    for (const std::string& mtl : mtls) {
      std::error_code ec;
      if (!fs::is_regular_file(mtl, ec)) continue;
      std::ifstream m(mtl, std::ios::binary);
      mtlText += std::string(std::istreambuf_iterator<char>(m), {}) + "\n";
    }
    std::ifstream in(path, std::ios::binary);
    const std::string objText((std::istreambuf_iterator<char>(in)), {});
    ok = reader.ParseFromString(objText, mtlText, config);
  } else {
    ok = reader.ParseFromFile(path, config);
  }
  if (!ok)
    throw InputError(path + ": could not read OBJ: " + reader.Error() +
                     " Fix: check the file and the MTL it names.");
  return reader;
}

/// Appends the faces of one OBJ shape to a mesh whose vertices are the whole OBJ's.
void appendShapeFaces(const tinyobj::shape_t& shape, std::vector<Face>& faces,
                      std::vector<int>* faceMaterials) {
  std::size_t offset = 0;
  for (std::size_t f = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
    Face face;
    for (unsigned k = 0; k < shape.mesh.num_face_vertices[f]; ++k)
      face.vertices.push_back(shape.mesh.indices[offset + k].vertex_index);
    offset += shape.mesh.num_face_vertices[f];
    faces.push_back(std::move(face));
    if (faceMaterials) faceMaterials->push_back(shape.mesh.material_ids[f]);
  }
}

std::vector<Vec3> objVertices(const tinyobj::attrib_t& attrib) {
  std::vector<Vec3> vertices;
  for (std::size_t k = 0; k + 2 < attrib.vertices.size(); k += 3)
    vertices.push_back({attrib.vertices[k], attrib.vertices[k + 1], attrib.vertices[k + 2]});
  return vertices;
}

/// Keeps only the vertices the faces use, renumbered in first-use order. `map` has one entry
/// per vertex of `all`, all -1, and is left so: it is shared by the surfaces, because a fresh
/// one per surface costs surfaces × vertices (an OBJ of many one-face groups).
void compactVertices(const std::vector<Vec3>& all, Surface& surface, std::vector<int>& map) {
  std::vector<int> used;  // the file's indices, in first-use order
  for (std::size_t face = 0; face < surface.faces.size(); ++face)
    for (int& v : surface.faces[face].vertices) {
      if (v < 0 || v >= int(all.size()))  // checkMeshStructure refuses these first
        throw InputError(surface.source + ": face " + std::to_string(face) +
                         " names a vertex that does not "
                         "exist. Fix: correct the face's indices.");
      if (map[v] < 0) {
        map[v] = static_cast<int>(surface.vertices.size());
        surface.vertices.push_back(all[v]);
        used.push_back(v);
      }
      v = map[v];
    }
  for (int v : used) map[v] = -1;
}

}  // namespace

RawMesh readMeshFile(const std::string& path, bool repair, const MeshReadProgress& progress,
                     bool streaming) {
  std::error_code ec;
  if (!fs::exists(path, ec))
    throw InputError(path +
                     ": mesh file not found. Fix: give a path relative to the scene "
                     "file, or an absolute path.");
  if (streaming)
    if (std::optional<RawMesh> raw = readMeshStreaming(path, repair, progress))
      return std::move(*raw);
  std::string offText;
  const long long declaredFaces = checkMeshStructure(path, &offText);
  checkTextMeshNumbers(path);
  std::string ext = lowerExtension(path);
  if (ext == ".ply" || ext == ".off" || ext == ".stl")
    return readWithOpenMesh(path, declaredFaces, repair, offText);
  if (ext == ".obj") {
    tinyobj::ObjReader reader = parseObj(path);
    RawMesh raw;
    raw.vertices = objVertices(reader.GetAttrib());
    for (const auto& shape : reader.GetShapes()) appendShapeFaces(shape, raw.faces, nullptr);
    return raw;
  }
  throw InputError(path + ": unknown mesh format '" + ext +
                   "'. Fix: use .obj, .ply, .off or .stl.");
}

namespace {

/// An MTL material as radkit reads it (the MTL format of Wavefront's Advanced Visualizer): Kd is
/// the diffuse albedo, Ke the emission in W/m², Ks and Ns a glossy Phong lobe; Ka (ambient
/// colour) has no physical meaning and is ignored. Each assumption is a warning naming the
/// material.
/// sRGB-encoded value in [0, 1] to linear light (IEC 61966-2-1).
double srgbToLinear(double c) {
  return c <= 0.04045 ? c / 12.92 : std::pow((c + 0.055) / 1.055, 2.4);
}

/// The mean linear colour of an image file, or nullopt with `why` when it cannot be read.
/// 8-bit images are sRGB-decoded per pixel before averaging; HDR (.hdr) is already linear.
std::optional<Vec3> meanTextureColour(const fs::path& file, std::string& why) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) {
    why = "no such file";
    return std::nullopt;
  }
  const std::string name = file.string();
  int w = 0, h = 0, channels = 0;
  if (!stbi_info(name.c_str(), &w, &h, &channels)) {
    why = std::string("not an image stb_image reads (") + stbi_failure_reason() + ")";
    return std::nullopt;
  }
  // Checked before decoding: a header may declare any size.
  if (w <= 0 || h <= 0 || w > 32768 || h > 32768 || double(w) * h > double(1 << 26)) {
    why = std::to_string(w) + "x" + std::to_string(h) + " pixels, over the 2^26 read";
    return std::nullopt;
  }
  Vec3 sum{0, 0, 0};
  const std::size_t n = std::size_t(w) * std::size_t(h);
  if (stbi_is_hdr(name.c_str())) {
    float* px = stbi_loadf(name.c_str(), &w, &h, &channels, 3);
    if (!px) {
      why = stbi_failure_reason();
      return std::nullopt;
    }
    for (std::size_t k = 0; k < n; ++k) sum += Vec3{px[3 * k], px[3 * k + 1], px[3 * k + 2]};
    stbi_image_free(px);
  } else {
    unsigned char* px = stbi_load(name.c_str(), &w, &h, &channels, 3);
    if (!px) {
      why = stbi_failure_reason();
      return std::nullopt;
    }
    double table[256];
    for (int v = 0; v < 256; ++v) table[v] = srgbToLinear(v / 255.0);
    for (std::size_t k = 0; k < n; ++k)
      sum += Vec3{table[px[3 * k]], table[px[3 * k + 1]], table[px[3 * k + 2]]};
    stbi_image_free(px);
  }
  const Vec3 mean = sum * (1.0 / double(n));
  if (!isFinite(mean)) {
    why = "its pixels are not finite";
    return std::nullopt;
  }
  return mean;
}

/// `ambientOnly` collects the materials whose Ka is ignored (one warning names them all).
Material mtlMaterial(const tinyobj::material_t& m, const std::string& path,
                     std::vector<std::string>* warnings, std::vector<std::string>& ambientOnly) {
  auto warn = [&](const std::string& what) {
    if (warnings) warnings->push_back(path + ": MTL material \"" + m.name + "\": " + what);
  };
  Vec3 kd{m.diffuse[0], m.diffuse[1], m.diffuse[2]};
  const Vec3 ks{m.specular[0], m.specular[1], m.specular[2]};
  if (!m.diffuse_texname.empty()) {
    // Radiosity gives a patch one colour: a diffuse texture becomes its mean colour.
    std::string texture = m.diffuse_texname;
    std::replace(texture.begin(), texture.end(), '\\', '/');  // Windows exporters
    const fs::path file = fs::path(path).parent_path() / texture;
    std::string why;
    if (const std::optional<Vec3> mean = meanTextureColour(file, why)) {
      Vec3 capped = *mean;
      for (int c = 0; c < 3; ++c) capped[c] = std::min(capped[c], kMaxTextureReflectance);
      warn("map_Kd " + m.diffuse_texname + " read as its mean linear colour (" +
           formatNumber(capped.x, 3) + ", " + formatNumber(capped.y, 3) + ", " +
           formatNumber(capped.z, 3) + ") for the diffuse reflectance in place of Kd (" +
           formatNumber(kd.x, 3) + ", " + formatNumber(kd.y, 3) + ", " + formatNumber(kd.z, 3) +
           "): radiosity gives a patch one colour" +
           (maxComponent(*mean) > kMaxTextureReflectance
                ? std::string(", capped at ") + formatNumber(kMaxTextureReflectance) +
                      " (a white texture would reflect all light)"
                : std::string()));
      kd = capped;
    } else {
      warn("map_Kd " + m.diffuse_texname + " cannot be read (" + file.string() + ": " + why +
           "): Kd kept");
    }
  }
  const Vec3 ka{m.ambient[0], m.ambient[1], m.ambient[2]};
  Material mat;
  mat.name = m.name;
  mat.emission = {m.emission[0], m.emission[1], m.emission[2]};
  if (maxComponent(ks) > 0) {
    // Phong conserves energy only with kd + ks < 1; exporters often write Ks = 1 beside Kd.
    double sum = 0;
    for (int c = 0; c < 3; ++c) sum = std::max(sum, kd[c] + ks[c]);
    const double scale = sum >= 1 ? 0.999 / sum : 1.0;
    const double n = m.shininess > 0 ? m.shininess : 32;
    mat.bsdf = "phong";
    mat.params.set("kd", kd * scale);
    mat.params.set("ks", ks * scale);
    mat.params.set("shininess", n);
    warn("Ks read as a glossy Phong lobe (shininess " + formatNumber(n) +
         "); radiosity sees only Kd" +
         (scale < 1 ? ", and Kd + Ks = " + formatNumber(sum) + " was scaled by " +
                          formatNumber(scale) + " to conserve energy"
                    : ""));
  } else {
    mat.params.set("reflectance", kd);
    if (maxComponent(kd) <= 0 && !mat.emits())
      warn("Kd is 0 and there is no Ks: it absorbs all light (black)");
  }
  if (maxComponent(ka) > 0 && !mat.emits()) ambientOnly.push_back(m.name);
  try {
    resolveMaterial(mat);
  } catch (const ParamError& e) {
    throw InputError(path + ": MTL material \"" + m.name + "\": " + e.what());
  }
  return mat;
}

}  // namespace

Scene loadObjScene(const std::string& path, std::vector<std::string>* warnings,
                   const std::unordered_set<std::string>* replaced) {
  std::error_code ec;
  if (!fs::exists(path, ec)) throw InputError(path + ": scene file not found.");
  checkMeshStructure(path);
  checkTextMeshNumbers(path);
  tinyobj::ObjReader reader = parseObj(path);
  Scene scene;
  scene.file = path;
  scene.name = fs::path(path).stem().string();
  const std::string& mtlWarning = reader.Warning();
  if (reader.GetMaterials().empty() && mtlWarning.find("not found") != std::string::npos) {
    bool whole = false;
    std::string looked;
    for (const std::string& f : mtlFilesTinyobjWouldSplit(path, whole))
      looked += (looked.empty() ? "" : ", ") + f;
    throw InputError(path + ": its MTL file was not found (looked for " +
                     (looked.empty() ? std::string("nothing: no file name after mtllib") : looked) +
                     "). Fix: correct the \"mtllib\" line to the MTL's file name (relative to "
                     "the OBJ's folder, case included), or copy the MTL there.");
  }
  std::vector<std::string> ambientOnly;
  for (const auto& m : reader.GetMaterials()) {
    if (replaced && replaced->count(m.name)) {
      Material placeholder;  // the including scene's material of this name takes its place
      placeholder.name = m.name;
      scene.materials.push_back(placeholder);
      continue;
    }
    scene.materials.push_back(mtlMaterial(m, path, warnings, ambientOnly));
  }
  // Exporters write Ka beside Kd on every material; one line says it, not one per material.
  if (warnings && !ambientOnly.empty()) {
    std::string names;
    for (std::size_t k = 0; k < ambientOnly.size() && k < 5; ++k)
      names += (k ? ", \"" : "\"") + ambientOnly[k] + "\"";
    if (ambientOnly.size() > 5) names += ", ...";
    warnings->push_back(path + ": Ka (ambient colour) is ignored in " +
                        std::to_string(ambientOnly.size()) + " MTL material" +
                        (ambientOnly.size() > 1 ? "s" : "") + " (" + names +
                        "); if one of them is a light, give it Ke (emission in W/m²)");
  }
  std::vector<Vec3> all = objVertices(reader.GetAttrib());
  // Surface index by name: looked up once per face, so it must not be a scan (a scan per face
  // over the group's faces made a 80 000-face OBJ take minutes; found by fuzzing).
  std::unordered_map<std::string, std::size_t> surfaceByName;
  for (const auto& shape : reader.GetShapes()) {
    std::vector<Face> faces;
    std::vector<int> materialIds;
    appendShapeFaces(shape, faces, &materialIds);
    // A surface has one material: an OBJ group that switches material mid-way is split.
    const std::string group = shape.name.empty() ? "object" : shape.name;
    const bool split = std::any_of(materialIds.begin(), materialIds.end(),
                                   [&](int m) { return m != materialIds[0]; });
    for (std::size_t f = 0; f < faces.size(); ++f) {
      const int mat = materialIds[f];
      std::string name = group;
      if (split) name += "." + (mat >= 0 ? scene.materials[mat].name : std::string("default"));
      auto [it, added] = surfaceByName.emplace(name, scene.surfaces.size());
      if (added) {
        Surface s;
        s.name = name;
        s.material = mat;
        s.source = path + ": object '" + name + "'";
        scene.surfaces.push_back(s);
      }
      scene.surfaces[it->second].faces.push_back(std::move(faces[f]));
    }
  }
  std::vector<int> vertexMap(all.size(), -1);
  for (Surface& s : scene.surfaces) {
    if (s.material < 0)
      throw InputError(
          s.source +
          " has no material (usemtl). Fix: either give the OBJ an MTL file (\"mtllib\") and a "
          "\"usemtl NAME\" before its faces, with Kd (and Ke for emitters) under \"newmtl "
          "NAME\"; or leave the OBJ as it is and name it from a JSON scene, as a surface "
          "{\"name\": ..., \"material\": ..., \"mesh\": \"" +
          fs::path(path).filename().string() +
          "\"} with the materials in the JSON (docs/bring-your-own-model.md)");
    compactVertices(all, s, vertexMap);
  }
  return scene;
}

}  // namespace radkit
