// OutputFolder: a run's files appear all together or not at all.
#pragma once

#include <functional>
#include <ostream>
#include <string>
#include <vector>

namespace radkit {

/// Files are written into a hidden staging folder `.NAME.partial-PID` beside the destination;
/// commit() renames that folder to the destination in one step, replacing an earlier output
/// folder (moved aside to `.NAME.old-PID`, then removed). A folder destroyed before commit()
/// removes its staging folder, so a failed run leaves no partial output behind; staging
/// folders of processes that were killed are removed by the next OutputFolder of that name.
/// An existing destination that radkit did not write (non-empty, none of report.json,
/// patches.csv, study.csv) is refused by the constructor rather than deleted.
class OutputFolder {
 public:
  explicit OutputFolder(std::string destination);
  ~OutputFolder();
  OutputFolder(const OutputFolder&) = delete;
  OutputFolder& operator=(const OutputFolder&) = delete;

  /// Path to write the file `name` to (inside the staging folder).
  std::string path(const std::string& name);
  /// Publishes the staged folder as the destination; returns the final paths of the files.
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

/// \brief The same for a file too large to build in memory: `write` streams into FILE.tmp
/// (buffered), which is renamed when complete and removed on an error or exception.
void writeFileStreaming(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace radkit
