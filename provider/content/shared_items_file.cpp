#include "provider/content/shared_items_file.hpp"

#include <sys/stat.h>

#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace umf::provider {

using nlohmann::json;

void save_shared_items(const std::filesystem::path& file, const std::vector<SharedItem>& items) {
    json list = json::array();
    for (const auto& item : items) {
        json entry{{"id", item.id},
                   {"title", item.title},
                   {"screen", item.screen},
                   {"rect", {item.rect.x, item.rect.y, item.rect.width, item.rect.height}}};
        if (item.file) entry["file"] = item.file->string();
        if (item.url) entry["url"] = *item.url;
        list.push_back(std::move(entry));
    }
    const auto partial = std::filesystem::path(file.string() + ".partial");
    {
        const mode_t old_mask = ::umask(077);
        std::ofstream out(partial, std::ios::binary | std::ios::trunc);
        ::umask(old_mask);
        out << list.dump() << "\n";
        if (!out.flush()) throw std::runtime_error("cannot write " + partial.string());
    }
    std::error_code ec;
    std::filesystem::rename(partial, file, ec);
    if (ec) throw std::runtime_error("cannot write " + file.string() + ": " + ec.message());
}

std::vector<SharedItem> load_shared_items(const std::filesystem::path& file) {
    std::ifstream in(file, std::ios::binary);
    if (!in) return {};
    std::vector<SharedItem> items;
    try {
        const json list = json::parse(in);
        if (!list.is_array()) throw std::runtime_error(file.string() + " is not a list of shared items");
        for (const auto& entry : list) {
            SharedItem item;
            item.id = entry.at("id").get<int>();
            item.title = entry.at("title").get<std::string>();
            item.screen = entry.at("screen").get<int>();
            const auto& r = entry.at("rect");
            item.rect = {r.at(0).get<int>(), r.at(1).get<int>(), r.at(2).get<int>(), r.at(3).get<int>()};
            if (entry.contains("file")) item.file = std::filesystem::path(entry.at("file").get<std::string>());
            if (entry.contains("url")) item.url = entry.at("url").get<std::string>();
            items.push_back(std::move(item));
        }
    } catch (const json::exception& e) {
        throw std::runtime_error(file.string() + " is not a list of shared items: " + e.what());
    }
    return items;
}

}  // namespace umf::provider
