#include "provider/browser/browser_link.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <iostream>
#include <stdexcept>

#include "provider/common/owner_socket.hpp"
#include "shared/protocol/json_checks.hpp"

namespace umf::provider {

namespace {

using json = nlohmann::json;
constexpr std::size_t kMaxClients = 32;

bool write_all(int fd, const std::string& data) {
    std::size_t done = 0;
    while (done < data.size()) {
        const ssize_t n = ::send(fd, data.data() + done, data.size() - done, MSG_NOSIGNAL);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        done += static_cast<std::size_t>(n);
    }
    return true;
}

std::string error_line(const std::string& what) { return json{{"type", "error"}, {"message", what}}.dump() + "\n"; }

}  // namespace

struct BrowserLink::Client {
    int fd = -1;
    std::string buffer;
    BrowserState state;
    std::mutex write_mutex;  // lines from ask() and from the link's thread never interleave
    ~Client() {
        if (fd >= 0) ::close(fd);
    }
};

void BrowserLink::listen(std::filesystem::path path) {
    if (listen_fd_ >= 0) throw std::logic_error("the browser link listens already");
    path_ = std::move(path);
    // A provider on the same port would have failed to serve; a socket file
    // here is one a provider left when it died.
    listen_fd_ = listen_owner_only(path_, nullptr);
    open_wake_pipe(wake_, listen_fd_, path_);
    thread_ = std::thread([this] { serve(); });
}

BrowserLink::~BrowserLink() {
    if (listen_fd_ < 0) return;
    const char c = 0;
    [[maybe_unused]] auto n = ::write(wake_[1], &c, 1);
    if (thread_.joinable()) thread_.join();
    {
        std::lock_guard lock(mutex_);
        clients_.clear();
        for (auto& [req, pending] : answers_)
            if (!pending.answer) pending.answer = json();  // nobody will answer now
    }
    answered_.notify_all();
    ::close(listen_fd_);
    ::close(wake_[0]);
    ::close(wake_[1]);
    ::unlink(path_.c_str());
}

std::vector<BrowserState> BrowserLink::browsers() const {
    std::lock_guard lock(mutex_);
    std::vector<BrowserState> out;
    for (const auto& [id, client] : clients_)
        if (!client->state.name.empty()) out.push_back(client->state);
    return out;
}

bool BrowserLink::send_line(int connection, const std::string& line) {
    std::shared_ptr<Client> client;
    {
        std::lock_guard lock(mutex_);
        const auto it = clients_.find(connection);
        if (it == clients_.end()) return false;
        client = it->second;
    }
    std::lock_guard write_lock(client->write_mutex);
    return write_all(client->fd, line);
}

std::optional<json> BrowserLink::ask(int connection, json question, std::chrono::milliseconds timeout) {
    long long req = 0;
    {
        std::lock_guard lock(mutex_);
        req = next_req_++;
        answers_[req] = Pending{connection, std::nullopt};
    }
    question["req"] = req;
    std::optional<json> answer;
    if (send_line(connection, question.dump(-1, ' ', false, json::error_handler_t::replace) + "\n")) {
        std::unique_lock lock(mutex_);
        answered_.wait_for(lock, timeout, [&] { return answers_[req].answer.has_value(); });
        answer = answers_[req].answer;
    }
    std::lock_guard lock(mutex_);
    answers_.erase(req);
    // An empty answer stands for a browser that went away.
    if (answer && answer->is_null()) return std::nullopt;
    return answer;
}

void BrowserLink::serve() {
    std::vector<pollfd> fds;
    std::vector<int> connections;
    for (;;) {
        fds.assign({{listen_fd_, POLLIN, 0}, {wake_[0], POLLIN, 0}});
        connections.clear();
        {
            std::lock_guard lock(mutex_);
            for (const auto& [id, client] : clients_) {
                fds.push_back({client->fd, POLLIN, 0});
                connections.push_back(id);
            }
        }
        if (::poll(fds.data(), fds.size(), -1) < 0) {
            if (errno == EINTR) continue;
            return;
        }
        if (fds[1].revents) return;
        if (fds[0].revents & POLLIN) accept_client();
        for (std::size_t i = 0; i < connections.size(); ++i) {
            if (!fds[i + 2].revents) continue;
            std::shared_ptr<Client> client;
            {
                std::lock_guard lock(mutex_);
                client = clients_.at(connections[i]);
            }
            if (!read_client(*client)) drop_client(connections[i]);
        }
    }
}

void BrowserLink::accept_client() {
    const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
    if (fd < 0) return;
    auto client = std::make_shared<Client>();
    client->fd = fd;
    if (!peer_is_this_user(fd)) return;  // closed with the client
    timeval timeout{1, 0};  // a host that stops reading does not hold up a grab
    ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &timeout, sizeof timeout);
    std::lock_guard lock(mutex_);
    if (clients_.size() >= kMaxClients) {
        write_all(fd, error_line("too many browsers are connected"));
        return;
    }
    client->state.connection = next_connection_++;
    clients_[client->state.connection] = std::move(client);
}

