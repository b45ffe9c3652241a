#include "shared/protocol/json_checks.hpp"

#include <gtest/gtest.h>

#include <limits>

using namespace umf::protocol;
using nlohmann::json;

namespace {

TEST(ProtocolJsonChecks, Utf8Validation) {
    EXPECT_TRUE(is_valid_utf8(""));
    EXPECT_TRUE(is_valid_utf8("plain"));
    EXPECT_TRUE(is_valid_utf8("\xc3\xa9\xe2\x80\x94\xf0\x9f\x93\xb1"));  // é — 📱
    EXPECT_TRUE(is_valid_utf8("\xf4\x8f\xbf\xbf"));                      // U+10FFFF
    EXPECT_FALSE(is_valid_utf8("\x80"));                                 // lone continuation
    EXPECT_FALSE(is_valid_utf8("\xc3"));                                 // cut short
    EXPECT_FALSE(is_valid_utf8("\xc1\xbf"));                             // overlong
    EXPECT_FALSE(is_valid_utf8("\xe0\x9f\xbf"));                         // overlong
    EXPECT_FALSE(is_valid_utf8("\xed\xa0\x80"));                         // surrogate
    EXPECT_FALSE(is_valid_utf8("\xf4\x90\x80\x80"));                     // above U+10FFFF
    EXPECT_FALSE(is_valid_utf8("\xf5\x80\x80\x80"));
}

TEST(ProtocolJsonChecks, ClipTextKeepsWholeCharacters) {
    EXPECT_EQ(clip_text("abc", 10), "abc");
    EXPECT_EQ(clip_text("abc", 2), "ab");
    EXPECT_EQ(clip_text("a\xc3\xa9", 2), "a");  // é does not fit whole
    EXPECT_EQ(clip_text("a\xc3\xa9", 3), "a\xc3\xa9");
    EXPECT_EQ(clip_text("a\xffz", 10), "a\xef\xbf\xbdz");
    EXPECT_EQ(clip_text("a\xffz", 3), "a");  // the replacement does not fit
    EXPECT_EQ(clip_text("\xc3", 10), "\xef\xbf\xbd");
    EXPECT_TRUE(is_valid_utf8(clip_text("\xe2\x80\x94\xe2\x80", 100)));
}

TEST(ProtocolJsonChecks, NumbersAndIntegers) {
    EXPECT_EQ(finite_number(json(1.5)), 1.5);
    EXPECT_EQ(finite_number(json(-3)), -3.0);
    EXPECT_FALSE(finite_number(json("1")));
    EXPECT_FALSE(finite_number(json(std::numeric_limits<double>::infinity())));
    EXPECT_EQ(integer_in(json(5), 0, 10), 5);
    EXPECT_FALSE(integer_in(json(5.0), 0, 10));
    EXPECT_FALSE(integer_in(json(11), 0, 10));
    EXPECT_FALSE(integer_in(json(std::uint64_t{18446744073709551615u}), 0, INT64_MAX));
    EXPECT_EQ(integer_in(json(-kMaxSafeInteger), -kMaxSafeInteger, 0), -kMaxSafeInteger);
}

TEST(ProtocolJsonChecks, ReaderKeepsTheFirstProblem) {
    json doc = json::parse(R"({"a": "text", "n": 2.5, "i": 3, "o": {}, "arr": [1, 2], "z": null})");
    MemberReader r(doc, "outer");
    EXPECT_EQ(r.text("a", 1, 10), "text");
    EXPECT_EQ(r.number("n", 0, 3), 2.5);
    EXPECT_EQ(r.integer("i", 0, 3), 3);
    EXPECT_NE(r.object("o"), nullptr);
    EXPECT_NE(r.array("arr", 2, 2), nullptr);
    EXPECT_FALSE(r.has("z"));
    EXPECT_FALSE(r.optional_text("z", 0, 1));
    EXPECT_TRUE(r.ok());

    EXPECT_EQ(r.number("a", 0, 1), 0.0);
    EXPECT_FALSE(r.ok());
    EXPECT_EQ(r.problem(), "\"outer.a\" must be a number 0..1, not a string");
    r.text("missing", 0, 1);  // a second problem is not recorded
    EXPECT_EQ(r.problem(), "\"outer.a\" must be a number 0..1, not a string");

    const json array = json::array();
    MemberReader not_object(array, "x");
    EXPECT_EQ(not_object.problem(), "\"x\" must be a JSON object");
    EXPECT_EQ(not_object.text("a", 0, 1), "");

    MemberReader top(doc);
    top.integer("n", 0, 5);
    EXPECT_EQ(top.problem(), "\"n\" must be an integer 0..5, not 2.5");
    MemberReader missing(doc);
    missing.text("b", 0, 1);
    EXPECT_EQ(missing.problem(), "missing \"b\"");
}

}  // namespace
