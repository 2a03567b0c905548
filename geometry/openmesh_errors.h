// OpenMesh's error stream captured, so its complaints reach the user in radkit's words with the
// file and the element, not as stray console lines. Internal to geometry/.
#pragma once

#include <OpenMesh/Core/System/omstream.hh>

#include <sstream>
#include <string>

namespace radkit {

/// Routes OpenMesh's error stream into a string for the duration of a read (or a build), so its
/// complaints become part of our message instead of stray console lines. Swaps the stream's
/// buffer: OpenMesh's disconnect() never frees the target that connect() allocated.
class CapturedOpenMeshErrors {
 public:
  CapturedOpenMeshErrors() : m_saved(omerr().rdbuf(&m_text)) {}
  ~CapturedOpenMeshErrors() { omerr().rdbuf(m_saved); }
  CapturedOpenMeshErrors(const CapturedOpenMeshErrors&) = delete;
  CapturedOpenMeshErrors& operator=(const CapturedOpenMeshErrors&) = delete;
  std::string text() const { return m_text.str(); }

 private:
  std::stringbuf m_text;
  std::streambuf* m_saved;
};

}  // namespace radkit
