// The presets a user can choose from: the built-ins, and the user's own in a
// file (normally $XDG_CONFIG_HOME/umf/presets.json). A user preset named like
// a built-in overrides it; the built-ins themselves are never changed, so
// "reset" can always bring one back. Every change is written to the file at
// once, atomically, and only then taken into memory: a failed write leaves
// both the file and the store as they were.
#pragma once

#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "shared/overlay/preset.hpp"

namespace umf::provider {

// A change the store refuses; the message names the preset (and the member,
// when a preset is invalid).
class PresetStoreError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

class PresetStore {
public:
    // Reads the user's presets from `path` when it exists; a missing file is
    // no user presets. Throws overlay::PresetError for a file that cannot be
    // read or holds an invalid preset, so a broken file is never overwritten
    // by the next save.
    explicit PresetStore(std::string path);

    // $XDG_CONFIG_HOME/umf/presets.json, else $HOME/.config/umf/presets.json.
    static std::string default_path();

    const std::string& path() const { return path_; }

    // The built-ins in their order (the user's version where overridden),
    // then the user's own presets in the file's order.
    std::vector<overlay::Preset> list() const;
    bool contains(std::string_view name) const;
    bool is_built_in(std::string_view name) const;
    // True for a built-in name the user has overridden.
    bool is_overridden(std::string_view name) const;
    // True for a preset held in the user's file (own or override).
    bool is_user(std::string_view name) const;
    // Throws PresetStoreError when there is no such preset.
    overlay::Preset get(std::string_view name) const;
    // The built-in as shipped, ignoring any override; throws when not built in.
    overlay::Preset built_in(std::string_view name) const;

    // Adds or replaces the user preset of that name (a built-in name makes an
    // override). Refuses an invalid preset.
    void save(const overlay::Preset& preset);
    // User presets only, not built-in names (overrides included: the
    // built-in would silently come back under the old name); refuses a new
    // name already in use or invalid.
    void rename(std::string_view old_name, const std::string& new_name);
    // User presets only; a built-in's override is dropped with reset().
    void remove(std::string_view name);
    // Drops the user's override of a built-in.
    void reset(std::string_view name);

private:
    void write(std::vector<overlay::Preset> user);

    std::string path_;
    std::vector<overlay::Preset> built_ins_;
    std::vector<overlay::Preset> user_;
};

}  // namespace umf::provider
