#include "provider/tuning/preset_store.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <system_error>

namespace umf::provider {

namespace {

using overlay::Preset;

std::string preset_named(std::string_view name) { return "preset \"" + std::string(name) + "\""; }

std::vector<Preset>::iterator find_in(std::vector<Preset>& presets, std::string_view name) {
    return std::find_if(presets.begin(), presets.end(), [&](const Preset& p) { return p.name == name; });
}

}  // namespace

PresetStore::PresetStore(std::string path) : path_(std::move(path)), built_ins_(overlay::built_in_presets()) {
    std::error_code ec;
    if (std::filesystem::exists(path_, ec)) user_ = overlay::load_presets(path_);
}

std::string PresetStore::default_path() {
    const char* xdg = std::getenv("XDG_CONFIG_HOME");
    // The XDG spec says a relative value is to be ignored.
    std::filesystem::path base;
    if (xdg && *xdg && std::filesystem::path(xdg).is_absolute()) {
        base = xdg;
    } else {
        const char* home = std::getenv("HOME");
        base = std::filesystem::path(home && *home ? home : ".") / ".config";
    }
    return (base / "umf" / "presets.json").string();
}

std::vector<Preset> PresetStore::list() const {
    std::vector<Preset> out;
    for (const auto& b : built_ins_) {
        const Preset* own = overlay::find_preset(user_, b.name);
        out.push_back(own ? *own : b);
    }
    for (const auto& u : user_)
        if (!overlay::find_preset(built_ins_, u.name)) out.push_back(u);
    return out;
}

bool PresetStore::contains(std::string_view name) const { return is_built_in(name) || is_user(name); }
bool PresetStore::is_built_in(std::string_view name) const { return overlay::find_preset(built_ins_, name); }
bool PresetStore::is_user(std::string_view name) const { return overlay::find_preset(user_, name); }
bool PresetStore::is_overridden(std::string_view name) const { return is_built_in(name) && is_user(name); }

Preset PresetStore::get(std::string_view name) const {
    if (const Preset* own = overlay::find_preset(user_, name)) return *own;
    if (const Preset* b = overlay::find_preset(built_ins_, name)) return *b;
    throw PresetStoreError("there is no " + preset_named(name));
}

Preset PresetStore::built_in(std::string_view name) const {
    if (const Preset* b = overlay::find_preset(built_ins_, name)) return *b;
    throw PresetStoreError(preset_named(name) + " is not a built-in preset");
}

void PresetStore::save(const Preset& preset) {
    if (auto problem = overlay::describe_invalid(preset); !problem.empty())
        throw PresetStoreError("cannot save " + preset_named(preset.name) + ": " + problem);
    std::vector<Preset> user = user_;
    if (auto it = find_in(user, preset.name); it != user.end()) {
        *it = preset;
    } else {
        if (user.size() >= overlay::kMaxPresets)
            throw PresetStoreError("cannot save " + preset_named(preset.name) + ": already " +
                                   std::to_string(overlay::kMaxPresets) + " user presets, the limit");
        user.push_back(preset);
    }
    write(std::move(user));
}

void PresetStore::rename(std::string_view old_name, const std::string& new_name) {
    if (is_built_in(old_name))
        throw PresetStoreError("cannot rename the built-in " + preset_named(old_name) +
                               "; save it under a new name instead");
    std::vector<Preset> user = user_;
    auto it = find_in(user, old_name);
    if (it == user.end()) throw PresetStoreError("cannot rename " + preset_named(old_name) + ": there is no such preset");
    if (new_name == old_name) return;
    if (contains(new_name))
        throw PresetStoreError("cannot rename " + preset_named(old_name) + " to \"" + new_name + "\": that name is taken");
    it->name = new_name;
    if (auto problem = overlay::describe_invalid(*it); !problem.empty())
        throw PresetStoreError("cannot rename " + preset_named(old_name) + ": " + problem);
    write(std::move(user));
}

void PresetStore::remove(std::string_view name) {
    if (is_built_in(name))
        throw PresetStoreError("cannot delete the built-in " + preset_named(name) +
                               (is_user(name) ? "; reset it to drop your changes" : ""));
    std::vector<Preset> user = user_;
    auto it = find_in(user, name);
    if (it == user.end()) throw PresetStoreError("cannot delete " + preset_named(name) + ": there is no such preset");
    user.erase(it);
    write(std::move(user));
}

void PresetStore::reset(std::string_view name) {
    if (!is_built_in(name)) throw PresetStoreError("cannot reset " + preset_named(name) + ": it is not a built-in preset");
    std::vector<Preset> user = user_;
    auto it = find_in(user, name);
    if (it == user.end()) throw PresetStoreError("cannot reset " + preset_named(name) + ": it has no changes to drop");
    user.erase(it);
    write(std::move(user));
}

void PresetStore::write(std::vector<Preset> user) {
    std::error_code ec;
    const auto dir = std::filesystem::path(path_).parent_path();
    if (!dir.empty()) std::filesystem::create_directories(dir, ec);
    if (ec) throw PresetStoreError("cannot create " + dir.string() + ": " + ec.message());
    try {
        overlay::save_presets(user, path_);
    } catch (const std::exception& e) {
        throw PresetStoreError(e.what());
    }
    user_ = std::move(user);
}

}  // namespace umf::provider
