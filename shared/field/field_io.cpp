#include "shared/field/field_io.hpp"

#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>

#include "shared/io/atomic_file.hpp"

namespace umf {

namespace {

using nlohmann::json;

[[noreturn]] void fail(const std::string& source, const std::string& what) {
    throw FieldFileError(source + ": " + what);
}

int integer_member(const json& doc, const char* name, const std::string& source) {
    auto it = doc.find(name);
    if (it == doc.end()) fail(source, std::string("missing \"") + name + "\"");
    if (!it->is_number_integer()) fail(source, std::string("\"") + name + "\" must be an integer");
    auto v = it->get<long long>();
    if (v < 0 || v > 1'000'000) fail(source, std::string("\"") + name + "\" is out of range: " + std::to_string(v));
    return static_cast<int>(v);
}

}  // namespace

Field parse_field(const std::string& text, const std::string& source) {
    if (text.size() > kMaxFieldFileBytes)
        fail(source, "file is " + std::to_string(text.size()) + " bytes, more than the limit of " +
                         std::to_string(kMaxFieldFileBytes));
    json doc = json::parse(text, nullptr, false);
    if (doc.is_discarded()) fail(source, "not valid JSON");
    if (!doc.is_object()) fail(source, "the top level must be a JSON object");

    auto fmt = doc.find("format");
    if (fmt == doc.end() || !fmt->is_string()) fail(source, "missing \"format\" (expected \"umf-field/1\")");
    if (fmt->get<std::string>() != kFieldFormat)
        fail(source, "format is \"" + fmt->get<std::string>() + "\", expected \"" + kFieldFormat + "\"");

    Field f;
    if (auto id = doc.find("id"); id != doc.end()) {
        if (!id->is_string()) fail(source, "\"id\" must be a string");
        f.id = id->get<std::string>();
    }
    if (auto screen = doc.find("screen"); screen != doc.end()) {
        if (!screen->is_string()) fail(source, "\"screen\" must be a string");
        f.screen = screen->get<std::string>();
        if (f.screen.size() > kMaxScreenNameBytes)
            fail(source, "\"screen\" is longer than " + std::to_string(kMaxScreenNameBytes) + " bytes");
    }
    f.width = integer_member(doc, "width", source);
    f.height = integer_member(doc, "height", source);
    f.window = integer_member(doc, "window", source);
    f.colors = integer_member(doc, "colors", source);
    if (f.width > kMaxFieldSide || f.height > kMaxFieldSide)
        fail(source, "size " + std::to_string(f.width) + " x " + std::to_string(f.height) + " is above the limit of " +
                         std::to_string(kMaxFieldSide) + " modules a side");
    if (f.window != 3 && f.window != 4) fail(source, "window must be 3 or 4, not " + std::to_string(f.window));
    if (f.colors < kMinColors || f.colors > kMaxColors)
        fail(source, "colors must be " + std::to_string(kMinColors) + ".." + std::to_string(kMaxColors) + ", not " +
                         std::to_string(f.colors));

    f.key = default_key(f.colors);
    if (auto key = doc.find("key"); key != doc.end()) {
        if (!key->is_string()) fail(source, "\"key\" must be \"modules\" or \"edges\"");
        auto k = key->get<std::string>();
        if (k == "modules")
            f.key = WindowKey::modules;
        else if (k == "edges")
            f.key = WindowKey::edges;
        else
            fail(source, "key is \"" + k + "\", expected \"modules\" or \"edges\"");
    }

    if (auto pal = doc.find("palette"); pal != doc.end()) {
        if (!pal->is_array()) fail(source, "\"palette\" must be an array of \"#rrggbb\" strings");
        for (const auto& c : *pal) {
            if (!c.is_string()) fail(source, "\"palette\" must be an array of \"#rrggbb\" strings");
            f.palette.push_back(c.get<std::string>());
        }
    } else {
        f.palette = grey_palette(f.colors);
    }

    auto rows = doc.find("rows");
    if (rows == doc.end() || !rows->is_array()) fail(source, "missing \"rows\" (an array of digit strings)");
    if (rows->size() != static_cast<std::size_t>(f.height))
        fail(source, "\"rows\" has " + std::to_string(rows->size()) + " rows but height is " +
                         std::to_string(f.height));
    f.modules.reserve(static_cast<std::size_t>(f.width) * f.height);
    for (std::size_t r = 0; r < rows->size(); ++r) {
        const auto& row = (*rows)[r];
        if (!row.is_string()) fail(source, "row " + std::to_string(r) + " is not a string");
        const auto& s = row.get_ref<const std::string&>();
        if (s.size() != static_cast<std::size_t>(f.width))
            fail(source, "row " + std::to_string(r) + " has " + std::to_string(s.size()) + " modules but width is " +
                             std::to_string(f.width));
        for (std::size_t c = 0; c < s.size(); ++c) {
            int v = s[c] - '0';
            if (v < 0 || v >= f.colors)
                fail(source, "row " + std::to_string(r) + ", column " + std::to_string(c) + ": '" +
                                 std::string(1, s[c]) + "' is not a digit 0.." + std::to_string(f.colors - 1));
            f.modules.push_back(static_cast<std::uint8_t>(v));
        }
    }
    if (auto problem = describe_invalid(f); !problem.empty()) fail(source, problem);
    return f;
}

Field load_field(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) fail(path, "cannot open the file");
    in.seekg(0, std::ios::end);
    auto size = in.tellg();
    if (size < 0) fail(path, "cannot read the file");
    if (static_cast<std::size_t>(size) > kMaxFieldFileBytes)
        fail(path, "file is " + std::to_string(static_cast<long long>(size)) + " bytes, more than the limit of " +
                       std::to_string(kMaxFieldFileBytes));
    in.seekg(0);
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    return parse_field(text, path);
}

std::string field_to_json(const Field& f) {
    if (auto problem = describe_invalid(f); !problem.empty())
        throw std::invalid_argument("cannot write an invalid field: " + problem);
    // Written by hand rather than json::dump so the rows stay one per line.
    std::ostringstream out;
    out << "{\n  \"format\": \"" << kFieldFormat << "\",\n";
    out << "  \"id\": " << json(f.id).dump() << ",\n";
    if (!f.screen.empty())
        out << "  \"screen\": " << json(f.screen).dump(-1, ' ', false, json::error_handler_t::replace) << ",\n";
    out << "  \"width\": " << f.width << ",\n  \"height\": " << f.height << ",\n";
    out << "  \"window\": " << f.window << ",\n  \"colors\": " << f.colors << ",\n";
    out << "  \"key\": \"" << to_string(f.key) << "\",\n";
    auto palette = f.palette.empty() ? grey_palette(f.colors) : f.palette;
    out << "  \"palette\": " << json(palette).dump() << ",\n";
    out << "  \"rows\": [\n";
    for (int r = 0; r < f.height; ++r) {
        out << "    \"";
        for (int c = 0; c < f.width; ++c) out << static_cast<char>('0' + f.at(r, c));
        out << (r + 1 < f.height ? "\",\n" : "\"\n");
    }
    out << "  ]\n}\n";
    return out.str();
}

void save_field(const Field& f, const std::string& path) {
    std::string text = field_to_json(f);
    try {
        write_file_atomically(path, text);
    } catch (const FileWriteError& e) {
        throw FieldFileError(e.what());
    }
}

}  // namespace umf
