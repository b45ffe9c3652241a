// Where a screen's field comes from. The shipped fields are the same on
// every screen, so a phone paired with one screen that points at another
// would find that screen's field and take what its own screen shows there.
// A screen of its own shows fields generated for it alone: the shipped
// field's size and kind, from the screen's own seed (kept as `field-seed` in
// its configuration directory), each kept in `fields/` there once made, so
// that the screen keeps its field even if a later generator would make
// another from the same seed. docs/ARCHITECTURE.md, "A field of its own",
// has the measurements behind it.
#pragma once

#include <cstdint>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <string>

#include "shared/field/field.hpp"

namespace umf::provider {

class FieldSource {
public:
    // The shipped fields, as they are.
    FieldSource() = default;
    // Fields generated from `seed` (not 0), kept in `keep_dir` (empty: made
    // again by each process, as tests do), naming `screen` as the screen
    // they belong to (what a printed field says).
    FieldSource(std::uint64_t seed, std::filesystem::path keep_dir, std::string screen = {});

    bool own() const { return seed_ != 0; }
    std::uint64_t seed() const { return seed_; }

    // The field to show where the shipped `shipped_file` (a path) would be
    // shown, and the file it is kept in (the shipped file itself, or the kept
    // one; empty when not kept). Throws std::runtime_error when a field
    // cannot be read, made or kept.
    struct Chosen {
        Field field;
        std::string file;
    };
    Chosen field_for(const std::string& shipped_file) const;

private:
    std::uint64_t seed_ = 0;
    std::filesystem::path keep_dir_;
    std::string screen_;
    // Made once per process and shipped file: a multi-screen layout asks for
    // the same size many times while it searches a module size.
    struct Made {
        std::mutex mutex;
        std::map<std::string, Chosen> by_shipped_file;
    };
    std::shared_ptr<Made> made_ = std::make_shared<Made>();
};

// The screen's own source in `config_dir`: its `field-seed` (16 hex digits),
// made at random the first time; fields kept in `config_dir/fields`, naming
// this machine (screen_name()) as their screen. Throws std::runtime_error
// when the seed cannot be read or written.
FieldSource own_field_source(const std::filesystem::path& config_dir);

// A new seed for the screen in `config_dir` (`pair --rotate --field`): the
// fields made from the old one are removed. Returns the new source.
FieldSource rotate_field_seed(const std::filesystem::path& config_dir);

}  // namespace umf::provider
