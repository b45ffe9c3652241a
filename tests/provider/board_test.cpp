// Boards: parsing (every defect named), layout, and the demo board's files.
// Built only with the provider (UMF_PROVIDER_TESTS, see tests/CMakeLists.txt).
#ifdef UMF_PROVIDER_TESTS

#include "provider/board/board.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <iterator>
#include <map>
#include <string>

namespace {

namespace fs = std::filesystem;
using namespace umf::provider;

fs::path temp_dir(const std::string& name) {
    const fs::path dir = fs::temp_directory_path() / ("umf-board-test-" + std::to_string(::getpid()) + "-" + name);
    fs::remove_all(dir);
    fs::create_directories(dir);
    return dir;
}

std::string read_bytes(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

TEST(Board, ParsesTheHeadersExample) {
    const Board b = parse_board(R"({"format": "umf-board/1", "title": "Open day", "columns": 3,
        "items": [
          {"title": "Timetable", "file": "timetable.pdf", "thumbnail": "timetable.png"},
          {"title": "Project site", "url": "https://example.org/"},
          {"title": "Map", "file": "/srv/map.png", "rect": [1200, 600, 600, 400]}]})",
                                "/boards/open-day");
    EXPECT_EQ(b.title, "Open day");
    EXPECT_EQ(b.columns, 3);
    ASSERT_EQ(b.items.size(), 3u);
    EXPECT_EQ(b.items[0].file, fs::path("/boards/open-day/timetable.pdf"));
    EXPECT_EQ(b.items[0].thumbnail, fs::path("/boards/open-day/timetable.png"));
    EXPECT_FALSE(b.items[0].url);
    EXPECT_EQ(b.items[1].url, "https://example.org/");
    EXPECT_FALSE(b.items[1].file);
    EXPECT_EQ(b.items[2].file, fs::path("/srv/map.png"));
    EXPECT_EQ(b.items[2].rect, (PixelRect{1200, 600, 600, 400}));

