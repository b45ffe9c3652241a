#include "provider/board/board.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <system_error>

#include "shared/field/png_writer.hpp"
#include "shared/io/atomic_file.hpp"
#include "shared/io/pdf_objects.hpp"

namespace umf::provider {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

[[noreturn]] void fail(const std::string& where, const std::string& what) { throw BoardError(where + ": " + what); }

std::string quoted(const std::string& member) { return "\"" + member + "\""; }

// Strict UTF-8: no overlong forms, no surrogates, nothing above U+10FFFF.
// nlohmann's parser already refuses most of this; a board is checked anyway
// because titles go straight to the painter and the requester.
bool is_utf8(const std::string& s) {
    std::size_t i = 0;
    while (i < s.size()) {
        const auto b = static_cast<unsigned char>(s[i]);
        int extra = 0;
        std::uint32_t cp = 0;
        if (b < 0x80) {
            ++i;
            continue;
        } else if ((b & 0xE0) == 0xC0) {
            extra = 1;
            cp = b & 0x1F;
        } else if ((b & 0xF0) == 0xE0) {
            extra = 2;
            cp = b & 0x0F;
        } else if ((b & 0xF8) == 0xF0) {
            extra = 3;
            cp = b & 0x07;
        } else {
            return false;
        }
        if (i + extra >= s.size()) return false;
        for (int k = 1; k <= extra; ++k) {
            const auto c = static_cast<unsigned char>(s[i + k]);
            if ((c & 0xC0) != 0x80) return false;
            cp = (cp << 6) | (c & 0x3F);
        }
        static constexpr std::uint32_t kSmallest[] = {0, 0x80, 0x800, 0x10000};
        if (cp < kSmallest[extra] || cp > 0x10FFFF || (cp >= 0xD800 && cp <= 0xDFFF)) return false;
        i += static_cast<std::size_t>(extra) + 1;
    }
    return true;
}

std::string title_member(const json& doc, const std::string& where) {
    const json& v = doc.at("title");
    if (!v.is_string()) fail(where, "\"title\" must be a string");
    const auto s = v.get<std::string>();
    if (s.empty()) fail(where, "\"title\" must not be empty");
    if (s.size() > kMaxBoardTitleBytes)
        fail(where, "\"title\" is " + std::to_string(s.size()) + " bytes long, at most " +
                        std::to_string(kMaxBoardTitleBytes) + " allowed");
    if (!is_utf8(s)) fail(where, "\"title\" is not valid UTF-8");
    return s;
}

fs::path path_member(const json& doc, const char* member, const fs::path& base_dir, const std::string& where) {
    const json& v = doc.at(member);
    if (!v.is_string()) fail(where, quoted(member) + " must be a string (a path)");
    const auto s = v.get<std::string>();
    if (s.empty()) fail(where, quoted(member) + " must not be empty");
    if (s.size() > kMaxBoardPathBytes)
        fail(where, quoted(member) + " is longer than " + std::to_string(kMaxBoardPathBytes) + " bytes");
    if (s.find('\0') != std::string::npos) fail(where, quoted(member) + " contains a NUL character");
    if (!is_utf8(s)) fail(where, quoted(member) + " is not valid UTF-8");
    fs::path p(s);
    if (p.is_relative()) p = base_dir / p;
    std::error_code ec;
    fs::path absolute = fs::absolute(p, ec);
    if (ec) fail(where, quoted(member) + " \"" + s + "\" cannot be made absolute: " + ec.message());
    return absolute.lexically_normal();
}

bool starts_with_nocase(const std::string& s, std::string_view prefix) {
    if (s.size() < prefix.size()) return false;
    for (std::size_t i = 0; i < prefix.size(); ++i)
        if (std::tolower(static_cast<unsigned char>(s[i])) != prefix[i]) return false;
    return true;
}

std::string url_member(const json& doc, const std::string& where) {
    const json& v = doc.at("url");
    if (!v.is_string()) fail(where, "\"url\" must be a string");
    const auto s = v.get<std::string>();
    if (s.size() > kMaxBoardUrlBytes)
        fail(where, "\"url\" is " + std::to_string(s.size()) + " bytes long, at most " +
                        std::to_string(kMaxBoardUrlBytes) + " allowed");
    std::size_t scheme = 0;
    if (starts_with_nocase(s, "http://"))
        scheme = 7;
    else if (starts_with_nocase(s, "https://"))
        scheme = 8;
    else
        fail(where, "\"url\" must start with http:// or https://");
    if (s.size() == scheme || s[scheme] == '/') fail(where, "\"url\" has no host");
    for (char c : s) {
        const auto b = static_cast<unsigned char>(c);
        if (b <= 0x20 || b == 0x7F) fail(where, "\"url\" must not contain spaces or control characters");
    }
    if (!is_utf8(s)) fail(where, "\"url\" is not valid UTF-8");
    return s;
}

// A JSON integer as a signed number; nullopt for anything else, including
// unsigned values too large for one.
std::optional<std::int64_t> integer_value(const json& v) {
    if (!v.is_number_integer()) return std::nullopt;
    if (v.is_number_unsigned() && v.get<std::uint64_t>() > static_cast<std::uint64_t>(INT64_MAX)) return std::nullopt;
    return v.get<std::int64_t>();
}

PixelRect rect_member(const json& doc, const std::string& where) {
    const json& v = doc.at("rect");
    const std::string shape = "\"rect\" must be 4 integers [x, y, width, height]";
    if (!v.is_array() || v.size() != 4) fail(where, shape);
    static constexpr const char* kNames[] = {"x", "y", "width", "height"};
    int values[4] = {};
    for (std::size_t i = 0; i < 4; ++i) {
        const std::int64_t lo = i < 2 ? -kMaxBoardRectCoordinate : 1;
        const auto value = integer_value(v[i]);
        if (!value) fail(where, shape);
        if (*value < lo || *value > kMaxBoardRectCoordinate)
            fail(where, std::string("\"rect\" ") + kNames[i] + " must be " + std::to_string(lo) + ".." +
                            std::to_string(kMaxBoardRectCoordinate) + ", not " + std::to_string(*value));
        values[i] = static_cast<int>(*value);
    }
    return {values[0], values[1], values[2], values[3]};
}

BoardItem item_from(const json& doc, std::size_t index, const fs::path& base_dir, const std::string& source) {
    std::string where = source + ": item " + std::to_string(index + 1);
    if (!doc.is_object()) fail(where, "an item must be a JSON object");
    static const std::set<std::string> known = {"title", "file", "url", "thumbnail", "rect"};
    for (const auto& [key, value] : doc.items())
        if (!known.count(key)) fail(where, "unknown member \"" + key + "\"");
    BoardItem item;
    if (!doc.contains("title")) fail(where, "missing \"title\"");
    item.title = title_member(doc, where);
    where += " (\"" + item.title + "\")";
    const bool has_file = doc.contains("file");
    const bool has_url = doc.contains("url");
    if (has_file == has_url) fail(where, "needs exactly one of \"file\" and \"url\"");
    if (has_file) item.file = path_member(doc, "file", base_dir, where);
    if (has_url) item.url = url_member(doc, where);
    if (doc.contains("thumbnail")) item.thumbnail = path_member(doc, "thumbnail", base_dir, where);
    if (doc.contains("rect")) item.rect = rect_member(doc, where);
    return item;
}

Board board_from(std::string_view text, const fs::path& base_dir, const std::string& source) {
    if (text.size() > kMaxBoardFileBytes)
        fail(source, "is " + std::to_string(text.size()) + " bytes, at most " + std::to_string(kMaxBoardFileBytes) +
                         " allowed");
    json doc;
    try {
        doc = json::parse(text);
    } catch (const json::exception& e) {  // parse_error, or out_of_range for a number beyond a double
        fail(source, std::string("not valid JSON: ") + e.what());
    }
    if (!doc.is_object()) fail(source, "a board must be a JSON object");
    static const std::set<std::string> known = {"format", "title", "columns", "items"};
    for (const auto& [key, value] : doc.items())
        if (!known.count(key)) fail(source, "unknown member \"" + key + "\"");
    auto format = doc.find("format");
    if (format == doc.end()) fail(source, std::string("missing \"format\" (\"") + kBoardFormat + "\")");
    if (!format->is_string() || format->get<std::string>() != kBoardFormat)
        fail(source, std::string("\"format\" must be \"") + kBoardFormat + "\", not " + format->dump());

    Board board;
    if (doc.contains("title")) board.title = title_member(doc, source);
    if (auto columns = doc.find("columns"); columns != doc.end()) {
        const auto value = integer_value(*columns);
        if (!value || *value < 0 || *value > kMaxBoardColumns)
            fail(source, "\"columns\" must be an integer 0.." + std::to_string(kMaxBoardColumns) +
                             " (0: chosen to suit the screen)");
        board.columns = static_cast<int>(*value);
    }
    auto items = doc.find("items");
    if (items == doc.end()) fail(source, "missing \"items\"");
    if (!items->is_array()) fail(source, "\"items\" must be an array");
    if (items->empty() || items->size() > kMaxBoardItems)
        fail(source, "\"items\" must hold 1 to " + std::to_string(kMaxBoardItems) + " items, not " +
                         std::to_string(items->size()));
    for (std::size_t i = 0; i < items->size(); ++i) board.items.push_back(item_from((*items)[i], i, base_dir, source));
    return board;
}

// The grid column count whose tiles come closest to 4:3 on this area.
int automatic_columns(int n, int area_w, int area_h, int gap) {
    int best = 0;
    double best_score = std::numeric_limits<double>::infinity();
    for (int c = 1; c <= std::min(n, kMaxBoardColumns); ++c) {
        const int rows = (n + c - 1) / c;
        const double tw = (area_w - (c - 1.0) * gap) / c;
        const double th = (area_h - (rows - 1.0) * gap) / rows;
        if (tw <= 0 || th <= 0) continue;
        const double score = std::abs(std::log(tw / th / (4.0 / 3.0)));
        if (score < best_score) {
            best_score = score;
            best = c;
        }
    }
    return best > 0 ? best : std::max(1, static_cast<int>(std::ceil(std::sqrt(static_cast<double>(n)))));
}

std::string path_text(const fs::path& p, const fs::path& base_dir) {
    const fs::path base = fs::absolute(base_dir).lexically_normal();
    const fs::path rel = p.lexically_normal().lexically_relative(base);
    if (!rel.empty() && *rel.begin() != "..") return rel.generic_string();
    return p.generic_string();
}

// --- the demo board's files: fixed bytes, nothing taken from the clock or
// the machine, so that writing them twice changes nothing.

std::string demo_note() {
    return "umf demo board\n"
           "==============\n"
           "\n"
           "This board is shown by umf-provider. A faint pulsing pattern of squares is\n"
           "mixed into the screen: point the umf requester (a phone's camera) at any\n"
           "tile and grab it. The note, the picture, the leaflet and the table arrive\n"
           "as files, the two links as web addresses.\n"
           "\n"
           "Nothing leaves this screen unless a paired requester asks for it.\n";
}

std::string demo_csv() {
    return "hour,temperature_c,humidity_pct,wind_m_s\n"
           "06:00,9.5,88,1.2\n"
           "08:00,11.0,84,1.8\n"
           "10:00,14.5,71,2.6\n"
           "12:00,17.0,62,3.1\n"
           "14:00,18.5,57,3.4\n"
           "16:00,17.5,60,2.9\n"
           "18:00,15.0,68,2.0\n"
           "20:00,12.5,77,1.4\n";
}

// A landscape drawn with integer arithmetic only: sky, sun, two hills, a lake.
std::string demo_png() {
    constexpr int w = 480, h = 320;
    std::vector<std::uint8_t> rgb(static_cast<std::size_t>(w) * h * 3);
    for (int y = 0; y < h; ++y)
        for (int x = 0; x < w; ++x) {
            int r = 70 + y * 90 / h, g = 130 + y * 80 / h, b = 220 - y * 30 / h;  // sky
            const int dx = x - 360, dy = y - 80;
            if (dx * dx + dy * dy < 38 * 38) r = 255, g = 214, b = 90;  // sun
            const int far_hill = 170 + (x - 140) * (x - 140) / 260;
            if (y > far_hill) r = 96, g = 140, b = 96;
            const int near_hill = 215 + (x - 400) * (x - 400) / 500;
            if (y > near_hill) r = 60, g = 112, b = 60;
            if (y > 270) r = 50 + (x + y) % 12, g = 100 + (x * 3 + y) % 20, b = 170;  // lake, rippled
            auto* px = &rgb[(static_cast<std::size_t>(y) * w + x) * 3];
            px[0] = static_cast<std::uint8_t>(r);
            px[1] = static_cast<std::uint8_t>(g);
            px[2] = static_cast<std::uint8_t>(b);
        }
    return encode_png_rgb(w, h, rgb);
}

// A one-page PDF 1.4 written by hand: Helvetica (one of the standard 14
// fonts, so nothing is embedded) and an info dictionary.
std::string demo_pdf() {
    const std::string text =
        "BT /F1 28 Tf 72 760 Td (umf demo leaflet) Tj ET\n"
        "BT /F1 14 Tf 72 720 Td (This PDF was grabbed from a screen with a phone camera.) Tj ET\n"
        "BT /F1 14 Tf 72 700 Td (The provider mixed a faint marker field into the board;) Tj ET\n"
        "BT /F1 14 Tf 72 680 Td (the requester found it and asked for the tile under its aim.) Tj ET\n";
    const std::vector<std::string> objects = {
        "<< /Type /Catalog /Pages 2 0 R >>",
        "<< /Type /Pages /Kids [3 0 R] /Count 1 >>",
        "<< /Type /Page /Parent 2 0 R /MediaBox [0 0 595 842] /Contents 4 0 R "
        "/Resources << /Font << /F1 5 0 R >> >> >>",
        "<< /Length " + std::to_string(text.size()) + " >>\nstream\n" + text + "endstream",
        "<< /Type /Font /Subtype /Type1 /BaseFont /Helvetica /Encoding /WinAnsiEncoding >>",
        "<< /Title (umf demo leaflet) /Producer (umf-provider) >>",
    };
    return io::pdf_from_objects(objects, 6);
}

}  // namespace

