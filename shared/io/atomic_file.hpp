// Writing a file so that readers see the old contents or the new, never half.
#pragma once

#include <stdexcept>
#include <string>

namespace umf {

class FileWriteError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// Writes `bytes` to `path` through a temporary file beside it and a rename.
// On failure the temporary file is removed, any existing file is untouched,
// and FileWriteError names the path.
void write_file_atomically(const std::string& path, const std::string& bytes);

}  // namespace umf
