// The native library's SHA-256 and certificate fingerprint, against the
// standard's test vectors (FIPS 180-2, appendix B).
#if defined(UMF_PROVIDER_TESTS)

#include <gtest/gtest.h>

#include <string>

#include "native/certificate_fingerprint.hpp"
#include "native/sha256.hpp"

namespace {

using umf::native::der_fingerprint;
using umf::native::Sha256;

TEST(NativeSha256, TheStandardsVectorsPieceByPiece) {
    Sha256 abc;
    abc.update("a", 1);
    abc.update("bc", 2);
    EXPECT_EQ(abc.hex(), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    Sha256 empty;
    EXPECT_EQ(empty.hex(), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
    const std::string million(1000000, 'a');
    Sha256 many;
    for (std::size_t i = 0; i < million.size(); i += 4096) many.update(million.data() + i, std::min<std::size_t>(4096, million.size() - i));
    EXPECT_EQ(many.hex(), "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

TEST(NativeSha256, AFingerprintIsTheDersHashAndNoCertificateHasNone) {
    const unsigned char der[3] = {'a', 'b', 'c'};
    EXPECT_EQ(der_fingerprint(der, 3), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
    EXPECT_EQ(umf::native::certificate_fingerprint(nullptr), "");
}

}  // namespace

#endif
