// The provider's configuration directory and the private files in it (the
// TLS key, the pairing token): readable by the user only.
#pragma once

#include <cstddef>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>

namespace umf::provider {

class ConfigError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// $XDG_CONFIG_HOME/umf, or ~/.config/umf when XDG_CONFIG_HOME is unset or
// not absolute. Throws ConfigError when neither variable helps.
std::filesystem::path default_config_dir();

// Creates the directory (and its parents) when missing; a directory it
// creates is 0700. Throws ConfigError.
void ensure_config_dir(const std::filesystem::path& dir);

// Writes through a temporary file created 0600 beside `path`, fsync and a
// rename, so the file is never readable by others nor left half-written.
// Throws ConfigError.
void write_private_file(const std::filesystem::path& path, const std::string& bytes);

// The file's contents; nullopt when it does not exist. Throws ConfigError
// when it exists but cannot be read or is larger than max_bytes.
std::optional<std::string> read_small_file(const std::filesystem::path& path, std::size_t max_bytes = 64 * 1024);

}  // namespace umf::provider
