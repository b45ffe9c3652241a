// Resolver 2: files and URLs the user shared on purpose
// (`umf-provider share FILE|URL --rect x,y,w,h`), pinned to a region of a
// screen until removed. The most recently shared item is on top.
#pragma once

#include <filesystem>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "board/board.hpp"
#include "content/resolver.hpp"

namespace umf::provider {

struct SharedItem {
    int id = 0;  // given by SharedItems::add
    std::string title;
    std::optional<std::filesystem::path> file;  // absolute
    std::optional<std::string> url;
    int screen = 0;
    PixelRect rect;
};

class SharedItems : public Resolver {
public:
    inline static constexpr std::size_t kMaxItems = 256;

    // Validates (a title, exactly one of an existing regular file and an
    // http(s) URL, a non-empty rect) and returns the item's id. Throws
    // std::invalid_argument saying what is wrong, std::length_error when full.
    int add(SharedItem item);
    bool remove(int id);
    std::vector<SharedItem> items() const;

    const char* name() const override { return "shared"; }
    std::optional<Resolved> resolve(const ScreenPoint& point, Purpose purpose) const override;

private:
    mutable std::mutex mutex_;
    std::vector<SharedItem> items_;
    int next_id_ = 1;
};

}  // namespace umf::provider