Board parse_board(std::string_view json, const fs::path& base_dir) { return board_from(json, base_dir, "board"); }

Board load_board(const fs::path& file) {
    const std::string source = "board file " + file.string();
    std::error_code ec;
    if (!fs::is_regular_file(file, ec)) fail(source, ec ? ec.message() : "does not exist or is not a regular file");
    const auto size = fs::file_size(file, ec);
    if (ec) fail(source, "cannot be read: " + ec.message());
    if (size > kMaxBoardFileBytes)
        fail(source, "is " + std::to_string(size) + " bytes, at most " + std::to_string(kMaxBoardFileBytes) +
                         " allowed");
    std::ifstream in(file, std::ios::binary);
    if (!in) fail(source, "cannot be opened");
    std::string text;
    text.resize(static_cast<std::size_t>(size));
    in.read(text.data(), static_cast<std::streamsize>(size));
    if (in.gcount() != static_cast<std::streamsize>(size)) fail(source, "cannot be read");
    fs::path dir = fs::absolute(file, ec).parent_path();
    if (ec) fail(source, "cannot be made absolute: " + ec.message());
    return board_from(text, dir, source);
}

int board_title_height(const Board& board, int screen_height) {
    if (board.title.empty() || screen_height <= 0) return 0;
    const int wanted = std::max(48, static_cast<int>(std::lround(0.08 * screen_height)));
    return std::min(wanted, screen_height / 4);
}

