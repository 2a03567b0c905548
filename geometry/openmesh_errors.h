// OpenMesh's error stream captured, so its complaints reach the user in radkit's words with the
// file and the element, not as stray console lines. Internal to geometry/.
#pragma once

#include <OpenMesh/Core/System/omstream.hh>

#include <algorithm>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

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
  /// What OpenMesh said, one clause per distinct line ("; "-joined), a repeated line once
  /// with its count: a bad file can make it say the same thing once per face.
  std::string text() const {
    std::istringstream lines(m_text.str());
    std::vector<std::pair<std::string, int>> seen;
    for (std::string line; std::getline(lines, line);) {
      while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
      if (line.empty()) continue;
      auto it =
          std::find_if(seen.begin(), seen.end(), [&](const auto& s) { return s.first == line; });
      if (it == seen.end())
        seen.emplace_back(line, 1);
      else
        ++it->second;
    }
    std::string out;
    for (const auto& [line, count] : seen)
      out += (out.empty() ? "" : "; ") + line +
             (count > 1 ? " (" + std::to_string(count) + " times)" : "");
    return out;
  }

 private:
  std::stringbuf m_text;
  std::streambuf* m_saved;
};

}  // namespace radkit
