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
/// The marker file of an output folder: a fixed first line, then one entry name per line.
inline constexpr const char* kOutputMarker = ".radkit-output";

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

/// Records `path`, a file radkit just wrote into a marked output folder (a viewer screenshot,
/// say), in that folder's marker, so a later run may replace it. Does nothing elsewhere.
void registerOutputFile(const std::string& path);

/// Throws std::runtime_error naming `option` for an output path that exists and is not a
/// regular file or a symlink to one: a device, a FIFO or a folder. Writing a
/// temporary file and renaming it onto such a path would replace the device node or block.
void checkRegularOutput(const std::string& option, const std::string& path);

/// Refuses a file output (an image, a report) whose path is empty, an existing folder, not a
/// regular file, or in a folder that does not exist, before any work is done; throws InputError
/// naming the option.
void checkOutputFile(const std::string& option, const std::string& path);

/// Writes `text` to `path` through a temporary file in the same folder and a rename.
void writeFileAtomically(const std::string& path, const std::string& text);

/// \brief The same for a file too large to build in memory (a symlink to a regular file is
/// written through: its target is replaced, the link kept; other non-regular targets are
/// refused): `write` streams into FILE.tmp
/// (buffered), which is renamed when complete and removed on an error or exception.
void writeFileStreaming(const std::string& path, const std::function<void(std::ostream&)>& write);

}  // namespace radkit
