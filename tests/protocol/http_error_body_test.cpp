#include "shared/protocol/http_error_body.hpp"

#include <gtest/gtest.h>

#include <string>

namespace p = umf::protocol;

TEST(HttpErrorBody, WhatIsWrittenIsRead) {
    const p::Error error{std::nullopt, p::ErrorCode::not_found, "unknown, used or expired download link"};
    const std::string body = p::encode_error_body(error);
    EXPECT_EQ(body.rfind("{\"messages\":[{", 0), 0u) << body;
    const auto back = p::parse_error_body(body);
    ASSERT_TRUE(back);
    EXPECT_EQ(*back, error);
}

TEST(HttpErrorBody, AnythingElseIsNoError) {
    EXPECT_FALSE(p::parse_error_body(""));
    EXPECT_FALSE(p::parse_error_body("<html>502 Bad Gateway</html>"));
    EXPECT_FALSE(p::parse_error_body("{\"messages\":[]}"));
    // The old bare shape is not the envelope.
    EXPECT_FALSE(p::parse_error_body(p::encode(p::Error{std::nullopt, p::ErrorCode::internal, "x"})));
    // Two messages, or one that is not an error.
    const std::string e = p::encode(p::Error{std::nullopt, p::ErrorCode::internal, "x"});
    EXPECT_FALSE(p::parse_error_body("{\"messages\":[" + e + "," + e + "]}"));
    EXPECT_FALSE(p::parse_error_body("{\"messages\":[{\"type\":\"welcome\"}]}"));
    EXPECT_FALSE(p::parse_error_body(std::string(100000, '[')));
}