std::vector<PixelRect> layout_board(const Board& board, int screen_width, int screen_height) {
    if (screen_width < 1 || screen_height < 1)
        throw std::invalid_argument("layout_board: screen size " + std::to_string(screen_width) + " x " +
                                    std::to_string(screen_height) + " is empty");
    const int top = board_title_height(board, screen_height);
    const int gap = std::max(2, static_cast<int>(std::lround(0.02 * std::min(screen_width, screen_height))));
    // The grid's area: a gap from every screen edge and from the title bar.
    const int left = std::min(gap, screen_width), right = std::max(left, screen_width - gap);
    const int grid_top = std::min(top + gap, screen_height), bottom = std::max(grid_top, screen_height - gap);
    const int area_w = right - left, area_h = bottom - grid_top;

    const int in_grid = static_cast<int>(
        std::count_if(board.items.begin(), board.items.end(), [](const BoardItem& i) { return !i.rect; }));
    const int columns = in_grid == 0             ? 1
                        : board.columns > 0 ? board.columns
                                            : automatic_columns(in_grid, area_w, area_h, gap);
    const int rows = std::max(1, (in_grid + columns - 1) / columns);
    // Cell k starts at the k-th of (count) equal steps over area + gap, so
    // the last cell ends at the area's edge and rounding never overlaps two.
    const auto start = [gap](int origin, int extent, int k, int count) {
        return origin + static_cast<int>(static_cast<long long>(k) * (extent + gap) / count);
    };

    std::vector<PixelRect> tiles;
    int cell = 0;
    for (const auto& item : board.items) {
        if (item.rect) {
            const PixelRect& r = *item.rect;
            const int x0 = std::clamp(r.x, 0, screen_width), x1 = std::clamp(r.x + r.width, 0, screen_width);
            const int y0 = std::clamp(r.y, top, screen_height), y1 = std::clamp(r.y + r.height, top, screen_height);
            tiles.push_back({x0, y0, std::max(0, x1 - x0), std::max(0, y1 - y0)});
            continue;
        }
        const int row = cell / columns, col = cell % columns;
        ++cell;
        const int x = start(left, area_w, col, columns), y = start(grid_top, area_h, row, rows);
        const int w = std::max(0, start(left, area_w, col + 1, columns) - gap - x);
        const int h = std::max(0, start(grid_top, area_h, row + 1, rows) - gap - y);
        tiles.push_back({x, y, w, h});
    }
    return tiles;
}

