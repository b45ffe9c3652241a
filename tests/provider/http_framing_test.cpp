// Requests whose body could be delimited two ways (RFC 9112, 6.1 and 6.3)
// are answered 400 and the connection closed: a second request hidden in
// such a body is never served, whatever stands in front of the provider.
#ifdef UMF_PROVIDER_TESTS

#include "provider/net/http_framing.hpp"

#include <gtest/gtest.h>

#include <string>

#include "provider/service/service.hpp"
#include "provider/service/service_server.hpp"
#include "provider/trust/tls_identity_store.hpp"
#include "shared/protocol/http_error_body.hpp"
#include "tests/support/raw_tls_client.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

namespace http = boost::beast::http;
using umf::provider::ambiguous_framing;

http::fields fields(std::initializer_list<std::pair<const char*, const char*>> list) {
    http::fields f;
    for (const auto& [name, value] : list) f.insert(name, value);
    return f;
}

TEST(HttpFraming, OnlyOneWayToDelimitABodyIsTaken) {
    EXPECT_FALSE(ambiguous_framing(11, fields({})));
    EXPECT_FALSE(ambiguous_framing(11, fields({{"Content-Length", "12"}})));
    EXPECT_FALSE(ambiguous_framing(11, fields({{"Transfer-Encoding", "chunked"}})));
    EXPECT_FALSE(ambiguous_framing(11, fields({{"Transfer-Encoding", " Chunked ,"}})));
    EXPECT_FALSE(ambiguous_framing(10, fields({{"Content-Length", "3"}})));

    EXPECT_TRUE(ambiguous_framing(11, fields({{"Transfer-Encoding", "chunked"}, {"Content-Length", "5"}})));
    EXPECT_TRUE(ambiguous_framing(11, fields({{"Transfer-Encoding", "chunked, identity"}})));
    EXPECT_TRUE(ambiguous_framing(11, fields({{"Transfer-Encoding", "xchunked"}})));
    EXPECT_TRUE(ambiguous_framing(11, fields({{"Transfer-Encoding", "gzip, chunked"}})));
    EXPECT_TRUE(ambiguous_framing(11, fields({{"Transfer-Encoding", "chunked"}, {"Transfer-Encoding", "chunked"}})));
    EXPECT_TRUE(ambiguous_framing(11, fields({{"Transfer-Encoding", ""}})));
    EXPECT_TRUE(ambiguous_framing(11, fields({{"Content-Length", "5"}, {"Content-Length", "5"}})));
    EXPECT_TRUE(ambiguous_framing(10, fields({{"Transfer-Encoding", "chunked"}})));
}

class HttpFramingServer : public ::testing::Test {
protected:
    umf::test::TempDir dir;
    std::unique_ptr<umf::provider::Server> server;
    void SetUp() override {
        auto service = std::make_shared<umf::provider::Service>(umf::provider::default_service_config(),
                                                                "framing-test-token-0123456789");
        server = umf::provider::make_server(
            service, umf::provider::load_or_create_tls_identity(dir.path / "cfg"));
        server->start();
    }
    // How many answers `received` holds: status lines at a line's start.
    static int answers(const std::string& received) {
        int n = received.rfind("HTTP/1.1 ", 0) == 0 ? 1 : 0;
        for (std::size_t at = received.find("\nHTTP/1.1 "); at != std::string::npos;
             at = received.find("\nHTTP/1.1 ", at + 1))
            ++n;
        return n;
    }
};

TEST_F(HttpFramingServer, ASmuggledRequestIsNeverServed) {
    // A body that, read by its Content-Length, holds a second request.
    const std::string hidden = "GET / HTTP/1.1\r\nHost: x\r\n\r\n";
    const std::string body = "{}" + hidden;
    for (const std::string encoding : {"chunked, identity", "xchunked", "chunked"}) {
        const std::string request = "POST /api/hello HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\n"
                                    "Transfer-Encoding: " + encoding + "\r\nContent-Length: " +
                                    std::to_string(body.size()) + "\r\n\r\n" + body;
        const auto got = umf::test::raw_tls_exchange(server->port(), request);
        SCOPED_TRACE(encoding);
        EXPECT_TRUE(got.closed) << "the connection must close after the answer";
        EXPECT_EQ(got.received.rfind("HTTP/1.1 400 ", 0), 0u) << got.received;
        EXPECT_EQ(answers(got.received), 1) << "the hidden request was served:\n" << got.received;
        const auto error = umf::protocol::parse_error_body(got.received.substr(got.received.find("\r\n\r\n") + 4));
        ASSERT_TRUE(error) << got.received;
        EXPECT_EQ(error->code, umf::protocol::ErrorCode::bad_request);
    }
}

TEST_F(HttpFramingServer, AnHttp10RequestWithTransferEncodingIsRefused) {
    const auto got = umf::test::raw_tls_exchange(
        server->port(), "GET / HTTP/1.0\r\nTransfer-Encoding: chunked\r\n\r\n0\r\n\r\nGET / HTTP/1.1\r\nHost: x\r\n\r\n");
    EXPECT_TRUE(got.closed);
    EXPECT_NE(got.received.find(" 400 "), std::string::npos) << got.received;
    EXPECT_EQ(answers(got.received), 1) << got.received;
}

TEST_F(HttpFramingServer, APlainChunkedRequestIsStillServed) {
    const std::string message = R"({"type":"hello","v":1,"token":"wrong-token-00000000000000","client":"t"})";
    char size[16];
    std::snprintf(size, sizeof size, "%zx", message.size());
    const auto got = umf::test::raw_tls_exchange(
        server->port(), "POST /api/hello HTTP/1.1\r\nHost: x\r\nContent-Type: application/json\r\n"
                        "Transfer-Encoding: chunked\r\nConnection: close\r\n\r\n" +
                            std::string(size) + "\r\n" + message + "\r\n0\r\n\r\n");
    EXPECT_EQ(got.received.rfind("HTTP/1.1 200 ", 0), 0u) << got.received;
    EXPECT_NE(got.received.find("unauthorized"), std::string::npos) << got.received;
}

}  // namespace

#endif
