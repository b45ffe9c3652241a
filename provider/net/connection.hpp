// One connection as the registry holds it, whatever it is doing: the TLS
// detection and handshake (DetectConnection), HTTP requests (HttpConnection) or the
// WebSocket (WebSocketConnection). Each hands the connection on to the next and
// the registry's entry with it, so the server stops every connection alike.
#pragma once

namespace umf::provider {

class Connection {
public:
    virtual ~Connection() = default;
    // From any thread: a WebSocket session closes with going_away (1001); an
    // open long poll is answered first; anything else is dropped, except a
    // response being written, which ends the connection when it is done.
    virtual void shutdown() = 0;
    // From any thread: drops the connection at once.
    virtual void abort() = 0;
};

}  // namespace umf::provider
