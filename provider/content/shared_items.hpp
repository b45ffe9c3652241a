// Resolver 2: files and URLs the user shared on purpose
// (`umf-provider share FILE|URL --rect x,y,w,h`), pinned to a region of a
// screen until removed. The most recently shared item is on top.
#pragma once

#include <filesystem>
#include <functional>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include "provider/board/board.hpp"
#include "provider/content/resolver.hpp"

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

    // Items kept from an earlier run of the provider (content/shared_items_file.hpp),
    // with their ids; each is checked as `add` checks it, and one that no
    // longer holds (a file gone) is left out. Returns how many came back.
    int restore(const std::vector<SharedItem>& kept);
    // Told the whole list after every change, under the list's lock, so
    // the calls come in the order of the changes.
    void on_change(std::function<void(const std::vector<SharedItem>&)> listener);

    const char* name() const override { return "shared"; }
    std::optional<Resolved> resolve(const ScreenPoint& point, Purpose purpose) const override;

private:
    static void check(SharedItem& item);

    mutable std::mutex mutex_;
    std::function<void(const std::vector<SharedItem>&)> listener_;
    std::vector<SharedItem> items_;
    int next_id_ = 1;
};

}  // namespace umf::provider