    // Title and columns are optional; the URL scheme is case-insensitive.
    const Board minimal =
        parse_board(R"({"format": "umf-board/1", "items": [{"title": "Ä", "url": "HTTP://x.example"}]})", "/");
    EXPECT_EQ(minimal.title, "");
    EXPECT_EQ(minimal.columns, 0);
    EXPECT_EQ(minimal.items[0].title, "Ä");
}

struct BadBoard {
    const char* json;
    const char* must_mention;
};

TEST(Board, EachDefectIsRefusedNamingTheMember) {
    const std::string many_items = [] {
        std::string s = R"({"format": "umf-board/1", "items": [)";
        for (std::size_t i = 0; i <= kMaxBoardItems; ++i) s += std::string(i ? "," : "") + R"({"title": "t", "url": "https://a.b/"})";
        return s + "]}";
    }();
    const std::string long_title =
        R"({"format": "umf-board/1", "items": [{"title": ")" + std::string(513, 'x') + R"(", "url": "https://a/"}]})";
    const std::string long_url = R"({"format": "umf-board/1", "items": [{"title": "t", "url": "https://a/)" +
                                 std::string(8192, 'x') + R"("}]})";
    const BadBoard cases[] = {
        {"[1, 2]", "JSON object"},
        {"{not json", "JSON"},
        {R"({"format": "umf-board/1", "columns": 1e999, "items": [{"title": "t", "url": "https://a/"}]})", "JSON"},
        {R"({"items": [{"title": "t", "url": "https://a/"}]})", "\"format\""},
        {R"({"format": "umf-board/2", "items": [{"title": "t", "url": "https://a/"}]})", "\"format\""},
        {R"({"format": "umf-board/1", "colour": "red", "items": [{"title": "t", "url": "https://a/"}]})", "\"colour\""},
        {R"({"format": "umf-board/1", "title": "", "items": [{"title": "t", "url": "https://a/"}]})", "\"title\""},
        {R"({"format": "umf-board/1", "title": 5, "items": [{"title": "t", "url": "https://a/"}]})", "\"title\""},
        {R"({"format": "umf-board/1", "columns": 65, "items": [{"title": "t", "url": "https://a/"}]})", "\"columns\""},
        {R"({"format": "umf-board/1", "columns": -1, "items": [{"title": "t", "url": "https://a/"}]})", "\"columns\""},
        {R"({"format": "umf-board/1", "columns": 2.5, "items": [{"title": "t", "url": "https://a/"}]})", "\"columns\""},
        {R"({"format": "umf-board/1"})", "\"items\""},
        {R"({"format": "umf-board/1", "items": []})", "\"items\""},
        {R"({"format": "umf-board/1", "items": {}})", "\"items\""},
        {R"({"format": "umf-board/1", "items": [5]})", "item 1"},
        {R"({"format": "umf-board/1", "items": [{"url": "https://a/"}]})", "\"title\""},
        {R"({"format": "umf-board/1", "items": [{"title": "", "url": "https://a/"}]})", "\"title\""},
        {R"({"format": "umf-board/1", "items": [{"title": "t"}]})", "\"file\" and \"url\""},
        {R"({"format": "umf-board/1", "items": [{"title": "t", "file": "a", "url": "https://a/"}]})",
         "\"file\" and \"url\""},
        {R"({"format": "umf-board/1", "items": [{"title": "t", "url": "ftp://a/"}]})", "\"url\""},
        {R"({"format": "umf-board/1", "items": [{"title": "t", "url": "javascript:void"}]})", "\"url\""},
        {R"({"format": "umf-board/1", "items": [{"title": "t", "url": "https://a/b c"}]})", "\"url\""},
        {R"({"format": "umf-board/1", "items": [{"title": "t", "url": "https://a/\tb"}]})", "\"url\""},
        {R"({"format": "umf-board/1", "items": [{"title": "t", "url": "https://"}]})", "\"url\""},
        {R"({"format": "umf-board/1", "items": [{"title": "t", "url": 7}]})", "\"url\""},
        {R"({"format": "umf-board/1", "items": [{"title": "t", "file": ""}]})", "\"file\""},
        {R"({"format": "umf-board/1", "items": [{"title": "t", "file": "a\u0000b"}]})", "\"file\""},
        {R"({"format": "umf-board/1", "items": [{"title": "t", "file": "a", "thumbnail": 3}]})", "\"thumbnail\""},
        {R"({"format": "umf-board/1", "items": [{"title": "t", "file": "a", "rect": [1, 2, 3]}]})", "\"rect\""},
        {R"({"format": "umf-board/1", "items": [{"title": "t", "file": "a", "rect": [1, 2, 0, 4]}]})", "width"},
        {R"({"format": "umf-board/1", "items": [{"title": "t", "file": "a", "rect": [1, 2, 3, -4]}]})", "height"},
        {R"({"format": "umf-board/1", "items": [{"title": "t", "file": "a", "rect": [1.5, 2, 3, 4]}]})", "\"rect\""},
        {R"({"format": "umf-board/1", "items": [{"title": "t", "file": "a", "rect": [1, 2, 3, 99999999999]}]})",
         "height"},
        {R"({"format": "umf-board/1", "items": [{"title": "t", "file": "a", "size": 3}]})", "\"size\""},
        {many_items.c_str(), "\"items\""},
        {long_title.c_str(), "\"title\""},
        {long_url.c_str(), "\"url\""},
    };
    for (const auto& c : cases) {
        try {
            parse_board(c.json, "/tmp");
            ADD_FAILURE() << "accepted: " << std::string(c.json).substr(0, 200);
        } catch (const BoardError& e) {
            EXPECT_NE(std::string(e.what()).find(c.must_mention), std::string::npos)
                << "message \"" << e.what() << "\" does not name " << c.must_mention;
        }
    }
    // The item and its title are named, to find the defect in a long board.
    try {
        parse_board(R"({"format": "umf-board/1", "items": [{"title": "a", "url": "https://a/"},
                         {"title": "Map", "file": "m.png", "rect": [0, 0, 0, 1]}]})",
                    "/");
        ADD_FAILURE();
    } catch (const BoardError& e) {
        EXPECT_NE(std::string(e.what()).find("item 2 (\"Map\")"), std::string::npos) << e.what();
    }
}

TEST(Board, LoadNamesTheFile) {
    const fs::path dir = temp_dir("load");
    EXPECT_THROW(load_board(dir / "missing.json"), BoardError);
    {
        std::ofstream(dir / "bad.json") << R"({"format": "umf-board/1", "items": [{"title": "t"}]})";
    }
    try {
        load_board(dir / "bad.json");
        ADD_FAILURE();
    } catch (const BoardError& e) {
        EXPECT_NE(std::string(e.what()).find("bad.json"), std::string::npos) << e.what();
    }
    {
        std::ofstream big(dir / "big.json");
        big << std::string(kMaxBoardFileBytes + 1, ' ');
    }
    EXPECT_THROW(load_board(dir / "big.json"), BoardError);
    {
        std::ofstream(dir / "good.json") << R"({"format": "umf-board/1", "items": [{"title": "t", "file": "x.txt"}]})";
    }
    // Relative paths are taken from the board's folder.
    EXPECT_EQ(load_board(dir / "good.json").items[0].file, dir / "x.txt");
    fs::remove_all(dir);
}

void expect_disjoint_within(const std::vector<PixelRect>& tiles, int w, int h, int top) {
    for (std::size_t i = 0; i < tiles.size(); ++i) {
        const PixelRect& a = tiles[i];
        EXPECT_GE(a.width, 1) << "tile " << i;
        EXPECT_GE(a.height, 1) << "tile " << i;
        EXPECT_GE(a.x, 0);
        EXPECT_GE(a.y, top) << "tile " << i << " overlaps the title bar";
        EXPECT_LE(a.x + a.width, w);
        EXPECT_LE(a.y + a.height, h);
        for (std::size_t j = i + 1; j < tiles.size(); ++j) {
            const PixelRect& b = tiles[j];
            const bool apart = a.x + a.width <= b.x || b.x + b.width <= a.x || a.y + a.height <= b.y ||
                               b.y + b.height <= a.y;
            EXPECT_TRUE(apart) << "tiles " << i << " and " << j << " overlap";
        }
    }
}

Board grid_board(int n, const std::string& title = "A board") {
    Board b;
    b.title = title;
    for (int i = 0; i < n; ++i) {
        BoardItem item;
        item.title = "item " + std::to_string(i);
        item.url = "https://example.org/" + std::to_string(i);
        b.items.push_back(item);
    }
    return b;
}

TEST(Board, GridTilesLieInsideTheScreenApartAndBelowTheTitle) {
    for (auto [w, h] : {std::pair{1920, 1080}, std::pair{1080, 1920}, std::pair{3840, 2160}, std::pair{800, 600},
                        std::pair{1366, 768}})
        for (int n : {1, 2, 3, 5, 6, 7, 12, 30}) {
            SCOPED_TRACE(std::to_string(w) + "x" + std::to_string(h) + ", " + std::to_string(n) + " items");
            const Board b = grid_board(n);
            const int top = board_title_height(b, h);
            EXPECT_GE(top, 48);
            const auto tiles = layout_board(b, w, h);
            ASSERT_EQ(tiles.size(), static_cast<std::size_t>(n));
            expect_disjoint_within(tiles, w, h, top);
        }
    // No title: no title bar.
    Board untitled = grid_board(4, "");
    EXPECT_EQ(board_title_height(untitled, 1080), 0);
    expect_disjoint_within(layout_board(untitled, 1920, 1080), 1920, 1080, 0);
    EXPECT_THROW(layout_board(untitled, 0, 1080), std::invalid_argument);
}

TEST(Board, AutomaticColumnsSuitTheScreen) {
    // Six tiles on a landscape screen: 3 x 2, each near 4:3; on a portrait one, 2 x 3.
    const auto landscape = layout_board(grid_board(6), 1920, 1080);
    EXPECT_EQ(landscape[0].y, landscape[2].y);
    EXPECT_LT(landscape[2].y, landscape[3].y);
    const double aspect = static_cast<double>(landscape[0].width) / landscape[0].height;
    EXPECT_NEAR(aspect, 4.0 / 3.0, 0.2);
    const auto portrait = layout_board(grid_board(6), 1080, 1920);
    EXPECT_EQ(portrait[0].y, portrait[1].y);
    EXPECT_LT(portrait[1].y, portrait[2].y);
    // Columns given are kept.
    Board b = grid_board(6);
    b.columns = 6;
    const auto row = layout_board(b, 1920, 1080);
    for (const auto& t : row) EXPECT_EQ(t.y, row[0].y);
}

TEST(Board, ExplicitRectsAreKeptAndClipped) {
    Board b = grid_board(4);
    b.items[1].rect = PixelRect{1200, 600, 600, 400};
    b.items[3].rect = PixelRect{1700, -50, 400, 300};  // past the right edge and over the title bar
    const auto tiles = layout_board(b, 1920, 1080);
    const int top = board_title_height(b, 1080);
    EXPECT_EQ(tiles[1], (PixelRect{1200, 600, 600, 400}));
    EXPECT_EQ(tiles[3], (PixelRect{1700, top, 220, 250 - top}));
    // The other two share the grid, apart from each other.
    expect_disjoint_within({tiles[0], tiles[2]}, 1920, 1080, top);
    EXPECT_EQ(tiles[0].y, tiles[2].y);
}

TEST(Board, JsonRoundTrips) {
    Board b = grid_board(2);
    b.columns = 2;
    b.items[0].url.reset();
    b.items[0].file = "/data/boards/notes/a.txt";
    b.items[0].thumbnail = "/elsewhere/a.png";
    b.items[1].rect = PixelRect{-10, 5, 20, 30};
    const std::string text = board_to_json(b, "/data/boards");
    EXPECT_NE(text.find("\"notes/a.txt\""), std::string::npos) << text;
    EXPECT_NE(text.find("\"/elsewhere/a.png\""), std::string::npos) << text;
    EXPECT_EQ(parse_board(text, "/data/boards"), b);
}

TEST(Board, DemoBoardWritesItsFilesTheSameEachTime) {
    const fs::path dir = temp_dir("demo") / "nested";
    const Board b = write_demo_board(dir);
    EXPECT_EQ(b.title, "umf demo board");
    ASSERT_EQ(b.items.size(), 6u);
    int files = 0, urls = 0;
    std::map<std::string, std::string> first_bytes;
    for (const auto& item : b.items) {
        EXPECT_FALSE(item.title.empty());
        EXPECT_NE(item.file.has_value(), item.url.has_value());
        if (item.file) {
            ++files;
            EXPECT_TRUE(item.file->is_absolute());
            EXPECT_TRUE(fs::is_regular_file(*item.file)) << *item.file;
            EXPECT_GT(fs::file_size(*item.file), 0u);
            first_bytes[item.file->filename().string()] = read_bytes(*item.file);
        } else {
            ++urls;
        }
        if (item.thumbnail) {
            EXPECT_TRUE(fs::is_regular_file(*item.thumbnail));
        }
    }
    EXPECT_EQ(files, 4);
    EXPECT_EQ(urls, 2);
    const auto extension_of = [&](const char* ext) {
        for (const auto& item : b.items)
            if (item.file && item.file->extension() == ext) return true;
        return false;
    };
    for (const char* ext : {".txt", ".png", ".pdf", ".csv"}) EXPECT_TRUE(extension_of(ext)) << ext;
    EXPECT_EQ(read_bytes(b.items[1].file.value()).substr(1, 3), "PNG");
    // The board file written beside them loads as the same board.
    EXPECT_EQ(load_board(dir / "board.json"), b);

    const Board again = write_demo_board(dir);
    EXPECT_EQ(again, b);
    for (const auto& [name, bytes] : first_bytes) EXPECT_EQ(read_bytes(dir / name), bytes) << name;
    fs::remove_all(dir.parent_path());
}

TEST(Board, DemoPdfIsAcceptedByPdfinfo) {
    if (std::system("command -v pdfinfo > /dev/null 2>&1") != 0) GTEST_SKIP() << "pdfinfo (poppler-utils) not installed";
    const fs::path dir = temp_dir("pdf");
    const Board b = write_demo_board(dir);
    const fs::path* pdf = nullptr;
    for (const auto& item : b.items)
        if (item.file && item.file->extension() == ".pdf") pdf = &*item.file;
    ASSERT_NE(pdf, nullptr);
    const fs::path report = dir / "pdfinfo.txt";
    // pdfinfo prints "Syntax Error" lines but still exits 0 for some repaired
    // files, so its error output must be empty too.
    const std::string command = "pdfinfo '" + pdf->string() + "' > '" + report.string() + "' 2> '" +
                                (dir / "pdfinfo.err").string() + "'";
    EXPECT_EQ(std::system(command.c_str()), 0);
    EXPECT_EQ(read_bytes(dir / "pdfinfo.err"), "");
    const std::string info = read_bytes(report);
    EXPECT_NE(info.find("Pages:"), std::string::npos) << info;
    EXPECT_NE(info.find("umf demo leaflet"), std::string::npos) << info;
    fs::remove_all(dir);
}

}  // namespace

#endif  // UMF_PROVIDER_TESTS
