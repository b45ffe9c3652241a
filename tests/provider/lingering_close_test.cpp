// A request refused before its body was read still hears why: the provider
// answers, then reads and drops what the client is still sending until it
// closes, so the close is not a reset that destroys the answer on its way.
#ifdef UMF_PROVIDER_TESTS

#include <gtest/gtest.h>

#include <string>

#include "provider/service/service.hpp"
#include "provider/service/service_server.hpp"
#include "provider/trust/tls_identity_store.hpp"
#include "shared/protocol/http_error_body.hpp"
#include "tests/support/raw_tls_client.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

using namespace umf::provider;

TEST(LingeringClose, ABodyTooLargeSentAtOnceStillGetsIts413) {
    umf::test::TempDir dir;
    auto service = std::make_shared<Service>(default_service_config(), "linger-test-token-0123456789");
    const auto server = make_server(service, load_or_create_tls_identity(dir.path / "cfg"));
    server->start();
    const std::string body(8 << 20, 'x');
    for (int attempt = 0; attempt < 5; ++attempt) {
        const auto got = umf::test::raw_tls_exchange(
            server->port(), "POST /api/hello HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\nContent-Length: " +
                               std::to_string(body.size()) + "\r\n\r\n" + body);
        SCOPED_TRACE("attempt " + std::to_string(attempt) + ", write: " + got.write_error);
        ASSERT_EQ(got.received.rfind("HTTP/1.1 413 ", 0), 0u) << got.received;
        const auto error = umf::protocol::parse_error_body(got.received.substr(got.received.find("\r\n\r\n") + 4));
        ASSERT_TRUE(error) << got.received;
        EXPECT_EQ(error->code, umf::protocol::ErrorCode::too_large);
        EXPECT_TRUE(got.closed);
    }
    EXPECT_EQ(umf::test::raw_tls_exchange(server->port(), "GET / HTTP/1.1\r\nHost: x\r\nConnection: close\r\n\r\n")
                  .received.rfind("HTTP/1.1 200 ", 0),
              0u)
        << "the provider serves on";
}

}  // namespace

#endif
