#include "provider/service/pairing.hpp"

#include "shared/protocol/pairing_url.hpp"

#include <openssl/crypto.h>
#include <openssl/evp.h>
#include <openssl/rand.h>

#include <stdexcept>

#include "provider/common/config_dir.hpp"

namespace umf::provider {

std::string make_token() {
    unsigned char bytes[kTokenRandomBytes];
    if (RAND_bytes(bytes, sizeof bytes) != 1) throw std::runtime_error("the random generator failed");
    return base64url(bytes, sizeof bytes);
}

namespace {

bool is_token(std::string_view s) {
    if (s.size() < 22 || s.size() > 128) return false;
    for (char c : s)
        if (!((c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '-' || c == '_'))
            return false;
    return true;
}

}  // namespace

std::string load_or_create_token(const std::filesystem::path& dir, bool rotate) {
    ensure_config_dir(dir);
    const auto path = dir / kTokenFile;
    if (!rotate) {
        if (auto text = read_small_file(path, 4096)) {
            while (!text->empty() && (text->back() == '\n' || text->back() == '\r' || text->back() == ' '))
                text->pop_back();
            if (is_token(*text)) return *text;
        }
    }
    std::string token = make_token();
    write_private_file(path, token + "\n");
    return token;
}

std::string pairing_url(const std::string& host, unsigned short port, const std::string& token,
                        const std::string& fingerprint, const std::string& local_name) {
    return protocol::format_pairing_url(host, port, token, fingerprint, local_name);
}

}  // namespace umf::provider