bool BrowserLink::read_client(Client& client) {
    char chunk[65536];
    const ssize_t n = ::recv(client.fd, chunk, sizeof chunk, 0);
    if (n < 0 && (errno == EINTR || errno == EAGAIN)) return true;
    if (n <= 0) return false;
    client.buffer.append(chunk, static_cast<std::size_t>(n));
    std::size_t start = 0;
    for (std::size_t end; (end = client.buffer.find('\n', start)) != std::string::npos; start = end + 1)
        take_line(client, client.buffer.substr(start, end - start));
    client.buffer.erase(0, start);
    if (client.buffer.size() > kMaxLine) {
        std::lock_guard write_lock(client.write_mutex);
        write_all(client.fd, error_line("a line longer than " + std::to_string(kMaxLine) + " bytes"));
        return false;
    }
    return true;
}

void BrowserLink::take_line(Client& client, const std::string& line) {
    auto complain = [&](const std::string& what) {
        std::lock_guard write_lock(client.write_mutex);
        write_all(client.fd, error_line(what));
    };
    if (line.size() > kMaxLine) return complain("a line longer than " + std::to_string(kMaxLine) + " bytes");
    json message;
    try {
        message = json::parse(line);
    } catch (const json::exception&) {
        return complain("not JSON");
    }
    if (!message.is_object() || !message.contains("type") || !message["type"].is_string())
        return complain("a message is an object with a string \"type\"");
    const std::string type = message["type"];
    try {
        if (type == "hello") {
            std::string name = message.value("browser", std::string());
            if (name.empty() || name.size() > 32) throw std::invalid_argument("\"browser\" names the browser");
            std::lock_guard lock(mutex_);
            client.state.name = protocol::clip_text(name, 32);
            client.state.version = protocol::clip_text(message.value("version", std::string()), 64);
            const auto pid = message.find("pid");
            client.state.pid = pid != message.end() && pid->is_number_integer() && pid->get<long long>() > 0 &&
                                       pid->get<long long>() < (1 << 30)
                                   ? pid->get<int>()
                                   : 0;
        } else if (type == "windows") {
            auto windows = parse_browser_windows(message);
            std::lock_guard lock(mutex_);
            client.state.windows = std::move(windows);
        } else if (type == "answer") {
            const auto req = message.find("req");
            if (req == message.end() || !req->is_number_integer()) throw std::invalid_argument("an answer needs its \"req\"");
            {
                std::lock_guard lock(mutex_);
                const auto it = answers_.find(req->get<long long>());
                if (it == answers_.end() || it->second.answer || it->second.connection != client.state.connection)
                    return;  // too late, never asked, or asked of another browser
                it->second.answer = std::move(message);
            }
            answered_.notify_all();
        } else {
            complain("unknown message type \"" + protocol::clip_text(type, 64) + "\"");
        }
    } catch (const std::exception& e) {
        complain(e.what());
    }
}

void BrowserLink::drop_client(int connection) {
    {
        std::lock_guard lock(mutex_);
        clients_.erase(connection);
        for (auto& [req, pending] : answers_)
            if (pending.connection == connection && !pending.answer) pending.answer = json();
    }
    answered_.notify_all();
}

}  // namespace umf::provider
