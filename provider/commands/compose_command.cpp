#include "provider/commands/compose_command.hpp"

#include <QBuffer>
#include <QByteArray>
#include <QImage>
#include <QImageReader>
#include <QString>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <system_error>
#include <vector>

#include "provider/board/board.hpp"
#include "provider/commands/preset_options.hpp"
#include "provider/screen/screen_field.hpp"
#include "provider/screen/screen_image.hpp"
#include "shared/field/field_io.hpp"
#include "shared/io/atomic_file.hpp"
#include "shared/overlay/preset.hpp"
#include "shared/overlay/pulse.hpp"

namespace umf::provider {

const char* const kComposeUsage = R"(umf-provider compose: the screen as shown at a moment, and where its field lies

usage:
  umf-provider compose (--content SCREEN.png | --board BOARD.json | both) --preset NAME
                       --time T --out OUT.png --map MAP.json [--screen WxH]
                       [preset settings]

--content  a screenshot to mix the field into; its size is the screen's
           (at most 16384 pixels a side)
--board    a board file (umf-board/1): the board window, shown full screen,
           covers the content
--screen   the screen size when there is no --content (default 1920x1080)
--preset   a built-in preset (subtle, balanced, visible, static, kiosk,
           invisible) or one of presets.json in the configuration directory
--opacity-min A --opacity-max A --period S --waveform sine|triangle --blur B
--region full|focus --focus-radius M --activation always|on_demand --fade S
--palette #rrggbb,#rrggbb
           change the preset's settings, as for the provider; --blur B blurs
           the content under the field (0..1, at 1 a Gaussian of half a
           module) before the field is mixed in. --module-px P is the
           module size (as on a 96 dpi screen, as the headless provider
           places the field); the smallest shipped field that covers the
           screen at that size is used, or larger modules where none does.
--time     seconds since the pulse started; the opacity is the preset's at
           that time, as while a requester is aiming
--out      the screen image: PNG, 8-bit RGB
--map      JSON: {"field": <field file>, "field_id", "origin": [x, y],
           "module_px", "opacity", "blur", "screen": [w, h], "preset", "time"};
           screen pixel = origin + module_px * (u, v) for field point (u, v).
           A field turned for a portrait screen is written beside it as
           <map name>.field.json.

exit codes: 0 success; 2 wrong usage; 3 the content, board, presets or field
            could not be read or are invalid; 4 OUT.png or MAP.json could not
            be written.
)";

