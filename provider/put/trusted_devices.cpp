#include "provider/put/trusted_devices.hpp"

#include <algorithm>
#include <fstream>
#include <iterator>
#include <nlohmann/json.hpp>

#include "shared/io/atomic_file.hpp"

namespace umf::provider {

namespace {
constexpr const char* kFormat = "umf-trusted-devices/1";
constexpr std::size_t kMaxFileBytes = 256 * 1024;
}  // namespace

TrustedDevices::TrustedDevices(std::filesystem::path file) : file_(std::move(file)) {
    if (file_.empty()) return;
    std::ifstream in(file_, std::ios::binary);
    if (!in) return;
    std::string text;
    char buffer[4096];
    while (in.read(buffer, sizeof buffer) || in.gcount() > 0) {
        text.append(buffer, static_cast<std::size_t>(in.gcount()));
        if (text.size() > kMaxFileBytes) return;
    }
    const auto doc = nlohmann::json::parse(text, nullptr, /*allow_exceptions=*/false);
    if (!doc.is_object() || doc.value("format", "") != kFormat) return;
    const auto it = doc.find("devices");
    if (it == doc.end() || !it->is_array()) return;
    for (const auto& d : *it) {
        if (!d.is_string()) continue;
        const auto& name = d.get_ref<const std::string&>();
        if (name.empty() || devices_.count(name)) continue;
        devices_.insert(name);
        order_.push_back(name);
    }
    if (const auto open = doc.find("open_files"); open != doc.end() && open->is_array())
        for (const auto& d : *open)
            if (d.is_string() && devices_.count(d.get_ref<const std::string&>()))
                open_files_.insert(d.get_ref<const std::string&>());
    while (order_.size() > kMaxTrustedDevices) {
        devices_.erase(order_.front());
        open_files_.erase(order_.front());
        order_.erase(order_.begin());
    }
}

std::optional<PutAnswer> TrustedDevices::files_answer(std::string_view device) const {
    if (device.empty()) return std::nullopt;
    std::lock_guard lock(mutex_);
    if (devices_.find(device) == devices_.end()) return std::nullopt;
    return open_files_.find(device) != open_files_.end() ? PutAnswer::open : PutAnswer::save;
}

bool TrustedDevices::contains(std::string_view device) const {
    if (device.empty()) return false;
    std::lock_guard lock(mutex_);
    return devices_.find(device) != devices_.end();
}

bool TrustedDevices::add(const std::string& device, std::optional<PutAnswer> files) {
    if (device.empty() || files == PutAnswer::dismiss) return false;
    std::lock_guard lock(mutex_);
    const bool known = devices_.count(device) > 0;
    const bool opened_before = open_files_.count(device) > 0;
    const bool open = files ? *files == PutAnswer::open : opened_before;
    if (known && open == opened_before) return true;
    if (!known) {
        devices_.insert(device);
        order_.push_back(device);
    }
    if (open)
        open_files_.insert(device);
    else
        open_files_.erase(device);
    while (order_.size() > kMaxTrustedDevices) {
        devices_.erase(order_.front());
        open_files_.erase(order_.front());
        order_.erase(order_.begin());
    }
    return save_locked();
}

bool TrustedDevices::remove(const std::string& device) {
    std::lock_guard lock(mutex_);
    if (!devices_.erase(device)) return true;
    open_files_.erase(device);
    order_.erase(std::remove(order_.begin(), order_.end(), device), order_.end());
    return save_locked();
}

std::size_t TrustedDevices::size() const {
    std::lock_guard lock(mutex_);
    return devices_.size();
}

bool TrustedDevices::save_locked() const {
    if (file_.empty()) return true;
    nlohmann::ordered_json doc;
    doc["format"] = kFormat;
    doc["devices"] = order_;
    // In the order of "devices", so the file reads the same after each rewrite.
    std::vector<std::string> open;
    for (const auto& d : order_)
        if (open_files_.count(d)) open.push_back(d);
    if (!open.empty()) doc["open_files"] = open;
    try {
        std::error_code ec;
        std::filesystem::create_directories(file_.parent_path(), ec);
        write_file_atomically(file_.string(), doc.dump(2) + "\n");
        return true;
    } catch (const std::exception&) {
        return false;
    }
}

}  // namespace umf::provider
