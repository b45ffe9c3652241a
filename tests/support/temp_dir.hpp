// A private temporary folder for one test, removed with everything in it
// when the test ends. Its path is canonical (no symbolic links), so paths a
// program under test prints can be compared with it.
#pragma once

#include <stdlib.h>

#include <filesystem>
#include <stdexcept>
#include <string>

namespace umf::test {

struct TempDir {
    std::filesystem::path path;
    explicit TempDir(const std::string& prefix = "umf-test") {
        std::string tmpl = (std::filesystem::temp_directory_path() / (prefix + "-XXXXXX")).string();
        if (!mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed");
        path = std::filesystem::canonical(tmpl);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
};

}  // namespace umf::test
