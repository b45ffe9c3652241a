#include "provider/net/connection_registry.hpp"

namespace umf::provider {

void ConnectionRegistry::add(Connection* connection, std::weak_ptr<Connection> weak) {
    std::lock_guard lock(mutex_);
    connections_[connection] = std::move(weak);
}

void ConnectionRegistry::hand_over(Connection* from, Connection* to, std::weak_ptr<Connection> weak) {
    std::lock_guard lock(mutex_);
    connections_.erase(from);
    connections_[to] = std::move(weak);
}

void ConnectionRegistry::remove(Connection* connection) {
    std::lock_guard lock(mutex_);
    ended_ += connections_.erase(connection);
}

std::uint64_t ConnectionRegistry::ended() const {
    std::lock_guard lock(mutex_);
    return ended_;
}

std::vector<std::shared_ptr<Connection>> ConnectionRegistry::connections() const {
    std::lock_guard lock(mutex_);
    std::vector<std::shared_ptr<Connection>> out;
    for (const auto& [ptr, weak] : connections_)
        if (auto s = weak.lock()) out.push_back(std::move(s));
    return out;
}

std::size_t ConnectionRegistry::size() const {
    std::lock_guard lock(mutex_);
    return connections_.size();
}

}  // namespace umf::provider
