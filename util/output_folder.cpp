#include "util/output_folder.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <optional>
#include <stdexcept>
#include <system_error>

#include "util/errors.h"
#include "util/setting_names.h"

namespace radkit {

namespace fs = std::filesystem;

namespace {

/// Removes `.NAME.partial-PID` and `.NAME.old-PID` folders whose process has ended: a kill or
/// a crash skips the destructor and commit() that would have removed them.
void removeStaleStaging(const fs::path& parent, const std::string& name) {
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(parent, ec)) {
    const std::string file = entry.path().filename().string();
    for (const std::string& prefix : {"." + name + ".partial-", "." + name + ".old-"}) {
      if (file.size() <= prefix.size() || file.compare(0, prefix.size(), prefix) != 0) continue;
      const std::string pid = file.substr(prefix.size());
      if (pid.size() > 9 ||
          !std::all_of(pid.begin(), pid.end(), [](unsigned char c) { return std::isdigit(c); }))
        continue;
      if (::kill(pid_t(std::stol(pid)), 0) != 0 && errno == ESRCH) fs::remove_all(entry.path(), ec);
    }
  }
}

constexpr const char* kMarkerHeader =
    "radkit output folder: radkit replaces this folder only if it holds nothing but the "
    "entries listed below";

/// The entries a valid marker lists, or nullopt if `dir` has no marker radkit wrote.
std::optional<std::vector<std::string>> markedEntries(const fs::path& dir) {
  const fs::path marker = dir / kOutputMarker;
  std::error_code ec;
  if (fs::is_symlink(marker, ec) || !fs::is_regular_file(marker, ec)) return std::nullopt;
  std::ifstream in(marker);
  std::string line;
  if (!std::getline(in, line) || line != kMarkerHeader) return std::nullopt;
  std::vector<std::string> names;
  while (std::getline(in, line))
    if (!line.empty()) names.push_back(line);
  return names;
}

/// Why commit() may not replace `dir`, or "" if it may: the folder is empty, or radkit marked
/// it and it holds only the entries the marker lists. Anything else may be the user's own.
std::string notReplaceable(const fs::path& dir) {
  if (fs::is_empty(dir)) return "";
  const auto listed = markedEntries(dir);
  if (!listed)
    return dir.string() + " exists and radkit did not mark it as its output (no valid " +
           std::string(kOutputMarker) +
           " file), and an output folder is replaced whole. Fix: choose another " + setting("out") +
           ", or "
           "empty or remove that folder (an output of an older radkit has no marker: remove it).";
  for (const auto& entry : fs::directory_iterator(dir)) {
    const std::string name = entry.path().filename().string();
    if (name != kOutputMarker && std::find(listed->begin(), listed->end(), name) == listed->end())
      return dir.string() + " holds " + name +
             ", which radkit did not write, and an output folder is replaced whole. Fix: move " +
             name + " out of it, or choose another " + setting("out") + ".";
  }
  return "";
}

}  // namespace

OutputFolder::OutputFolder(std::string destination) : m_destination(std::move(destination)) {
  if (m_destination.empty())
    throw std::runtime_error("the output folder (" + setting("out") +
                             ") is empty. Fix: give a folder name, e.g. " + setting("out") +
                             " out/run1");
  fs::path dest = fs::absolute(m_destination).lexically_normal();
  if (dest.filename().empty()) dest = dest.parent_path();
  // The folder is replaced whole: `--out .` would move the working folder away under the shell.
  std::error_code ec;
  const fs::path cwd = fs::current_path(ec);
  const auto [end, rest] = std::mismatch(dest.begin(), dest.end(), cwd.begin(), cwd.end());
  if (dest == dest.root_path() || (!ec && end == dest.end()))
    throw std::runtime_error(setting("out") + " " + m_destination +
                             " is the working folder or contains it, and an output "
                             "folder is replaced whole. Fix: give a new folder name, e.g. " +
                             setting("out") + " out/run1");
  m_destination = dest.string();
  fs::path parent = dest.parent_path();
  if (fs::exists(dest) && !fs::is_directory(dest))
    throw std::runtime_error(dest.string() +
                             " exists and is not a folder, and an output folder is replaced "
                             "whole. Fix: choose another " +
                             setting("out") + ".");
  if (fs::exists(dest))
    if (const std::string why = notReplaceable(dest); !why.empty()) throw std::runtime_error(why);
  fs::create_directories(parent, ec);
  if (ec)
    throw std::runtime_error("cannot create the folder " + parent.string() + ": " + ec.message());
  removeStaleStaging(parent, dest.filename().string());
  m_staging = (parent / ("." + dest.filename().string() + ".partial-" + std::to_string(::getpid())))
                  .string();
  fs::remove_all(m_staging, ec);
  fs::create_directories(m_staging, ec);
  if (ec)
    throw std::runtime_error("cannot create the staging folder " + m_staging + ": " + ec.message());
}

OutputFolder::~OutputFolder() {
  std::error_code ec;
  fs::remove_all(m_staging, ec);
}

std::string OutputFolder::path(const std::string& name) {
  m_names.push_back(name);
  return (fs::path(m_staging) / name).string();
}

