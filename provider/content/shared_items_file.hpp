// The shared items written to a file, so that a provider started again by
// its keeper (commands/desktop_keeper.hpp) serves what was shared before.
// Owner-only, replaced whole on every change.
#pragma once

#include <filesystem>
#include <vector>

#include "provider/content/shared_items.hpp"

namespace umf::provider {

// Writes beside and renames, so a reader sees the old list or the new one.
// Throws std::runtime_error naming the file when it cannot be written.
void save_shared_items(const std::filesystem::path& file, const std::vector<SharedItem>& items);

// No file: no items. Throws std::runtime_error naming the file when it is
// not a list of shared items.
std::vector<SharedItem> load_shared_items(const std::filesystem::path& file);

}  // namespace umf::provider
