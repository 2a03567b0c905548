// Settings named in library messages. A library names a setting by its key ("max_area"); the
// front end that shows the message spells it: the command line as its flag ("--max-area", the
// default), the Python module as its keyword ("max_area="). So "Fix: raise --max-iterations"
// reaches a Python user as "Fix: raise max_iterations=", and no library speaks in flag words.
#pragma once

#include <string>

namespace radkit {

/// Spells a setting's key for the user.
using SettingSpeller = std::string (*)(const std::string& key);

/// \brief The key as the current front end spells it; by default the command line's flag,
///        "--" followed by the key with '_' turned into '-'.
std::string setting(const std::string& key);

/// \brief The command line's spelling of a key ("max_area" -> "--max-area").
std::string flagSpelling(const std::string& key);

/// \brief Installs a front end's speller (nullptr restores the flags). Call once at start,
///        before any work runs on other threads.
void setSettingSpeller(SettingSpeller speller);

}  // namespace radkit
