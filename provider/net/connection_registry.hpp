// The live connections of a server, so a shutdown can reach each of them.
#pragma once

#include <cstddef>
#include <cstdint>
#include <memory>
#include <mutex>
#include <unordered_map>
#include <vector>

#include "provider/net/connection.hpp"

namespace umf::provider {

// The live connections, by address. A connection adds itself when it starts,
// hands its entry on when it changes role (detection to HTTP to WebSocket)
// and removes it when its last role is destroyed: one entry and one end per
// connection.
class ConnectionRegistry {
public:
    void add(Connection* connection, std::weak_ptr<Connection> weak);
    // `from`'s entry is now `to`'s; no connection ended.
    void hand_over(Connection* from, Connection* to, std::weak_ptr<Connection> weak);
    // Nothing when `connection` handed its entry on.
    void remove(Connection* connection);
    // The connections still alive.
    std::vector<std::shared_ptr<Connection>> connections() const;
    std::size_t size() const;
    // Connections ended since the registry was made (the heap trimmer's cue).
    std::uint64_t ended() const;

private:
    mutable std::mutex mutex_;
    std::unordered_map<Connection*, std::weak_ptr<Connection>> connections_;
    std::uint64_t ended_ = 0;
};

}  // namespace umf::provider
