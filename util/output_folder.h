// OutputFolder: a run's files appear all together or not at all.
#pragma once

#include <string>
#include <vector>

namespace radkit {

/// Files are written into a hidden staging folder beside the destination; commit() renames
/// each into the destination (created if needed). A folder destroyed before commit() removes
/// its staging folder, so a failed run leaves no partial output behind.
class OutputFolder {
 public:
  explicit OutputFolder(std::string destination);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  /// Path to write the file `name` to (inside the staging folder).
  std::string path(const std::string& name);
  /// Moves every staged file into the destination; returns their final paths.
  std::vector<std::string> commit();
  const std::string& destination() const { return m_destination; }

 private:
  std::string m_destination;
  std::string m_staging;
  std::vector<std::string> m_names;
  bool m_committed = false;
};

/// A CSV field as RFC 4180 wants it: quoted, with inner quotes doubled, when it contains a
/// comma, a quote or a line break; unchanged otherwise.
std::string csvField(const std::string& text);

/// Writes `text` to `path` through a temporary file in the same folder and a rename.
void writeFileAtomically(const std::string& path, const std::string& text);

}  // namespace radkit
