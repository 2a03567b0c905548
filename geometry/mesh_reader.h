// Mesh files for mesh surfaces: PLY, OFF, STL through OpenMesh's readers, OBJ through
// tinyobjloader. Internal to geometry/.
#pragma once

#include <functional>
#include <string>
#include <unordered_set>
#include <vector>

#include "geometry/scene.h"
#include "util/errors.h"

namespace radkit {

/// A mesh as read: vertex positions and faces (vertex indices, file order).
struct RawMesh {
  std::vector<Vec3> vertices;
  std::vector<Face> faces;
  std::size_t droppedFaces = 0;  ///< faces repeating a vertex, dropped when repairing
};

/// Called with the fraction of a mesh file read (0..1).
using MeshReadProgress = std::function<void(double)>;

/// \brief Reads a PLY, OFF, STL or OBJ file into one mesh, vertices in file order; throws
/// InputError naming the file on a missing file, an unknown extension, unreadable content, a
/// text number that is not a finite decimal (text_numbers.h) or a face repeating a vertex.
/// Faces wound against their neighbours and non-manifold edges are left to validateScene.
/// `repair`: faces repeating a vertex, which OpenMesh's readers drop, are counted instead.
/// ASCII OFF, PLY and binary STL of the common layouts take the streaming reader
/// (mesh_stream.h); `streaming` false reads every file the full way (checkMeshStructure,
/// checkTextMeshNumbers, OpenMesh), the reference the streaming reader is tested against.
RawMesh readMeshFile(const std::string& path, bool repair = false,
                     const MeshReadProgress& progress = {}, bool streaming = true);

/// \brief Loads an OBJ with its MTL as a whole scene: each OBJ object or group is a named
/// surface; MTL Kd becomes reflectance and Ke emission.
/// A diffuse texture (map_Kd) gives the reflectance its mean linear colour, at most this.
inline constexpr double kMaxTextureReflectance = 0.99;

/// `replaced`: names of materials the including JSON scene defines itself; their MTL entries
/// are neither checked nor warned about, so a JSON material can fix an MTL value radkit
/// refuses (a window's Kd 1).
Scene loadObjScene(const std::string& path, std::vector<std::string>* warnings = nullptr,
                   const std::unordered_set<std::string>* replaced = nullptr);

}  // namespace radkit
