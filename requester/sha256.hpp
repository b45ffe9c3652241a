// SHA-256 as the requester checks downloads and announces puts: OpenSSL's,
// fed piece by piece, so no file is ever held whole in memory.
#pragma once

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>

#include <openssl/evp.h>

namespace umf::requester {

class Sha256 {
public:
    Sha256();
    void update(const void* data, std::size_t size);
    // 64 lowercase hex digits; the object is used up.
    std::string hex();

private:
    std::unique_ptr<EVP_MD_CTX, void (*)(EVP_MD_CTX*)> ctx_;
};

struct FileDigest {
    std::int64_t size = 0;
    std::string sha256;
};

// The size and SHA-256 of a regular file, read once. Throws
// std::runtime_error naming the file when it cannot be read or is not a
// regular file.
FileDigest digest_file(const std::filesystem::path& file);

}  // namespace umf::requester
