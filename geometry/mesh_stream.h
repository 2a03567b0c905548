// The fast load path for large meshes: ASCII OFF, ASCII and binary PLY, binary STL read in one
// pass from a memory-mapped file straight into vertices and faces. Internal to geometry/.
#pragma once

#include <functional>
#include <optional>
#include <string>

#include "geometry/mesh_reader.h"
#include "util/errors.h"

namespace radkit {

/// \brief Reads `path` (.off, .ply, .stl) in one streaming pass, with the checks and results of
/// checkMeshStructure + checkTextMeshNumbers + OpenMesh's readers: the same vertices in the same
/// order (coordinates rounded to float as OpenMesh's readers round them), the same faces.
/// Returns nullopt for anything it does not cover (an unusual header, a structural error, a
/// face OpenMesh would give vertex copies where positions repeat, ...): the caller then reads
/// the file the full way, which also words every structural error. Throws InputError for what
/// it reports itself: a text number that is not finite, a face repeating a vertex.
std::optional<RawMesh> readMeshStreaming(const std::string& path, bool repair,
                                         const MeshReadProgress& progress = {});

}  // namespace radkit
