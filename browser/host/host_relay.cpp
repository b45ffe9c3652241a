#include "browser/host/host_relay.hpp"

#include <poll.h>
#include <sys/socket.h>
#include <unistd.h>

#include <cerrno>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>

#include "browser/host/native_messaging.hpp"
#include "browser/host/provider_socket.hpp"

namespace umf::browser {

namespace {

using json = nlohmann::json;
// Longest line from the provider; the browser takes no more than kMaxToBrowser anyway.
constexpr std::size_t kMaxProviderLine = kMaxToBrowser;

bool write_all(int fd, const std::string& data) {
    std::size_t done = 0;
    while (done < data.size()) {
        const ssize_t n = ::write(fd, data.data() + done, data.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) return false;
        done += static_cast<std::size_t>(n);
    }
    return true;
}

struct Relay {
    Relay(const RelayOptions& relay_options, std::ostream& relay_log) : options(relay_options), log(relay_log) {}

    const RelayOptions& options;
    std::ostream& log;
    int provider = -1;
    std::string provider_buffer;
    std::optional<std::string> hello, windows;  // lines to send again on reconnecting
    std::string last_failure;

    void to_browser(const json& message) {
        std::string framed;
        try {
            framed = frame_message(message.dump(-1, ' ', false, json::error_handler_t::replace));
        } catch (const FramingError& e) {
            log << "umf-browser-host: not passed on to the browser: " << e.what() << "\n";
            return;
        }
        write_all(options.to_browser, framed);
    }

    void tell_status() { to_browser({{"type", "status"}, {"provider", provider >= 0}}); }

    void disconnect() {
        if (provider < 0) return;
        ::close(provider);
        provider = -1;
        provider_buffer.clear();
        tell_status();
    }

    void connect() {
        std::string why;
        provider = connect_to_provider(provider_sockets(options.runtime_dir), why);
        if (provider < 0) {
            if (why != last_failure) log << "umf-browser-host: " << why << "\n";
            last_failure = why;
            return;
        }
        last_failure.clear();
        log << "umf-browser-host: connected to the provider\n";
        for (const auto* line : {&hello, &windows})
            if (*line && !write_all(provider, **line)) return disconnect();
        tell_status();
    }

    void from_browser(const std::string& text) {
        json message;
        try {
            message = json::parse(text);
        } catch (const json::exception&) {
            log << "umf-browser-host: the extension sent something that is not JSON\n";
            return;
        }
        if (!message.is_object() || !message.contains("type") || !message["type"].is_string()) {
            log << "umf-browser-host: the extension sent a message without a \"type\"\n";
            return;
        }
        const std::string type = message["type"];
        if (type == "hello") message["pid"] = options.browser_pid;
        const std::string line = message.dump(-1, ' ', false, json::error_handler_t::replace) + "\n";
        if (type == "hello") hello = line;
        if (type == "windows") windows = line;
        if (provider >= 0 && !write_all(provider, line)) disconnect();
    }

    void from_provider() {
        char chunk[65536];
        const ssize_t n = ::recv(provider, chunk, sizeof chunk, 0);
        if (n < 0 && errno == EINTR) return;
        if (n <= 0) {
            log << "umf-browser-host: the provider went away\n";
            return disconnect();
        }
        provider_buffer.append(chunk, static_cast<std::size_t>(n));
        std::size_t start = 0;
        for (std::size_t end; (end = provider_buffer.find('\n', start)) != std::string::npos; start = end + 1) {
            try {
                const json message = json::parse(provider_buffer.substr(start, end - start));
                if (message.is_object() && message.contains("type") && message["type"].is_string()) to_browser(message);
            } catch (const json::exception&) {
                log << "umf-browser-host: the provider sent something that is not JSON\n";
            }
        }
        provider_buffer.erase(0, start);
        if (provider_buffer.size() > kMaxProviderLine) {
            log << "umf-browser-host: the provider sent a line too long\n";
            disconnect();
        }
    }
};

}  // namespace

int run_relay(const RelayOptions& options, std::ostream& log) {
    Relay relay(options, log);
    FrameReader reader;
    relay.connect();
    for (;;) {
        pollfd fds[2] = {{options.from_browser, POLLIN, 0}, {relay.provider, POLLIN, 0}};
        const int ready = ::poll(fds, relay.provider >= 0 ? 2 : 1, relay.provider >= 0 ? -1 : options.retry_ms);
        if (ready < 0 && errno != EINTR) return 1;
        if (ready <= 0) {
            if (relay.provider < 0) relay.connect();
            continue;
        }
        if (relay.provider >= 0 && fds[1].revents) relay.from_provider();
        if (!fds[0].revents) continue;
        char chunk[65536];
        const ssize_t n = ::read(options.from_browser, chunk, sizeof chunk);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
            relay.disconnect();
            return 0;  // the browser closed the port
        }
        reader.feed(chunk, static_cast<std::size_t>(n));
        try {
            while (auto message = reader.next()) relay.from_browser(*message);
        } catch (const FramingError& e) {
            log << "umf-browser-host: " << e.what() << "\n";
            relay.disconnect();
            return 1;
        }
    }
}

}  // namespace umf::browser
