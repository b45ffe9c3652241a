// The recently used files list: XBEL parsing from fixture strings, file
// URLs, GLib's timestamps, and matching a window's title to a file.
#ifdef UMF_PROVIDER_TESTS

#include <gtest/gtest.h>
#include <stdlib.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <string>
#include <thread>

#include "provider/content/recent_files.hpp"
#include "tests/support/temp_dir.hpp"

namespace {

// A temporary folder that also makes files with some content.
struct FilesDir : umf::test::TempDir {
    std::filesystem::path touch(const std::string& name) const {
        std::ofstream(path / name) << "content";
        return path / name;
    }
};

namespace fs = std::filesystem;
using namespace umf::provider;
using namespace std::chrono_literals;

std::string bookmark(const std::string& href, const std::string& modified, const std::string& inner = {}) {
    return "  <bookmark href=\"" + href + "\" added=\"2020-01-01T00:00:00Z\" modified=\"" + modified +
           "\" visited=\"2020-01-01T00:00:00Z\">" + inner + "</bookmark>\n";
}

std::string xbel(const std::string& bookmarks) {
    return "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n"
           "<xbel version=\"1.0\"\n"
           "      xmlns:bookmark=\"http://www.freedesktop.org/standards/desktop-bookmarks\"\n"
           "      xmlns:mime=\"http://www.freedesktop.org/standards/shared-mime-info\">\n" +
           bookmarks + "</xbel>\n";
}

std::chrono::system_clock::time_point at(int year, unsigned month, unsigned day, int hour, int minute, int second) {
    using namespace std::chrono;
    return sys_days(std::chrono::year{year} / month / day) + hours(hour) + minutes(minute) + seconds(second);
}

// A bookmark as GLib 2.74 writes it.
const std::string kGlibBookmark = R"(
  <bookmark href="file:///home/ann/Documents/Q3%20report%20%C3%A9t%C3%A9.pdf" added="2024-03-01T09:30:00.123456Z" modified="2024-03-01T09:30:00.123456Z" visited="2024-03-01T09:30:00.123456Z">
    <title>Quarterly report</title>
    <info>
      <metadata owner="http://freedesktop.org">
        <mime:mime-type type="application/pdf"/>
        <bookmark:applications>
          <bookmark:application name="Document Viewer" exec="&apos;evince %u&apos;" modified="2024-03-02T10:00:00Z" count="2"/>
        </bookmark:applications>
      </metadata>
    </info>
  </bookmark>
)";

TEST(RecentFiles, ParsesGlibBookmarks) {
    const auto entries = parse_recent_files(xbel(kGlibBookmark));
    ASSERT_EQ(entries.size(), 1u);
    EXPECT_EQ(entries[0].path, fs::path("/home/ann/Documents/Q3 report \xC3\xA9t\xC3\xA9.pdf"));
    EXPECT_EQ(entries[0].title, "Quarterly report");
    EXPECT_EQ(entries[0].mime, "application/pdf");
    // The application's later use counts.
    EXPECT_EQ(entries[0].modified, at(2024, 3, 2, 10, 0, 0));
}

TEST(RecentFiles, KeepsOnlyLocalFiles) {
    const auto entries = parse_recent_files(xbel(bookmark("https://example.org/a.pdf", "2024-01-01T00:00:00Z") +
                                                 bookmark("file://otherhost/b.pdf", "2024-01-01T00:00:00Z") +
                                                 bookmark("file://localhost/c.pdf", "2024-01-01T00:00:00Z") +
                                                 bookmark("file:///d%2.pdf", "2024-01-01T00:00:00Z") +
                                                 bookmark("file:///e%00.pdf", "2024-01-01T00:00:00Z") +
                                                 bookmark("file:///f.pdf", "2024-01-01T00:00:00Z")));
    ASSERT_EQ(entries.size(), 2u);
    EXPECT_EQ(entries[0].path, fs::path("/c.pdf"));
    EXPECT_EQ(entries[1].path, fs::path("/f.pdf"));
}

