// SHA-256 through OpenSSL, fed piece by piece: files hashed from disk
// (file_facts.hpp) and uploads hashed as they arrive (put/upload_sink.hpp).
#pragma once

#include <cstddef>
#include <memory>
#include <string>

struct evp_md_ctx_st;

namespace umf::provider {

class Sha256 {
public:
    // Throws std::runtime_error when OpenSSL cannot start the digest.
    Sha256();
    ~Sha256();
    Sha256(const Sha256&) = delete;
    Sha256& operator=(const Sha256&) = delete;

    void update(const void* data, std::size_t size);
    // Lowercase hex; the hasher is used up.
    std::string hex();

private:
    std::unique_ptr<evp_md_ctx_st, void (*)(evp_md_ctx_st*)> ctx_;
};

}  // namespace umf::provider