namespace {

namespace fs = std::filesystem;
using cli::UsageError;

// Raised for the inputs' faults; run_compose turns it into exit code 3.
struct InputError : std::runtime_error {
    using std::runtime_error::runtime_error;
};

std::string required(const cli::Args& args, const char* name) {
    auto v = cli::get(args, name);
    if (!v) throw UsageError(std::string("compose needs --") + name);
    if (v->empty()) throw UsageError(std::string("--") + name + " must not be empty");
    return *v;
}

QSize screen_option(const std::string& text) {
    const auto x = text.find('x');
    if (x == std::string::npos) throw UsageError("--screen must be WxH, for example 1920x1080, not '" + text + "'");
    const auto w = cli::to_integer("screen", text.substr(0, x), 1, kMaxScreenSide);
    const auto h = cli::to_integer("screen", text.substr(x + 1), 1, kMaxScreenSide);
    return QSize(static_cast<int>(w), static_cast<int>(h));
}

overlay::Preset choose_preset(const std::string& name, const fs::path& config_dir) {
    std::vector<overlay::Preset> presets;
    const fs::path user_file = config_dir / "presets.json";
    std::error_code ec;
    if (fs::exists(user_file, ec)) {
        try {
            presets = overlay::load_presets(user_file.string());
        } catch (const overlay::PresetError& e) {
            throw InputError(e.what());
        }
    }
    for (auto& p : overlay::built_in_presets())
        if (!overlay::find_preset(presets, p.name)) presets.push_back(std::move(p));
    if (const overlay::Preset* p = overlay::find_preset(presets, name)) return *p;
    std::string names;
    for (const auto& p : presets) names += (names.empty() ? "" : ", ") + p.name;
    throw UsageError("unknown preset \"" + name + "\"; available: " + names);
}

QImage read_content(const std::string& path) {
    std::error_code ec;
    if (!fs::is_regular_file(path, ec)) throw InputError("content " + path + ": no such file");
    QImageReader reader(QString::fromStdString(path));
    const QSize size = reader.size();
    if (!size.isValid())
        throw InputError("content " + path + " is not an image that can be read (" +
                         reader.errorString().toStdString() + ")");
    if (size.width() > kMaxScreenSide || size.height() > kMaxScreenSide || size.isEmpty())
        throw InputError("content " + path + " is " + std::to_string(size.width()) + " x " +
                         std::to_string(size.height()) + " pixels; 1 to " + std::to_string(kMaxScreenSide) +
                         " a side are accepted");
    // Qt's default allocation limit (256 MB) is below a 16384 x 16384 RGBA
    // screen; the size was checked above.
    reader.setAllocationLimit(0);
    QImage image = reader.read();
    if (image.isNull())
        throw InputError("content " + path + " cannot be decoded: " + reader.errorString().toStdString());
    return image;
}

// The same field as the shipped file holds, module for module.
bool same_field(const Field& a, const Field& b) {
    return a.id == b.id && a.width == b.width && a.height == b.height && a.window == b.window &&
           a.colors == b.colors && a.key == b.key && a.palette == b.palette && a.modules == b.modules;
}

fs::path absolute_path(const fs::path& p) { return fs::absolute(p).lexically_normal(); }

int compose(const cli::Args& args, const fs::path& config_dir) {
    if (!args.positional.empty()) throw UsageError("compose: unexpected argument " + args.positional.front());
    for (const auto& flag : args.flags)
        if (flag != "shipped-field" && flag != "own-field") throw UsageError("compose: unexpected flag --" + flag);
    const auto content_path = cli::get(args, "content");
    const auto board_path = cli::get(args, "board");
    if (!content_path && !board_path) throw UsageError("compose needs --content or --board (or both)");
    if (content_path && content_path->empty()) throw UsageError("--content must not be empty");
    if (board_path && board_path->empty()) throw UsageError("--board must not be empty");
    const std::string preset_name = required(args, "preset");
    const double time = cli::to_number("time", required(args, "time"), -1e9, 1e9);
    const fs::path out_path = required(args, "out");
    const fs::path map_path = required(args, "map");
    std::optional<QSize> screen_given;
    if (auto s = cli::get(args, "screen")) screen_given = screen_option(*s);
    const overlay::Preset preset = apply_preset_options(choose_preset(preset_name, config_dir), args);

    std::optional<QImage> content;
    QSize screen = screen_given.value_or(QSize(1920, 1080));
    if (content_path) {
        content = read_content(*content_path);
        if (screen_given && *screen_given != content->size())
            throw UsageError("--screen " + cli::get(args, "screen").value() + " differs from the content's " +
                             std::to_string(content->width()) + "x" + std::to_string(content->height()));
        screen = content->size();
    }
    std::optional<Board> board;
    if (board_path) {
        try {
            board = load_board(*board_path);
        } catch (const BoardError& e) {
            throw InputError(e.what());
        }
    }

    ScreenField field;
    bool shipped_unchanged = false;
    try {
        // The preset's module size as on a 96 dpi screen, as the headless
        // provider places it (serve_command.cpp).
        // The field the provider of this configuration shows, made and
        // kept there if it is not yet; with --shipped-field the shipped one.
        const FieldSource fields = cli::has_flag(args, "shipped-field") ? FieldSource() : own_field_source(config_dir);
        field = screen_field_for(screen.width(), screen.height(), preset.module_px, fields);
        shipped_unchanged = same_field(field.field, load_field(field.file));
    } catch (const std::runtime_error& e) {
        throw InputError(std::string("the screen's field: ") + e.what());
    }
    // A requester is taken to be aiming, so an on-demand preset is fully up.
    const double opacity = overlay::opacity_at(preset, time);
    QImage shown;
    try {
        shown = compose_screen(content ? &*content : nullptr, board ? &*board : nullptr, screen, field, opacity,
                               preset.palette, preset.blur);
    } catch (const std::invalid_argument& e) {
        throw InputError(std::string("preset \"") + preset.name + "\": " + e.what());
    }

    QByteArray png;
    QBuffer buffer(&png);
    buffer.open(QIODevice::WriteOnly);
    if (!shown.save(&buffer, "PNG")) throw FileWriteError(out_path.string() + ": the PNG could not be encoded");
    write_file_atomically(out_path.string(), std::string(png.constData(), static_cast<std::size_t>(png.size())));

    fs::path field_file = absolute_path(field.file);
    if (!shipped_unchanged) {
        field_file = absolute_path(map_path).parent_path() / (map_path.stem().string() + ".field.json");
        try {
            save_field(field.field, field_file.string());
        } catch (const FieldFileError& e) {
            throw FileWriteError(e.what());
        }
    }
    nlohmann::ordered_json map;
    map["field"] = field_file.string();
    map["field_id"] = field.field.id;
    map["origin"] = {field.placement.origin_x, field.placement.origin_y};
    map["module_px"] = field.placement.module_px;
    map["opacity"] = opacity;
    map["blur"] = preset.blur;
    map["screen"] = {screen.width(), screen.height()};
    map["preset"] = preset.name;
    map["time"] = time;
    write_file_atomically(map_path.string(), map.dump(2) + "\n");
    return 0;
}

}  // namespace

std::vector<std::string> compose_options() {
    std::vector<std::string> options = {"content", "board", "preset", "time", "out", "map", "screen", "config-dir"};
    for (const auto& o : preset_setting_options()) options.push_back(o);
    return options;
}

std::vector<std::string> compose_flags() { return {"shipped-field", "own-field"}; }

int run_compose(const cli::Args& args, const fs::path& config_dir) {
    try {
        return compose(args, config_dir);
    } catch (const InputError& e) {
        std::cerr << "umf-provider compose: " << e.what() << "\n";
        return kComposeInputError;
    } catch (const FileWriteError& e) {
        std::cerr << "umf-provider compose: " << e.what() << "\n";
        return kComposeOutputError;
    }
}

}  // namespace umf::provider
