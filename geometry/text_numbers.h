// Checks the numbers of text mesh files before a reader parses them. OpenMesh's and
// tinyobjloader's text readers turn "nan", "1,5" or "1e999" into 0, a truncated value or a
// misleading parse error; this names the file, the line and the token instead. Internal to
// geometry/.
#pragma once

#include <string>

#include "util/errors.h"

namespace radkit {

/// \brief Throws InputError naming path, line and token when a number field of a text OBJ, MTL
///        (Kd, Ke), OFF, ASCII PLY or ASCII STL file is not a finite decimal number. Binary PLY,
///        OFF and STL are left alone: their values are checked after reading (validation.h).
void checkTextMeshNumbers(const std::string& path);

}  // namespace radkit
