#include "util/output_folder.h"

#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

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

/// A folder commit() may replace: empty, or written by radkit (one of the files every command
/// writes). Anything else may be the user's own and is refused rather than deleted.
bool replaceable(const fs::path& dir) {
  if (fs::is_empty(dir)) return true;
  for (const char* file : {"report.json", "patches.csv", "study.csv"})
    if (fs::exists(dir / file)) return true;
  return false;
}

}  // namespace

OutputFolder::OutputFolder(std::string destination) : m_destination(std::move(destination)) {
  if (m_destination.empty())
    throw std::runtime_error(
        "the output folder (--out) is empty. Fix: give a folder name, e.g. --out out/run1");
  fs::path dest = fs::absolute(m_destination).lexically_normal();
  if (dest.filename().empty()) dest = dest.parent_path();
  // The folder is replaced whole: `--out .` would move the working folder away under the shell.
  std::error_code ec;
  const fs::path cwd = fs::current_path(ec);
  const auto [end, rest] = std::mismatch(dest.begin(), dest.end(), cwd.begin(), cwd.end());
  if (dest == dest.root_path() || (!ec && end == dest.end()))
    throw std::runtime_error(
        "--out " + m_destination +
        " is the working folder or contains it, and an output "
        "folder is replaced whole. Fix: give a new folder name, e.g. --out out/run1");
  m_destination = dest.string();
  fs::path parent = dest.parent_path();
  if (fs::exists(dest) && (!fs::is_directory(dest) || !replaceable(dest)))
    throw std::runtime_error(
        dest.string() +
        " exists and is not a radkit output folder (no report.json, "
        "patches.csv or study.csv), and an output folder is replaced whole. Fix: "
        "choose another --out, or empty or remove that folder.");
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

void writeFileStreaming(const std::string& path, const std::function<void(std::ostream&)>& write) {
  if (fs::is_directory(path))
    throw std::runtime_error(
        path + " is a folder, not a file. Fix: give a file name inside it or another path");
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
  std::error_code ec;
  fs::rename(tmp, path, ec);
  if (ec) {
    fs::remove(tmp);
    throw std::runtime_error("cannot replace " + path + ": " + ec.message());
  }
}

void writeFileAtomically(const std::string& path, const std::string& text) {
  writeFileStreaming(path, [&](std::ostream& out) { out << text; });
}

}  // namespace radkit