TEST(RecentFiles, MalformedDocumentsGiveNothing) {
    const std::string good = xbel(bookmark("file:///a.pdf", "2024-01-01T00:00:00Z"));
    EXPECT_EQ(parse_recent_files(good).size(), 1u);
    EXPECT_TRUE(parse_recent_files("").empty());
    EXPECT_TRUE(parse_recent_files(good.substr(0, good.size() / 2)).empty());
    EXPECT_TRUE(parse_recent_files("<xbel><bookmark href=\"file:///a.pdf\"></xbel>").empty());
    EXPECT_TRUE(parse_recent_files("<html><bookmark href=\"file:///a.pdf\"/></html>").empty());
    EXPECT_TRUE(parse_recent_files(std::string("\0\xff\xfe<xbel>", 8)).empty());
    // Entity expansion bombs stop at Qt's limit rather than eating memory.
    std::string bomb = "<?xml version=\"1.0\"?><!DOCTYPE xbel [<!ENTITY a \"aaaaaaaaaa\">";
    for (char c = 'b'; c <= 'k'; ++c) {
        bomb += std::string("<!ENTITY ") + c + " \"";
        for (int i = 0; i < 10; ++i) bomb += std::string("&") + static_cast<char>(c - 1) + ";";
        bomb += "\">";
    }
    bomb += "]><xbel><bookmark href=\"file:///a.pdf\"><title>&k;</title></bookmark></xbel>";
    EXPECT_TRUE(parse_recent_files(bomb).empty());
}

TEST(RecentFiles, ReadsFilesWithinTheCap) {
    FilesDir dir;
    const fs::path file = dir.path / "recently-used.xbel";
    std::ofstream(file) << xbel(bookmark("file:///a.pdf", "2024-01-01T00:00:00Z"));
    EXPECT_EQ(read_recent_files(file).size(), 1u);
    EXPECT_TRUE(read_recent_files(file, 16).empty());
    EXPECT_TRUE(read_recent_files(dir.path / "missing.xbel").empty());
    EXPECT_TRUE(read_recent_files(dir.path).empty());
}

TEST(RecentFiles, ParsesGlibTimes) {
    EXPECT_EQ(parse_iso8601("2024-03-01T09:30:00Z"), at(2024, 3, 1, 9, 30, 0));
    EXPECT_EQ(parse_iso8601("2024-03-01T09:30:00.5Z"), at(2024, 3, 1, 9, 30, 0) + 500ms);
    EXPECT_EQ(parse_iso8601("2024-03-01T09:30:00.123456Z"), at(2024, 3, 1, 9, 30, 0) + 123456us);
    EXPECT_EQ(parse_iso8601("2024-03-01T10:30:00+01:00"), at(2024, 3, 1, 9, 30, 0));
    EXPECT_EQ(parse_iso8601("2024-03-01T08:00:00-0130"), at(2024, 3, 1, 9, 30, 0));
    EXPECT_FALSE(parse_iso8601(""));
    EXPECT_FALSE(parse_iso8601("2024-02-30T00:00:00Z"));
    EXPECT_FALSE(parse_iso8601("2024-03-01 09:30"));
    EXPECT_FALSE(parse_iso8601("2024-03-01T09:30:00"));
    EXPECT_FALSE(parse_iso8601("1709285400"));
}

TEST(RecentFiles, DecodesFileUrls) {
    EXPECT_EQ(file_url_to_path("file:///tmp/a%20b.pdf"), fs::path("/tmp/a b.pdf"));
    EXPECT_EQ(file_url_to_path("FILE://localhost/tmp/x.txt"), fs::path("/tmp/x.txt"));
    EXPECT_EQ(file_url_to_path("file:///tmp/../etc/x"), fs::path("/etc/x"));
    EXPECT_EQ(file_url_to_path("file:///tmp/q.txt?x=1#y"), fs::path("/tmp/q.txt"));
    EXPECT_FALSE(file_url_to_path("file://host/tmp/x"));
    EXPECT_FALSE(file_url_to_path("file://localhostx/tmp/x"));
    EXPECT_FALSE(file_url_to_path("file:tmp/x"));
    EXPECT_FALSE(file_url_to_path("http:///tmp/x"));
    EXPECT_FALSE(file_url_to_path("file:///tmp/%zz"));
    EXPECT_FALSE(file_url_to_path("file:///tmp/%4"));
}

