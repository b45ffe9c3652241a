#include "provider/content/recent_files.hpp"

#include <QByteArray>
#include <QString>
#include <QXmlStreamReader>
#include <algorithm>
#include <cctype>
#include <initializer_list>
#include <limits>
#include <cstdlib>
#include <fstream>
#include <numeric>
#include <system_error>

namespace umf::provider {

namespace fs = std::filesystem;
using Clock = std::chrono::system_clock;

namespace {

int hex_value(char c) {
    if (c >= '0' && c <= '9') return c - '0';
    if (c >= 'a' && c <= 'f') return c - 'a' + 10;
    if (c >= 'A' && c <= 'F') return c - 'A' + 10;
    return -1;
}

// nullopt on a broken escape, so a mangled URL is not taken for another file.
std::optional<std::string> percent_decode(std::string_view text) {
    std::string out;
    out.reserve(text.size());
    for (std::size_t i = 0; i < text.size(); ++i) {
        if (text[i] != '%') {
            out += text[i];
            continue;
        }
        if (i + 2 >= text.size()) return std::nullopt;
        const int high = hex_value(text[i + 1]);
        const int low = hex_value(text[i + 2]);
        if (high < 0 || low < 0) return std::nullopt;
        out += static_cast<char>(high * 16 + low);
        i += 2;
    }
    return out;
}

bool starts_with_ci(std::string_view text, std::string_view prefix) {
    if (text.size() < prefix.size()) return false;
    for (std::size_t i = 0; i < prefix.size(); ++i)
        if (std::tolower(static_cast<unsigned char>(text[i])) != prefix[i]) return false;
    return true;
}

// Reads `count` digits at `pos`; nullopt when they are not all digits.
std::optional<int> digits(std::string_view text, std::size_t pos, std::size_t count) {
    if (pos + count > text.size()) return std::nullopt;
    int value = 0;
    for (std::size_t i = pos; i < pos + count; ++i) {
        if (text[i] < '0' || text[i] > '9') return std::nullopt;
        value = value * 10 + (text[i] - '0');
    }
    return value;
}

// The zone after the seconds: "Z", "+HH:MM", "+HHMM" or "+HH"; its offset
// from UTC in minutes, nullopt when malformed.
std::optional<int> zone_offset_minutes(std::string_view zone) {
    if (zone == "Z" || zone == "z") return 0;
    if (zone.size() < 3 || (zone[0] != '+' && zone[0] != '-')) return std::nullopt;
    const int sign = zone[0] == '-' ? -1 : 1;
    const auto hours = digits(zone, 1, 2);
    if (!hours) return std::nullopt;
    std::size_t pos = 3;
    if (pos < zone.size() && zone[pos] == ':') ++pos;
    int minutes = 0;
    if (pos < zone.size()) {
        const auto m = digits(zone, pos, 2);
        if (!m || pos + 2 != zone.size()) return std::nullopt;
        minutes = *m;
    }
    return sign * (*hours * 60 + minutes);
}

// Code points that end a file name in a title besides ASCII punctuation:
// typographic quotes, dashes and spaces that window titles use.
bool is_separator_code_point(char32_t c) {
    return c == 0x00A0 || c == 0x00AB || c == 0x00BB || c == 0x00B7 || (c >= 0x2000 && c <= 0x206F) ||
           (c >= 0x3000 && c <= 0x303F) || (c >= 0xFF08 && c <= 0xFF09);
}

bool is_name_byte(unsigned char c) {
    return std::isalnum(c) || c == '_' || c == '.' || c == '-' || c >= 0x80;
}

// Decodes the UTF-8 sequence starting at `pos` (lenient: whatever it finds
// is a code point, since the answer is only whether it separates).
char32_t code_point_at(std::string_view text, std::size_t pos) {
    const auto lead = static_cast<unsigned char>(text[pos]);
    if (lead < 0x80) return lead;
    const int length = lead >= 0xF0 ? 4 : lead >= 0xE0 ? 3 : lead >= 0xC0 ? 2 : 1;
    char32_t c = lead & (0x7F >> length);
    for (int i = 1; i < length && pos + i < text.size(); ++i)
        c = (c << 6) | (static_cast<unsigned char>(text[pos + i]) & 0x3F);
    return c;
}

bool separates_at(std::string_view text, std::size_t pos) {
    if (!is_name_byte(static_cast<unsigned char>(text[pos]))) return true;
    return text[pos] & 0x80 ? is_separator_code_point(code_point_at(text, pos)) : false;
}

bool separates_before(std::string_view text, std::size_t end) {
    std::size_t start = end - 1;
    while (start > 0 && (static_cast<unsigned char>(text[start]) & 0xC0) == 0x80) --start;
    return separates_at(text, start);
}

Clock::time_point time_attribute(const QXmlStreamAttributes& attributes, const char* name) {
    const QByteArray value = attributes.value(QLatin1String(name)).toUtf8();
    return parse_iso8601(std::string_view(value.constData(), static_cast<std::size_t>(value.size())))
        .value_or(Clock::time_point{});
}

std::string to_std(QStringView text) {
    const QByteArray utf8 = text.toUtf8();
    return std::string(utf8.constData(), static_cast<std::size_t>(utf8.size()));
}

// The parser's state inside one <bookmark>.
struct PendingBookmark {
    std::optional<fs::path> path;
    RecentFile entry;
    int depth = 0;  // the element depth of <bookmark>
};

PendingBookmark begin_bookmark(const QXmlStreamAttributes& attributes, int depth) {
    PendingBookmark pending;
    pending.depth = depth;
    pending.path = file_url_to_path(to_std(attributes.value(QLatin1String("href"))));
    pending.entry.modified = std::max({time_attribute(attributes, "added"), time_attribute(attributes, "modified"),
                                       time_attribute(attributes, "visited")});
    return pending;
}

// An element inside a bookmark: its title, mime type or an application's
// time of use. Returns true when it consumed the element's end too.
bool read_bookmark_child(QXmlStreamReader& reader, PendingBookmark& pending, int depth) {
    const QStringView name = reader.name();
    if (name == QLatin1String("title") && depth == pending.depth + 1) {
        pending.entry.title = to_std(reader.readElementText(QXmlStreamReader::SkipChildElements));
        return true;
    }
    const QXmlStreamAttributes attributes = reader.attributes();
    if (name == QLatin1String("mime-type")) pending.entry.mime = to_std(attributes.value(QLatin1String("type")));
    if (name == QLatin1String("application"))
        pending.entry.modified = std::max(pending.entry.modified, time_attribute(attributes, "modified"));
    return false;
}

}  // namespace

fs::path default_recent_files_path() {
    if (const char* xdg = std::getenv("XDG_DATA_HOME"); xdg && *xdg && fs::path(xdg).is_absolute())
        return fs::path(xdg) / "recently-used.xbel";
    if (const char* home = std::getenv("HOME"); home && *home)
        return fs::path(home) / ".local" / "share" / "recently-used.xbel";
    return {};
}

std::optional<fs::path> file_url_to_path(std::string_view url) {
    if (!starts_with_ci(url, "file://")) return std::nullopt;
    std::string_view rest = url.substr(7);
    const std::size_t slash = rest.find('/');
    if (slash == std::string_view::npos) return std::nullopt;
    const std::string_view host = rest.substr(0, slash);
    // Another host's file is not this one's, even at the same path.
    if (!host.empty() && !(host.size() == 9 && starts_with_ci(host, "localhost"))) return std::nullopt;
    rest = rest.substr(slash);
    rest = rest.substr(0, rest.find_first_of("?#"));
    const auto decoded = percent_decode(rest);
    if (!decoded || decoded->find('\0') != std::string::npos) return std::nullopt;
    return fs::path(*decoded).lexically_normal();
}

std::optional<Clock::time_point> parse_iso8601(std::string_view text) {
    const auto year = digits(text, 0, 4), month = digits(text, 5, 2), day = digits(text, 8, 2);
    const auto hour = digits(text, 11, 2), minute = digits(text, 14, 2), second = digits(text, 17, 2);
    if (!year || !month || !day || !hour || !minute || !second) return std::nullopt;
    if (text[4] != '-' || text[7] != '-' || (text[10] != 'T' && text[10] != 't' && text[10] != ' ') ||
        text[13] != ':' || text[16] != ':')
        return std::nullopt;
    const std::chrono::year_month_day date{std::chrono::year{*year}, std::chrono::month(*month),
                                           std::chrono::day(*day)};
    if (!date.ok() || *hour > 23 || *minute > 59 || *second > 60) return std::nullopt;
    std::size_t pos = 19;
    std::chrono::microseconds fraction{0};
    if (pos < text.size() && text[pos] == '.') {
        long long scale = 100000;
        for (++pos; pos < text.size() && text[pos] >= '0' && text[pos] <= '9'; ++pos, scale /= 10)
            fraction += std::chrono::microseconds((text[pos] - '0') * scale);
    }
    const auto offset = zone_offset_minutes(text.substr(pos));
    if (!offset) return std::nullopt;
    const auto utc = std::chrono::sys_days(date) + std::chrono::hours(*hour) + std::chrono::minutes(*minute) +
                     std::chrono::seconds(*second) + fraction - std::chrono::minutes(*offset);
    return std::chrono::time_point_cast<Clock::duration>(utc);
}

std::vector<RecentFile> parse_recent_files(std::string_view xbel) {
    if (xbel.size() > static_cast<std::size_t>(std::numeric_limits<int>::max())) return {};
    QXmlStreamReader reader(QByteArray::fromRawData(xbel.data(), static_cast<int>(xbel.size())));
    std::vector<RecentFile> entries;
    std::optional<PendingBookmark> pending;
    int depth = 0;
    while (!reader.atEnd()) {
        const auto token = reader.readNext();
        if (token == QXmlStreamReader::StartElement) {
            ++depth;
            if (depth == 1 && reader.name() != QLatin1String("xbel")) return {};
            if (depth == 2 && reader.name() == QLatin1String("bookmark"))
                pending = begin_bookmark(reader.attributes(), depth);
            else if (pending && read_bookmark_child(reader, *pending, depth))
                --depth;
        } else if (token == QXmlStreamReader::EndElement) {
            if (pending && depth == pending->depth) {
                if (pending->path) {
                    pending->entry.path = std::move(*pending->path);
                    entries.push_back(std::move(pending->entry));
                }
                pending.reset();
            }
            --depth;
        }
    }
    if (reader.hasError()) return {};
    return entries;
}

std::vector<RecentFile> read_recent_files(const fs::path& file, std::size_t max_bytes) {
    std::error_code ec;
    const auto size = fs::file_size(file, ec);
    if (ec || size > max_bytes) return {};
    std::ifstream in(file, std::ios::binary);
    if (!in) return {};
    std::string text(static_cast<std::size_t>(size), '\0');
    in.read(text.data(), static_cast<std::streamsize>(text.size()));
    text.resize(static_cast<std::size_t>(in.gcount()));
    return parse_recent_files(text);
}

bool title_mentions(std::string_view title, std::string_view name) {
    if (name.empty()) return false;
    for (std::size_t pos = title.find(name); pos != std::string_view::npos; pos = title.find(name, pos + 1)) {
        const std::size_t end = pos + name.size();
        const bool bounded_before = pos == 0 || separates_before(title, pos);
        const bool bounded_after = end == title.size() || separates_at(title, end);
        if (bounded_before && bounded_after) return true;
    }
    return false;
}

std::optional<fs::path> match_by_title(const std::vector<RecentFile>& entries, std::string_view window_title) {
    std::vector<std::size_t> order(entries.size());
    std::iota(order.begin(), order.end(), std::size_t{0});
    std::stable_sort(order.begin(), order.end(),
                     [&](std::size_t a, std::size_t b) { return entries[a].modified > entries[b].modified; });
    // Shorter keys than this match too much by chance ("a", "doc").
    constexpr std::size_t kMinKeyBytes = 3;
    const auto keys = {
        +[](const RecentFile& e) { return e.path.filename().string(); },
        +[](const RecentFile& e) { return e.title; },
        +[](const RecentFile& e) { return e.path.stem().string(); },
    };
    for (const auto key : keys) {
        for (const std::size_t i : order) {
            const std::string text = key(entries[i]);
            if (text.size() < kMinKeyBytes || !title_mentions(window_title, text)) continue;
            std::error_code ec;
            if (fs::is_regular_file(entries[i].path, ec)) return entries[i].path;
        }
    }
    return std::nullopt;
}

RecentFilesCache::RecentFilesCache(fs::path file)
    : file_(std::move(file)), entries_(std::make_shared<const std::vector<RecentFile>>()) {}

std::shared_ptr<const std::vector<RecentFile>> RecentFilesCache::entries() const {
    std::error_code ec;
    const auto stamp = fs::last_write_time(file_, ec);
    const auto size = ec ? 0 : fs::file_size(file_, ec);
    std::lock_guard lock(mutex_);
    if (ec) {
        entries_ = std::make_shared<const std::vector<RecentFile>>();
        stamp_ = {};
        size_ = 0;
        return entries_;
    }
    if (stamp != stamp_ || size != size_) {
        entries_ = std::make_shared<const std::vector<RecentFile>>(read_recent_files(file_));
        stamp_ = stamp;
        size_ = size;
    }
    return entries_;
}

}  // namespace umf::provider
