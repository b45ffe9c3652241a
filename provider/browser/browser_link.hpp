// The provider's end of the browser companion: a Unix socket (browser-PORT.sock
// in the runtime folder, this user only) where each browser's native-messaging
// host (browser/host) connects and relays its extension. One JSON object per
// line each way (docs/PROTOCOL.md, "Browser companion"):
//   host -> provider  {"type":"hello","browser":"chromium","version":"156","pid":4242}
//                     {"type":"windows","windows":[{"id":1,"left":0,"top":0,"width":1280,"height":800,
//                        "focused":true,"tab":{"id":7,"url":"https://...","title":"...","zoom":1}}]}
//                     {"type":"answer","req":3,...}
//   provider -> host  {"type":"<question>","req":3,...}   answered by an "answer" with the same req
//                     {"type":"error","message":"..."}    a message the provider could not take
// What a browser says is kept per connection and forgotten when it goes.
#pragma once

#include <chrono>
#include <condition_variable>
#include <filesystem>
#include <map>
#include <memory>
#include <mutex>
#include <nlohmann/json.hpp>
#include <optional>
#include <thread>
#include <vector>

#include "provider/browser/browser_windows.hpp"

namespace umf::provider {

class BrowserLink {
public:
    // Not listening yet: no browsers, every question unanswered.
    BrowserLink() = default;
    // Listens at `path` (see owner_socket.hpp), once. Throws std::runtime_error when it cannot.
    void listen(std::filesystem::path path);
    ~BrowserLink();
    BrowserLink(const BrowserLink&) = delete;
    BrowserLink& operator=(const BrowserLink&) = delete;

    const std::filesystem::path& path() const { return path_; }

    // The browsers connected now, as they last reported.
    std::vector<BrowserState> browsers() const;

    // Sends `question` (an object with "type"; "req" is set here) to the
    // browser on `connection` and waits for its answer. nullopt when the
    // browser is gone, cannot be written to or does not answer in time.
    std::optional<nlohmann::json> ask(int connection, nlohmann::json question, std::chrono::milliseconds timeout);

    // Longest line taken from a host; a longer one closes its connection.
    static constexpr std::size_t kMaxLine = 48 * 1024 * 1024;  // an image of 32 MiB in base64

private:
    struct Client;
    void serve();
    void accept_client();
    // false: the connection is to be closed.
    bool read_client(Client& client);
    void take_line(Client& client, const std::string& line);
    void drop_client(int connection);
    bool send_line(int connection, const std::string& line);

    std::filesystem::path path_;
    int listen_fd_ = -1;
    int wake_[2] = {-1, -1};
    std::thread thread_;

    mutable std::mutex mutex_;
    std::condition_variable answered_;
    std::map<int, std::shared_ptr<Client>> clients_;  // by connection id
    struct Pending {
        int connection = 0;
        std::optional<nlohmann::json> answer;  // nullopt: waiting; null: the browser went away
    };
    std::map<long long, Pending> answers_;  // by req
    long long next_req_ = 1;
    int next_connection_ = 1;
};

}  // namespace umf::provider
