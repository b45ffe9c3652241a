#include "provider/service/control_socket.hpp"

#include <algorithm>

#include <fcntl.h>
#include <poll.h>
#include <sys/socket.h>
#include <sys/stat.h>
#include <sys/un.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "provider/browser/browser_status.hpp"
#include "provider/common/owner_socket.hpp"
#include "provider/put/put_text.hpp"

namespace umf::provider {

namespace {

using json = nlohmann::json;
constexpr std::size_t kMaxLine = 64 * 1024;

std::string error_answer(const std::string& what) { return json{{"ok", false}, {"error", what}}.dump(); }

PixelRect rect_of(const json& j) {
    if (!j.is_array() || j.size() != 4) throw std::invalid_argument("\"rect\" must be [x, y, width, height]");
    int v[4];
    for (int i = 0; i < 4; ++i) {
        if (!j[i].is_number_integer()) throw std::invalid_argument("\"rect\" must hold four integers");
        const auto n = j[i].get<long long>();
        if (n < -65536 || n > 65536) throw std::invalid_argument("\"rect\" is out of range");
        v[i] = static_cast<int>(n);
    }
    return {v[0], v[1], v[2], v[3]};
}

std::uint64_t put_id_of(const json& request) {
    if (!request.contains("id") || !request["id"].is_number_integer() || request["id"].get<long long>() < 1)
        throw std::invalid_argument("\"id\" must be a put's id, a positive integer");
    return request["id"].get<std::uint64_t>();
}

std::string put_list_answer(const ControlPutDecider& puts) {
    json list = json::array();
    for (const auto& [offer, age] : puts.pending()) {
        json j{{"id", offer.id},
               {"kind", protocol::to_string(offer.kind)},
               {"title", offer.title},
               {"client", offer.client},
               {"device", offer.device},
               {"age_s", std::chrono::duration_cast<std::chrono::seconds>(age).count()}};
        if (offer.kind == protocol::ContentKind::url) {
            j["url"] = offer.url;
        } else {
            j["name"] = offer.name;
            j["mime"] = offer.mime;
            j["size"] = offer.size;
        }
        list.push_back(std::move(j));
    }
    return json{{"ok", true}, {"puts", std::move(list)}}.dump();
}

std::string put_answer_answer(const json& request, ControlPutDecider& puts) {
    const std::uint64_t id = put_id_of(request);
    if (!request.contains("answer") || !request["answer"].is_string())
        return error_answer("\"answer\" must be \"save\", \"open\" or \"dismiss\"");
    const auto answer = put_answer_from_string(request["answer"].get<std::string>());
    if (!answer) return error_answer("\"answer\" must be \"save\", \"open\" or \"dismiss\"");
    PutReply reply{*answer, false};
    if (request.contains("always")) {
        if (!request["always"].is_boolean()) return error_answer("\"always\" must be true or false");
        reply.always_from_device = request["always"].get<bool>() && *answer != PutAnswer::dismiss;
    }
    const auto offer = puts.answer(id, reply);
    if (!offer)
        return error_answer("no put " + std::to_string(id) +
                            " is waiting for an answer (it was answered, withdrawn or timed out, or never was)");
    return json{{"ok", true}, {"id", id}, {"answer", to_string(*answer)}, {"name", put_offer_name(*offer)}}.dump();
}

}  // namespace

std::string handle_control_request(const std::string& line, SharedItems& items) {
    return handle_control_request(line, &items, nullptr, nullptr);
}

std::string handle_control_request(const std::string& line, SharedItems* shared, ControlPutDecider* puts,
                                   const BrowserLink* browsers, const ReadRotated* read_rotated) {
    try {
        const json request = json::parse(line);
        if (!request.is_object() || !request.contains("cmd") || !request["cmd"].is_string())
            return error_answer("a request is an object with \"cmd\"");
        const std::string cmd = request["cmd"];
        if (cmd == "ping") return json{{"ok", true}}.dump();  // is a provider here (running_provider_ports)
        if (cmd == "puts" || cmd == "put_answer") {
            if (!puts)
                return error_answer("this provider does not take answers about puts here (it was started with "
                                    "--puts always or never, or takes no puts)");
            if (cmd == "puts") return put_list_answer(*puts);
            return put_answer_answer(request, *puts);
        }
        if (cmd == "browsers") {
            if (!browsers) return error_answer("this provider does not look into browsers (public or headless mode)");
            return json{{"ok", true}, {"browsers", browser_status(browsers->browsers())}}.dump(
                -1, ' ', false, json::error_handler_t::replace);
        }
        if (cmd == "rotated") {
            if (!read_rotated || !*read_rotated) return error_answer("this provider reads its pairing at its start only");
            const RotatedRead read = (*read_rotated)();
            return json{{"ok", true}, {"config_dir", read.config_dir.string()}, {"field", read.field.id},
                        {"field_changed", read.field.changed}}
                .dump(-1, ' ', false, json::error_handler_t::replace);
        }
        if (!shared) return error_answer("this provider shares nothing (public mode)");
        SharedItems& items = *shared;
        if (cmd == "share") {
            SharedItem item;
            if (request.contains("file")) item.file = request.at("file").get<std::string>();
            if (request.contains("url")) item.url = request.at("url").get<std::string>();
            if (request.contains("title")) item.title = request.at("title").get<std::string>();
            if (request.contains("screen")) item.screen = request.at("screen").get<int>();
            if (!request.contains("rect")) return error_answer("\"rect\" is required");
            item.rect = rect_of(request.at("rect"));
            return json{{"ok", true}, {"id", items.add(std::move(item))}}.dump();
        }
        if (cmd == "unshare") {
            if (!items.remove(request.at("id").get<int>())) return error_answer("no shared item with that id");
            return json{{"ok", true}}.dump();
        }
        if (cmd == "list") {
            json list = json::array();
            for (const auto& i : items.items()) {
                json j{{"id", i.id}, {"title", i.title}, {"screen", i.screen},
                       {"rect", {i.rect.x, i.rect.y, i.rect.width, i.rect.height}}};
                if (i.file) j["file"] = i.file->string();
                if (i.url) j["url"] = *i.url;
                list.push_back(std::move(j));
            }
            return json{{"ok", true}, {"items", std::move(list)}}.dump();
        }
        return error_answer("unknown command \"" + cmd + "\"");
    } catch (const std::exception& e) {
        return error_answer(e.what());
    }
}

ControlSocket::ControlSocket(std::filesystem::path path, std::shared_ptr<SharedItems> items,
                             std::shared_ptr<ControlPutDecider> puts, std::shared_ptr<const BrowserLink> browsers,
                             ReadRotated read_rotated)
    : path_(std::move(path)),
      items_(std::move(items)),
      puts_(std::move(puts)),
      browsers_(std::move(browsers)),
      read_rotated_(std::move(read_rotated)) {
    listen_fd_ = listen_owner_only(path_, [](const std::filesystem::path& p) {
        try {
            control_request(p, R"({"cmd":"ping"})");
            return true;
        } catch (const std::exception&) {
            return false;
        }
    });
    open_wake_pipe(wake_, listen_fd_, path_);
    thread_ = std::thread([this] { serve(); });
}

ControlSocket::~ControlSocket() {
    if (wake_[1] >= 0) {
        const char c = 0;
        [[maybe_unused]] auto n = ::write(wake_[1], &c, 1);
    }
    if (thread_.joinable()) thread_.join();
    ::close(listen_fd_);
    ::close(wake_[0]);
    ::close(wake_[1]);
    ::unlink(path_.c_str());
}

void ControlSocket::serve() {
    for (;;) {
        pollfd fds[2] = {{listen_fd_, POLLIN, 0}, {wake_[0], POLLIN, 0}};
        if (::poll(fds, 2, -1) < 0) {
            if (errno == EINTR) continue;
            return;
        }
        if (fds[1].revents) return;
        if (!(fds[0].revents & POLLIN)) continue;
        const int fd = ::accept4(listen_fd_, nullptr, nullptr, SOCK_CLOEXEC);
        if (fd < 0) continue;
        answer(fd);
        ::close(fd);
    }
}

void ControlSocket::answer(int fd) {
    if (!peer_is_this_user(fd)) return;
    // A client that says nothing does not hold the socket up for long.
    timeval timeout{2, 0};
    ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    ::setsockopt(fd, SOL_SOCKET, SO_SNDTIMEO, &timeout, sizeof timeout);
    std::string line;
    char buffer[4096];
    for (;;) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n <= 0) break;
        line.append(buffer, static_cast<std::size_t>(n));
        if (line.find('\n') != std::string::npos || line.size() > kMaxLine) break;
    }
    std::string reply = line.size() > kMaxLine ? error_answer("request too long")
                        : line.find('\n') == std::string::npos
                            ? error_answer("a request ends with a newline")
                            : handle_control_request(line.substr(0, line.find('\n')), items_.get(), puts_.get(),
                                                     browsers_.get(), &read_rotated_);
    reply += '\n';
    // A client gone before the answer must not end the provider with SIGPIPE.
    [[maybe_unused]] auto n = ::send(fd, reply.data(), reply.size(), MSG_NOSIGNAL);
}

