#pragma once
// A file's whole text, read in one place for every file the product takes in (programs, cell
// YAMLs, scenario and line files, recordings, the monitor's page).
#include <optional>
#include <string>

namespace plc_cell {

// Every byte of the file at path, as stored; nullopt when it cannot be opened or a read
// fails (why_unreadable in unreadable.h says why, in words to act on).
std::optional<std::string> file_text(const std::string& path);

}  // namespace plc_cell