std::string board_to_json(const Board& board, const fs::path& base_dir) {
    nlohmann::ordered_json doc;
    doc["format"] = kBoardFormat;
    if (!board.title.empty()) doc["title"] = board.title;
    if (board.columns != 0) doc["columns"] = board.columns;
    doc["items"] = nlohmann::ordered_json::array();
    for (const auto& item : board.items) {
        nlohmann::ordered_json o;
        o["title"] = item.title;
        if (item.file) o["file"] = path_text(*item.file, base_dir);
        if (item.url) o["url"] = *item.url;
        if (item.thumbnail) o["thumbnail"] = path_text(*item.thumbnail, base_dir);
        if (item.rect) o["rect"] = {item.rect->x, item.rect->y, item.rect->width, item.rect->height};
        doc["items"].push_back(std::move(o));
    }
    return doc.dump(2) + "\n";
}

Board write_demo_board(const fs::path& dir) {
    std::error_code ec;
    fs::create_directories(dir, ec);
    if (ec) throw FileWriteError("demo board folder " + dir.string() + " cannot be made: " + ec.message());
    const fs::path root = fs::absolute(dir).lexically_normal();
    const auto write = [&root](const char* name, const std::string& bytes) {
        write_file_atomically((root / name).string(), bytes);
        return root / name;
    };

    Board board;
    board.title = "umf demo board";
    const auto file_item = [](std::string title, fs::path file) {
        BoardItem item;
        item.title = std::move(title);
        item.file = std::move(file);
        return item;
    };
    const auto url_item = [](std::string title, std::string url) {
        BoardItem item;
        item.title = std::move(title);
        item.url = std::move(url);
        return item;
    };
    board.items.push_back(file_item("Welcome note", write("welcome.txt", demo_note())));
    BoardItem picture = file_item("Mountain picture", write("mountains.png", demo_png()));
    picture.thumbnail = picture.file;
    board.items.push_back(picture);
    board.items.push_back(file_item("Leaflet (PDF)", write("leaflet.pdf", demo_pdf())));
    board.items.push_back(file_item("Weather log (CSV)", write("weather.csv", demo_csv())));
    board.items.push_back(url_item("Example domain", "https://example.org/"));
    board.items.push_back(url_item("The WebSocket API (W3C)", "https://www.w3.org/TR/websockets/"));
    write("board.json", board_to_json(board, root));
    return board;
}

}  // namespace umf::provider