std::string control_request(const std::filesystem::path& path, const std::string& line) {
    const sockaddr_un addr = unix_address(path);
    const int fd = ::socket(AF_UNIX, SOCK_STREAM | SOCK_CLOEXEC, 0);
    if (fd < 0) throw std::runtime_error(std::string("cannot make a socket: ") + std::strerror(errno));
    struct Closer {
        int fd;
        ~Closer() { ::close(fd); }
    } closer{fd};
    if (::connect(fd, reinterpret_cast<const sockaddr*>(&addr), sizeof addr) != 0)
        throw std::runtime_error("no provider is running at " + path.string() + " (" + std::strerror(errno) + ")");
    timeval timeout{5, 0};
    ::setsockopt(fd, SOL_SOCKET, SO_RCVTIMEO, &timeout, sizeof timeout);
    const std::string request = line + "\n";
    if (::write(fd, request.data(), request.size()) != static_cast<ssize_t>(request.size()))
        throw std::runtime_error("cannot talk to the provider at " + path.string());
    std::string answer;
    char buffer[4096];
    for (;;) {
        const ssize_t n = ::read(fd, buffer, sizeof buffer);
        if (n <= 0) break;
        answer.append(buffer, static_cast<std::size_t>(n));
        if (answer.find('\n') != std::string::npos) break;
    }
    if (answer.empty()) throw std::runtime_error("the provider at " + path.string() + " did not answer");
    return answer.substr(0, answer.find('\n'));
}

std::vector<unsigned short> running_provider_ports() {
    std::vector<unsigned short> ports;
    std::error_code ec;
    for (const auto& entry : std::filesystem::directory_iterator(runtime_dir(), ec)) {
        const auto port = provider_socket_port(entry.path().filename().string());
        if (!port) continue;
        try {
            control_request(entry.path(), R"({"cmd":"ping"})");
            ports.push_back(*port);
        } catch (const std::exception&) {
            // A socket file a provider left behind when it was killed.
        }
    }
    std::sort(ports.begin(), ports.end());
    return ports;
}

}  // namespace umf::provider
