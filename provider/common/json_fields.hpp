// Fields of JSON from outside the provider (a compositor's answers, Sway's
// tree and Hyprland's clients, the browser companion's messages), read
// leniently: a missing or mistyped field is empty or zero, never an
// exception, since what they send is not the provider's to trust.
#pragma once

#include <nlohmann/json.hpp>
#include <string>

namespace umf::provider {

inline std::string json_text(const nlohmann::json& node, const char* key) {
    const auto it = node.find(key);
    return it != node.end() && it->is_string() ? it->get<std::string>() : std::string();
}

inline int json_int(const nlohmann::json& node, const char* key, int otherwise = 0) {
    const auto it = node.find(key);
    return it != node.end() && it->is_number() ? static_cast<int>(it->get<double>()) : otherwise;
}

}  // namespace umf::provider
