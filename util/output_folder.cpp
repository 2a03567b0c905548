#include "util/output_folder.h"

#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <system_error>

namespace radkit {

namespace fs = std::filesystem;

OutputFolder::OutputFolder(std::string destination) : m_destination(std::move(destination)) {
  fs::path dest = fs::absolute(m_destination).lexically_normal();
  if (dest.filename().empty()) dest = dest.parent_path();
  fs::path parent = dest.parent_path();
  std::error_code ec;
  fs::create_directories(parent, ec);
  if (ec) throw std::runtime_error("cannot create the folder " + parent.string() + ": " + ec.message());
  m_staging = (parent / ("." + dest.filename().string() + ".partial-" + std::to_string(::getpid()))).string();
  fs::remove_all(m_staging, ec);
  fs::create_directories(m_staging, ec);
  if (ec) throw std::runtime_error("cannot create the staging folder " + m_staging + ": " + ec.message());
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
  fs::create_directories(m_destination);
  for (const std::string& name : m_names) {
    fs::path from = fs::path(m_staging) / name;
    if (!fs::exists(from)) continue;
    fs::path to = fs::path(m_destination) / name;
    fs::rename(from, to);
    done.push_back(to.string());
  }
  m_committed = true;
  return done;
}

std::string csvField(const std::string& text) {
  if (text.find_first_of(",\"\r\n") == std::string::npos) return text;
  std::string quoted = "\"";
  for (char c : text) quoted += (c == '"') ? std::string("\"\"") : std::string(1, c);
  return quoted + "\"";
}

void writeFileAtomically(const std::string& path, const std::string& text) {
  std::string tmp = path + ".tmp";
  {
    std::ofstream out(tmp, std::ios::binary);
    if (!out) throw std::runtime_error("cannot write " + tmp);
    out << text;
    if (!out) throw std::runtime_error("error while writing " + tmp);
  }
  fs::rename(tmp, path);
}

}  // namespace radkit