TEST(RecentFiles, TitlesMentionWholeNames) {
    EXPECT_TRUE(title_mentions("report.pdf - 1/3 (96 dpi)", "report.pdf"));
    EXPECT_TRUE(title_mentions("report.pdf \xE2\x80\x94 Document Viewer", "report.pdf"));
    EXPECT_TRUE(title_mentions("Okular \xE2\x80\x94 report.pdf", "report.pdf"));
    EXPECT_TRUE(title_mentions("[report.pdf]", "report.pdf"));
    EXPECT_TRUE(title_mentions("\xE2\x80\x9Creport.pdf\xE2\x80\x9D", "report.pdf"));
    EXPECT_TRUE(title_mentions("\xC2\xABreport.pdf\xC2\xBB", "report.pdf"));
    EXPECT_TRUE(title_mentions("report.pdf", "report.pdf"));
    EXPECT_TRUE(title_mentions("data.pdf / a.pdf", "a.pdf"));
    EXPECT_FALSE(title_mentions("data.pdf - mupdf", "a.pdf"));
    EXPECT_FALSE(title_mentions("report.pdf.bak", "report.pdf"));
    EXPECT_FALSE(title_mentions("old-report.pdf", "report.pdf"));
    EXPECT_FALSE(title_mentions("r\xC3\xA9sum\xC3\xA9.pdf", "sum\xC3\xA9.pdf"));
    EXPECT_FALSE(title_mentions("anything", ""));
}

TEST(RecentFiles, MatchesTheMostRecentExistingFileByTitle) {
    FilesDir dir;
    fs::create_directory(dir.path / "old");
    const fs::path recent = dir.touch("report.pdf");
    const fs::path older = dir.path / "old" / "report.pdf";
    std::ofstream(older) << "old";
    const fs::path notes = dir.touch("notes.txt");
    std::vector<RecentFile> entries{
        {older, at(2024, 1, 1, 0, 0, 0), {}, {}},
        {dir.path / "gone" / "report.pdf", at(2024, 6, 1, 0, 0, 0), {}, {}},  // newest, but missing
        {recent, at(2024, 2, 1, 0, 0, 0), {}, {}},
        {notes, at(2024, 3, 1, 0, 0, 0), "Meeting notes", {}},
    };
    EXPECT_EQ(match_by_title(entries, "report.pdf - mupdf"), recent);
    EXPECT_EQ(match_by_title(entries, "Meeting notes \xE2\x80\x94 Text Editor"), notes);
    // Viewers that drop the extension.
    EXPECT_EQ(match_by_title(entries, "notes (~/Documents) - gedit"), notes);
    EXPECT_FALSE(match_by_title(entries, "Inbox - Mail"));
    EXPECT_FALSE(match_by_title(entries, ""));
    EXPECT_FALSE(match_by_title({}, "report.pdf"));
}

TEST(RecentFiles, CacheRereadsAChangedFile) {
    FilesDir dir;
    const fs::path file = dir.path / "recently-used.xbel";
    RecentFilesCache cache(file);
    EXPECT_TRUE(cache.entries()->empty());
    std::ofstream(file) << xbel(bookmark("file:///a.pdf", "2024-01-01T00:00:00Z"));
    EXPECT_EQ(cache.entries()->size(), 1u);
    const auto first = cache.entries();
    EXPECT_EQ(cache.entries(), first);  // unchanged: not parsed again
    std::ofstream(file) << xbel(bookmark("file:///a.pdf", "2024-01-01T00:00:00Z") +
                                bookmark("file:///b.pdf", "2024-01-01T00:00:00Z"));
    EXPECT_EQ(cache.entries()->size(), 2u);
    fs::remove(file);
    EXPECT_TRUE(cache.entries()->empty());
}

}  // namespace

#endif  // UMF_PROVIDER_TESTS
