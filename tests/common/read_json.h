// report.json and other JSON outputs read back by the end-to-end tests.
#pragma once

#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

namespace radkit::test {

inline nlohmann::json readJson(const std::string& path) {
  std::ifstream in(path);
  return nlohmann::json::parse(in);
}

}  // namespace radkit::test
