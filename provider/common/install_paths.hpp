// Where the provider finds what it ships: installed, under PREFIX/share/umf
// (found from the program's own place, /proc/self/exe, so any prefix
// works); run from a build, in the source and build trees.
#pragma once

#include <filesystem>
#include <optional>
#include <string>

namespace umf::provider {

// The running program's file, and its folder; empty when the system does
// not say.
std::filesystem::path program_path();
std::filesystem::path program_dir();

// PREFIX/share/umf for a program in PREFIX/bin; empty when the program does
// not say where it is.
std::filesystem::path installed_share_dir();

// The shipped fields (b4-64x36.json, ...). Throws std::runtime_error naming
// where it looked when neither an installed nor a built tree has them.
std::filesystem::path shipped_fields_dir();
// The phone page (index.html and the detector), or nullopt when none is there.
std::optional<std::filesystem::path> web_site_dir();
// The browser extension's files (manifest.json, ...), or nullopt.
std::optional<std::filesystem::path> browser_extension_dir();

// One line per place the provider takes something from, for `--version --verbose`.
std::string install_paths_report();

}  // namespace umf::provider
