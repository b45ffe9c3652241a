// The provider's server: an io_context with its threads, the TLS context, the
// listener and the live connections, serving a MessageHandler's sessions and
// HttpRoutes. Start, then stop (or destroy) from the
// thread that started it.
#pragma once

#include <boost/asio/io_context.hpp>
#include <boost/asio/ssl/context.hpp>
#include <chrono>
#include <memory>
#include <string>
#include <thread>
#include <vector>

#include "provider/net/api_sessions.hpp"
#include "provider/net/http_routes.hpp"
#include "provider/net/message_handler.hpp"
#include "provider/trust/tls_identity.hpp"

namespace umf::provider {

class HeapTrimmer;
class Listener;
class ConnectionRegistry;

struct ServerOptions {
    std::string bind_address = "127.0.0.1";
    unsigned short port = 0;  // 0: any free port (see Server::port)
    int threads = 2;
    // Connections at once (WebSocket sessions and HTTPS downloads); more are
    // closed as they arrive.
    std::size_t max_connections = 1024;
    // The HTTPS transport's sessions (docs/PROTOCOL.md, "HTTPS transport").
    ApiSessionOptions api_sessions;
};

class Server {
public:
    Server(std::shared_ptr<const MessageHandler> handler, std::shared_ptr<const HttpRoutes> routes,
           const TlsIdentity& identity, ServerOptions options = {});
    ~Server();
    Server(const Server&) = delete;
    Server& operator=(const Server&) = delete;

    // Binds, listens and starts the threads. Throws std::runtime_error naming
    // the address when it cannot bind.
    void start();
    // The port listened on, once started.
    unsigned short port() const { return port_; }
    // Stops accepting, closes every WebSocket session with going_away (1001)
    // and waits up to `grace` for the closing handshakes before dropping
    // what is left; returns when the threads have ended.
    void stop(std::chrono::milliseconds grace = std::chrono::milliseconds(2000));
    // Connections open (WebSocket sessions, HTTPS requests and polls).
    std::size_t connection_count() const;
    // The HTTPS transport's sessions.
    const ApiSessions& api_sessions() const { return *api_sessions_; }
    // Connections from now on are served `identity` (a serving certificate
    // issued again); open ones keep theirs. Throws TlsIdentityError.
    void replace_identity(const TlsIdentity& identity) { identity_.replace(identity); }

private:
    std::shared_ptr<const MessageHandler> handler_;
    std::shared_ptr<const HttpRoutes> routes_;
    ServerOptions options_;
    boost::asio::io_context io_;
    CurrentIdentity identity_;  // before tls_, which calls into it
    boost::asio::ssl::context tls_;
    std::shared_ptr<ConnectionRegistry> registry_;
    std::shared_ptr<ApiSessions> api_sessions_;
    std::shared_ptr<Listener> listener_;
    std::shared_ptr<HeapTrimmer> trimmer_;
    std::vector<std::thread> threads_;
    unsigned short port_ = 0;
    bool running_ = false;
};

}  // namespace umf::provider
