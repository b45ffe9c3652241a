// A text with one part replaced, for tests that spoil a good document in one
// place: the part must be there (a test whose edit misses its text would
// check nothing).
#pragma once

#include <gtest/gtest.h>

#include <string>

namespace umf::test {

// `s` with the first `from` replaced by `to`; a failed expectation (and `s`
// unchanged) where `from` is not in it.
inline std::string replaced(std::string s, const std::string& from, const std::string& to) {
    const auto at = s.find(from);
    EXPECT_NE(at, std::string::npos) << from << " not in " << s.substr(0, 300);
    return at == std::string::npos ? s : s.replace(at, from.size(), to);
}

}  // namespace umf::test
