#include "provider/screen/field_source.hpp"

#include <cstdio>
#include <fstream>
#include <random>
#include <sstream>
#include <stdexcept>

#include "provider/common/screen_name.hpp"
#include "shared/field/field_io.hpp"
#include "shared/field/generator.hpp"
#include "shared/io/atomic_file.hpp"

namespace umf::provider {

namespace fs = std::filesystem;

namespace {

constexpr const char* kSeedFile = "field-seed";
constexpr const char* kKeptDir = "fields";

std::string hex16(std::uint64_t v) {
    char text[17];
    std::snprintf(text, sizeof text, "%016llx", static_cast<unsigned long long>(v));
    return text;
}

std::uint64_t random_seed() {
    std::random_device device;
    std::uint64_t seed = 0;
    while (seed == 0) seed = (std::uint64_t{device()} << 32) ^ device();
    return seed;
}

// The seed in `file`, or 0 when there is none.
std::uint64_t read_seed(const fs::path& file) {
    std::ifstream in(file);
    if (!in) return 0;
    std::string text;
    in >> text;
    std::size_t used = 0;
    std::uint64_t seed = 0;
    try {
        seed = std::stoull(text, &used, 16);
    } catch (const std::exception&) {
        used = 0;
    }
    if (text.size() != 16 || used != 16 || seed == 0)
        throw std::runtime_error(file.string() + ": not a field seed (16 hex digits, not all zero); remove it to make "
                                                 "a new one, which changes the screen's field");
    return seed;
}

void write_seed(const fs::path& config_dir, std::uint64_t seed) {
    std::error_code ec;
    fs::create_directories(config_dir, ec);
    try {
        write_file_atomically((config_dir / kSeedFile).string(), hex16(seed) + "\n");
    } catch (const std::exception& e) {
        throw std::runtime_error(std::string("cannot keep the screen's field seed: ") + e.what());
    }
}

// The shipped field's size and kind from `seed`, named `id`.
Field generate_like(const Field& shipped, std::uint64_t seed, const std::string& id) {
    GeneratorOptions o;
    o.width = shipped.width;
    o.height = shipped.height;
    o.window = shipped.window;
    o.colors = shipped.colors;
    o.key = shipped.key;
    o.seed = seed;
    o.id = id;
    // The shipped sizes are made in well under a second; the limit only
    // keeps a screen from hanging on a size the generator cannot finish.
    o.time_limit_s = 60;
    GeneratorResult r = generate_field(o);
    if (!r.complete) throw std::runtime_error("no field of " + o.id + " could be made");
    return std::move(r.field);
}

}  // namespace

FieldSource::FieldSource(std::uint64_t seed, fs::path keep_dir, std::string screen)
    : seed_(seed), keep_dir_(std::move(keep_dir)), screen_(std::move(screen)) {}

FieldSource::Chosen FieldSource::field_for(const std::string& shipped_file) const {
    if (!own()) return {load_field(shipped_file), shipped_file};
    std::lock_guard<std::mutex> lock(made_->mutex);
    if (auto it = made_->by_shipped_file.find(shipped_file); it != made_->by_shipped_file.end()) return it->second;
    const Field shipped = load_field(shipped_file);
    const std::string id = default_field_id(shipped.width, shipped.height, shipped.window, shipped.colors, shipped.key) +
                           "-" + hex16(seed_);
    Chosen chosen;
    const fs::path kept = keep_dir_.empty() ? fs::path() : keep_dir_ / (id + ".json");
    std::error_code ec;
    if (!kept.empty() && fs::exists(kept, ec)) {
        chosen = {load_field(kept.string()), kept.string()};
        if (!screen_.empty() && chosen.field.screen != screen_) {
            // Kept before fields named their screen, or the machine was
            // renamed: the file says so from now on, where it can be written.
            chosen.field.screen = screen_;
            try {
                save_field(chosen.field, kept.string());
            } catch (const std::exception&) {
                // A read-only configuration still shows its field.
            }
        }
    } else {
        chosen.field = generate_like(shipped, seed_, id);
        chosen.field.screen = screen_;
        if (!kept.empty()) {
            fs::create_directories(keep_dir_, ec);
            try {
                save_field(chosen.field, kept.string());
            } catch (const std::exception& e) {
                throw std::runtime_error(std::string("cannot keep the screen's field: ") + e.what());
            }
            chosen.file = kept.string();
        }
    }
    made_->by_shipped_file[shipped_file] = chosen;
    return chosen;
}

FieldSource own_field_source(const fs::path& config_dir) {
    std::uint64_t seed = read_seed(config_dir / kSeedFile);
    if (seed == 0) {
        seed = random_seed();
        write_seed(config_dir, seed);
    }
    return FieldSource(seed, config_dir / kKeptDir, screen_name());
}

FieldSource rotate_field_seed(const fs::path& config_dir) {
    std::error_code ec;
    fs::remove_all(config_dir / kKeptDir, ec);
    const std::uint64_t seed = random_seed();
    write_seed(config_dir, seed);
    return FieldSource(seed, config_dir / kKeptDir, screen_name());
}

}  // namespace umf::provider
