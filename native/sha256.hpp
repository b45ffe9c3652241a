// SHA-256 through OpenSSL, fed piece by piece so no file is ever held whole:
// the provider's files and uploads, the requester's downloads and puts.
#pragma once

#include <cstddef>
#include <memory>
#include <string>

struct evp_md_ctx_st;

namespace umf::native {

class Sha256 {
public:
    // Throws std::runtime_error when OpenSSL cannot start the digest.
    Sha256();
    ~Sha256();
    Sha256(const Sha256&) = delete;
    Sha256& operator=(const Sha256&) = delete;

    void update(const void* data, std::size_t size);
    // A hasher in the same state, to go on from here apart from this one (a
    // resumed download's checkpoint). Throws std::runtime_error as the
    // constructor does.
    std::unique_ptr<Sha256> copy() const;
    // 64 lowercase hex digits; the hasher is used up.
    std::string hex();

private:
    std::unique_ptr<evp_md_ctx_st, void (*)(evp_md_ctx_st*)> ctx_;
};

// Lowercase hex of `size` bytes.
std::string to_hex(const unsigned char* bytes, std::size_t size);

}  // namespace umf::native
