// The requester's pure helpers, header-only so they are tested without the
// requester's program: the names a download takes when its own is used, and
// the default download directory. (The pairing URL's codec is shared's:
// tests/protocol/pairing_url_test.cpp.)
#if defined(UMF_PROVIDER_TESTS) && defined(UMF_REQUESTER_TOOL)

#include <gtest/gtest.h>

#include <string>

#include "requester/download_dir.hpp"
#include "shared/io/unique_name.hpp"

namespace {

using umf::io::numbered_name;
using umf::requester::parse_user_dirs_download;

TEST(RequesterUniqueName, NumbersBeforeTheExtension) {
    EXPECT_EQ(numbered_name("report.pdf", 0), "report.pdf");
    EXPECT_EQ(numbered_name("report.pdf", 1), "report (1).pdf");
    EXPECT_EQ(numbered_name("report.pdf", 12), "report (12).pdf");
    EXPECT_EQ(numbered_name("archive.tar.gz", 2), "archive.tar (2).gz");
    EXPECT_EQ(numbered_name("README", 1), "README (1)");
    EXPECT_EQ(numbered_name("notes.", 1), "notes. (1)");
    // Hidden files are all stem; their own extension still counts.
    EXPECT_EQ(numbered_name(".bashrc", 1), ".bashrc (1)");
    EXPECT_EQ(numbered_name(".config.json", 1), ".config (1).json");
    EXPECT_EQ(numbered_name("..", 1), ".. (1)");
    EXPECT_EQ(numbered_name("Bericht über Öl.pdf", 3), "Bericht über Öl (3).pdf");
}

TEST(RequesterUniqueName, StaysWithinTheFileSystemsLimit) {
    const std::string longest = std::string(251, 'a') + ".pdf";
    const std::string n = numbered_name(longest, 7);
    EXPECT_EQ(n.size(), 255u);
    EXPECT_EQ(n.substr(n.size() - 8), " (7).pdf");
    // Cut at a character boundary: "ö" is two bytes.
    std::string umlauts;
    while (umlauts.size() < 251) umlauts += "ö";
    const std::string u = numbered_name(umlauts + ".txt", 1);
    EXPECT_LE(u.size(), 255u);
    EXPECT_EQ(u.substr(u.size() - 8), " (1).txt");
    const std::string stem = u.substr(0, u.size() - 8);
    EXPECT_EQ(stem.size() % 2, 0u);
    EXPECT_EQ(stem.substr(stem.size() - 2), "ö");
    // An extension too long to keep is treated as stem.
    const std::string ext = "a." + std::string(253, 'x');
    EXPECT_LE(numbered_name(ext, 1).size(), 255u);
}

TEST(RequesterDownloadDir, ReadsXdgUserDirs) {
    EXPECT_EQ(parse_user_dirs_download("XDG_DOWNLOAD_DIR=\"$HOME/Downloads\"\n", "/home/ann"), "/home/ann/Downloads");
    EXPECT_EQ(parse_user_dirs_download("# comment\nXDG_DESKTOP_DIR=\"$HOME/Desktop\"\n"
                                       "XDG_DOWNLOAD_DIR=\"$HOME/Téléchargements\"\n",
                                       "/home/ann"),
              "/home/ann/Téléchargements");
    EXPECT_EQ(parse_user_dirs_download("XDG_DOWNLOAD_DIR=\"/data/in\"", "/home/ann"), "/data/in");
    EXPECT_EQ(parse_user_dirs_download("XDG_DOWNLOAD_DIR=\"$HOME/with \\\"quote\"", "/h"), "/h/with \"quote");
    // Switched off ("$HOME/"), missing, relative or unquoted: the caller's default.
    EXPECT_FALSE(parse_user_dirs_download("XDG_DOWNLOAD_DIR=\"$HOME/\"", "/h"));
    EXPECT_FALSE(parse_user_dirs_download("XDG_MUSIC_DIR=\"$HOME/Music\"", "/h"));
    EXPECT_FALSE(parse_user_dirs_download("XDG_DOWNLOAD_DIR=\"dl\"", "/h"));
    EXPECT_FALSE(parse_user_dirs_download("XDG_DOWNLOAD_DIR=$HOME/dl", "/h"));
    EXPECT_FALSE(parse_user_dirs_download("XDG_DOWNLOAD_DIR=\"$HOMEWORK/dl\"", "/h"));
    EXPECT_FALSE(parse_user_dirs_download("", "/h"));
}

}  // namespace

#endif
