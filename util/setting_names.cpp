#include "util/setting_names.h"

namespace radkit {

namespace {
SettingSpeller g_speller = nullptr;
}  // namespace

std::string flagSpelling(const std::string& key) {
  std::string flag = "--" + key;
  for (char& c : flag)
    if (c == '_') c = '-';
  return flag;
}

std::string setting(const std::string& key) {
  return g_speller ? g_speller(key) : flagSpelling(key);
}

void setSettingSpeller(SettingSpeller speller) { g_speller = speller; }

}  // namespace radkit
