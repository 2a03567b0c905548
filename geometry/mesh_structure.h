// Checks the structure of mesh files before a reader parses them: header counts against the
// file's size, face indices against the vertex count, truncation. OpenMesh's and
// tinyobjloader's readers trust these, and then allocate without bound, loop forever, read out
// of bounds or silently drop faces. Internal to geometry/.
#pragma once

#include <string>
#include <vector>

#include "util/errors.h"

namespace radkit {

/// Throws InputError naming path unless it is a regular file (FIFOs and devices hang readers).
void requireRegularFile(const std::string& path, const std::string& what);

/// The MTL files an OBJ line "mtllib ..." names (`tokens`: the line's tokens, "mtllib" first),
/// relative to `objDir`. The names joined by one space are one file name when a file of that
/// whole name exists (exporters write "mtllib 247_House 15_obj.mtl" for a name with a space);
/// otherwise each is a name, a backslash escaping the next character as tinyobjloader reads
/// them.
std::vector<std::string> mtllibFiles(const std::string& objDir,
                                     const std::vector<std::string>& tokens);

/// The triangles of a PLY's "tristrips" element (OpenMesh reads none of them): each strip
/// a, b, c, d, ... gives (a, b, c), (c, b, d), ... alternating so all share one winding; -1
/// restarts a strip, and the degenerate triangles strips use as joins are dropped.
std::vector<std::vector<int>> plyStripTriangles(const std::string& path);

/// \brief Throws InputError naming path, the line or element, and the fix when an OBJ (and the
///        MTL files it names), OFF, PLY or STL file is malformed. Returns the number of faces
///        the file declares (OFF, PLY, STL), or -1 where it declares none (OBJ).
/// \param offText for an ASCII OFF with comments or per-face colours, which OpenMesh's reader
///        misreads: set to the file as it reads it right (one element per line, without
///        comments, each face cut to its indices). Left as it is for any other file.
long long checkMeshStructure(const std::string& path, std::string* offText = nullptr);

}  // namespace radkit