std::vector<std::string> OutputFolder::commit() {
  std::vector<std::string> done;
  for (const std::string& name : m_names)
    if (fs::exists(fs::path(m_staging) / name))
      done.push_back((fs::path(m_destination) / name).string());
  // The marker lists what radkit wrote, so a later run replaces this folder only while it
  // holds nothing else.
  {
    std::vector<std::string> entries;
    for (const auto& entry : fs::directory_iterator(m_staging))
      entries.push_back(entry.path().filename().string());
    std::sort(entries.begin(), entries.end());
    std::string text = std::string(kMarkerHeader) + "\n";
    for (const std::string& e : entries) text += e + "\n";
    writeFileAtomically((fs::path(m_staging) / kOutputMarker).string(), text);
  }
  // A folder changed since the constructor checked it (a user's file saved into it while
  // the run worked) is still not replaced.
  if (fs::exists(m_destination))
    if (const std::string why = notReplaceable(m_destination); !why.empty())
      throw std::runtime_error(why);
  // One rename publishes the whole folder; an earlier one is moved aside first and removed
  // after, so the destination never holds a mix of two runs or part of one.
  const fs::path dest(m_destination);
  fs::path aside;
  std::error_code ec;
  if (fs::exists(dest)) {
    aside = dest.parent_path() /
            ("." + dest.filename().string() + ".old-" + std::to_string(::getpid()));
    fs::remove_all(aside, ec);
    fs::rename(dest, aside);
  }
  try {
    fs::rename(m_staging, dest);
  } catch (...) {
    if (!aside.empty()) fs::rename(aside, dest, ec);
    throw;
  }
  m_committed = true;
  if (!aside.empty()) fs::remove_all(aside, ec);
  return done;
}

std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

void registerOutputFile(const std::string& path) {
  const fs::path file = fs::absolute(path);
  const fs::path dir = file.parent_path();
  auto listed = markedEntries(dir);
  const std::string name = file.filename().string();
  if (!listed || std::find(listed->begin(), listed->end(), name) != listed->end()) return;
  listed->push_back(name);
  std::string text = std::string(kMarkerHeader) + "\n";
  for (const std::string& e : *listed) text += e + "\n";
  writeFileAtomically((dir / kOutputMarker).string(), text);
}

void checkRegularOutput(const std::string& option, const std::string& path) {
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);  // follows symlinks
  if (ec || !fs::exists(st) || fs::is_regular_file(st)) return;
  const char* kind = fs::is_directory(st)        ? "a folder"
                     : fs::is_fifo(st)           ? "a named pipe (FIFO)"
                     : fs::is_character_file(st) ? "a character device"
                     : fs::is_block_file(st)     ? "a block device"
                     : fs::is_socket(st)         ? "a socket"
                                                 : "not a regular file";
  throw std::runtime_error(
      (option.empty() ? "" : option + " ") + path + " is " + kind +
      (fs::is_symlink(fs::symlink_status(path, ec)) ? " (through a symlink)" : "") +
      "; radkit writes only regular files, through a temporary file and a rename that would "
      "replace it. Fix: give the path of a regular file or a new one.");
}

void writeFileStreaming(const std::string& given, const std::function<void(std::ostream&)>& write) {
  checkRegularOutput("", given);
  // A symlink is written through: the temporary file goes beside its target, and the rename
  // replaces the target, not the link.
  std::error_code ec;
  const std::string path =
      fs::is_symlink(fs::symlink_status(given, ec)) ? fs::weakly_canonical(given).string() : given;
  const std::string tmp = path + ".tmp";
  {
    std::vector<char> buffer(1 << 20);  // large writes, not one per line; outlives `out`
    std::ofstream out;
    out.rdbuf()->pubsetbuf(buffer.data(), std::streamsize(buffer.size()));
    out.open(tmp, std::ios::binary);
    if (!out)
      throw std::runtime_error("cannot write " + tmp +
                               ". Fix: check that its folder exists and is writable");
    try {
      write(out);
      out.flush();
    } catch (...) {
      out.close();
      fs::remove(tmp);
      throw;
    }
    if (!out) {
      out.close();
      fs::remove(tmp);
      throw std::runtime_error("error while writing " + tmp + " (disk full?)");
    }
  }
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp);
    throw std::runtime_error("cannot replace " + path + ": " + ec.message());
  }
}

void writeFileAtomically(const std::string& path, const std::string& text) {
  writeFileStreaming(path, [&](std::ostream& out) { out << text; });
}

void checkOutputFile(const std::string& option, const std::string& path) {
  if (path.empty()) throw InputError(option + " is empty. Fix: give a file name");
  if (fs::is_directory(path))
    throw InputError(option + " " + path + " is a folder. Fix: give a file name inside it, e.g. " +
                     (fs::path(path) / "image.png").string());
  try {
    checkRegularOutput(option, path);
  } catch (const std::runtime_error& e) {
    throw InputError(e.what());
  }
  const fs::path parent = fs::path(path).parent_path();
  if (!parent.empty() && !fs::is_directory(parent))
    throw InputError(option + " " + path + ": folder " + parent.string() +
                     " does not exist. Fix: create it or write elsewhere");
}

}  // namespace radkit
