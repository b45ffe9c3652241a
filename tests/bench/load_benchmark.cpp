// umf_load_benchmark: the provider's server under load on loopback, for
// docs/benchmarks/load.md. A program, not a test: it prints numbers and says
// which targets they meet, it does not fail on them.
//
// The server runs in a forked child so that its memory (VmRSS from
// /proc/PID/status) and CPU (utime + stime from /proc/PID/stat, all threads)
// are read without the clients' share mixed in. The clients are async Beast
// TLS WebSocket clients on one or two io_context threads of the parent, each
// on its own strand, pinned to the certificate's fingerprint as a native
// requester would be.
//
// Every wait has a deadline and an alarm ends the program (and the child)
// at --seconds + 30 s whatever happens.

#include <fcntl.h>
#include <openssl/evp.h>
#include <openssl/rand.h>
#include <openssl/x509.h>
#include <poll.h>
#include <signal.h>
#include <stdlib.h>
#include <sys/prctl.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <csignal>
#include <atomic>
#include <boost/asio/connect.hpp>
#include <boost/asio/executor_work_guard.hpp>
#include <boost/asio/io_context.hpp>
#include <boost/asio/ip/tcp.hpp>
#include <boost/asio/post.hpp>
#include <boost/asio/ssl.hpp>
#include <boost/asio/steady_timer.hpp>
#include <boost/asio/strand.hpp>
#include <boost/beast/core.hpp>
#include <boost/beast/http.hpp>
#include <boost/beast/ssl.hpp>
#include <boost/beast/websocket.hpp>
#include <boost/beast/websocket/ssl.hpp>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <deque>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <memory>
#include <optional>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <unordered_map>
#include <vector>

#include "provider/board/board.hpp"
#include "provider/content/board_resolver.hpp"
#include "provider/service/pairing.hpp"
#include "provider/service/service.hpp"
#include "provider/service/service_server.hpp"
#include "provider/trust/tls_identity_store.hpp"
#include "shared/protocol/messages.hpp"
#include "tests/support/pinned_client.hpp"

namespace {

namespace fs = std::filesystem;
namespace net = boost::asio;
namespace ssl = boost::asio::ssl;
namespace beast = boost::beast;
namespace http = beast::http;
namespace websocket = beast::websocket;
namespace p = umf::protocol;
using namespace umf::provider;
using Clock = std::chrono::steady_clock;
using Ms = std::chrono::duration<double, std::milli>;
using Seconds = std::chrono::duration<double>;

constexpr int kScreenWidth = 1920;
constexpr int kScreenHeight = 1080;
constexpr auto kReplyTimeout = std::chrono::seconds(2);
constexpr auto kConnectStepTimeout = std::chrono::seconds(5);
constexpr auto kAimPeriod = std::chrono::milliseconds(100);
constexpr auto kAimJitter = std::chrono::milliseconds(20);
constexpr auto kSettle = std::chrono::milliseconds(1500);

// ---- options ------------------------------------------------------------------

struct Options {
    int clients = 200;
    double seconds = 10;
    double grab_every = 2;
    int server_threads = 2;
    int client_threads = 1;
    int download_mb = 100;
    bool raise_limits = false;
    bool no_warm_up = false;
    bool quick = false;
    std::string out;
    std::string json;
    std::string command_line;
};

[[noreturn]] void usage(const char* why) {
    std::fprintf(stderr,
                 "%s\nusage: umf_load_benchmark [--clients N] [--seconds S] [--grab-every S] [--server-threads N]\n"
                 "       [--client-threads 1|2] [--download-mb M] [--raise-limits] [--no-warm-up] [--quick]\n"
                 "       [--out FILE.md] [--json FILE]\n"
                 "--no-warm-up: the file's first grab (the server hashes the file) is left to the load\n"
                 "clients instead of being made before the load, to show what it costs them.\n",
                 why);
    std::exit(2);
}

Options parse_options(int argc, char** argv) {
    Options o;
    for (int i = 0; i < argc; ++i) o.command_line += (i ? " " : "") + std::string(argv[i]);
    // --quick sets the defaults; options given with it still win.
    for (int i = 1; i < argc; ++i)
        if (std::string(argv[i]) == "--quick") {
            o.quick = true;
            o.clients = 20;
            o.seconds = 3;
            o.download_mb = 20;
        }
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        auto value = [&]() -> std::string {
            if (i + 1 >= argc) usage(("missing value for " + a).c_str());
            return argv[++i];
        };
        auto number = [&](double lo, double hi) {
            const std::string v = value();
            char* end = nullptr;
            const double d = std::strtod(v.c_str(), &end);
            if (v.empty() || *end || !(d >= lo && d <= hi)) usage(("bad value for " + a + ": " + v).c_str());
            return d;
        };
        if (a == "--quick") continue;
        if (a == "--clients") o.clients = static_cast<int>(number(1, 5000));
        else if (a == "--seconds") o.seconds = number(0.5, 600);
        else if (a == "--grab-every") o.grab_every = number(0.05, 600);
        else if (a == "--server-threads") o.server_threads = static_cast<int>(number(1, 64));
        else if (a == "--client-threads") o.client_threads = static_cast<int>(number(1, 2));
        else if (a == "--download-mb") o.download_mb = static_cast<int>(number(0, 4096));
        else if (a == "--raise-limits") o.raise_limits = true;
        else if (a == "--no-warm-up") o.no_warm_up = true;
        else if (a == "--out") o.out = value();
        else if (a == "--json") o.json = value();
        else if (a == "--help" || a == "-h") usage("");
        else usage(("unknown option " + a).c_str());
    }
    return o;
}

// ---- numbers --------------------------------------------------------------------

// Nearest rank, so a reported percentile is a measured value.
double percentile(std::vector<double> v, double q) {
    if (v.empty()) return std::nan("");
    std::sort(v.begin(), v.end());
    const auto rank = static_cast<std::size_t>(std::ceil(q / 100.0 * static_cast<double>(v.size())));
    return v[std::clamp<std::size_t>(rank, 1, v.size()) - 1];
}

double median(std::vector<double> v) { return percentile(std::move(v), 50); }

std::string fmt(double v, int digits = 2) {
    if (std::isnan(v)) return "n/a";
    char text[64];
    std::snprintf(text, sizeof text, "%.*f", digits, v);
    return text;
}

// ---- the server child's numbers, read from /proc ------------------------------------

long proc_status_kib(pid_t pid, const char* key) {
    std::ifstream in("/proc/" + std::to_string(pid) + "/status");
    std::string line;
    while (std::getline(in, line))
        if (line.rfind(key, 0) == 0) return std::atol(line.c_str() + std::strlen(key));
    return -1;
}

// utime + stime of a process or thread, in seconds; the comm field may hold
// spaces, so the fields are counted from the last ')'.
double proc_stat_cpu(const std::string& stat_path, std::string* comm = nullptr) {
    std::ifstream in(stat_path);
    std::string text((std::istreambuf_iterator<char>(in)), {});
    const auto open = text.find('('), close = text.rfind(')');
    if (open == std::string::npos || close == std::string::npos) return std::nan("");
    if (comm) *comm = text.substr(open + 1, close - open - 1);
    std::istringstream rest(text.substr(close + 2));
    std::vector<std::string> f;
    for (std::string s; rest >> s && f.size() < 13;) f.push_back(s);
    if (f.size() < 13) return std::nan("");
    const double tick = static_cast<double>(sysconf(_SC_CLK_TCK));
    return (std::atof(f[11].c_str()) + std::atof(f[12].c_str())) / tick;
}

double process_cpu(pid_t pid) { return proc_stat_cpu("/proc/" + std::to_string(pid) + "/stat"); }

std::map<int, double> thread_cpu(pid_t pid) {
    std::map<int, double> out;
    std::error_code ec;
    for (const auto& e : fs::directory_iterator("/proc/" + std::to_string(pid) + "/task", ec))
        out[std::atoi(e.path().filename().c_str())] = proc_stat_cpu((e.path() / "stat").string());
    return out;
}

double self_cpu() {
    rusage u{};
    getrusage(RUSAGE_SELF, &u);
    return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) +
           static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec) / 1e6;
}

// ---- the server, in a child process -------------------------------------------------

struct ServerChild {
    pid_t pid = -1;
    int control_fd = -1;  // closing it (or writing to it) stops the server
    unsigned short port = 0;
};

// Read with a deadline, so a child that never starts cannot hang the parent.
bool read_exact(int fd, void* data, std::size_t size, int timeout_ms) {
    auto* out = static_cast<char*>(data);
    const auto deadline = Clock::now() + std::chrono::milliseconds(timeout_ms);
    while (size > 0) {
        const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - Clock::now()).count();
        if (left <= 0) return false;
        pollfd pfd{fd, POLLIN, 0};
        if (::poll(&pfd, 1, static_cast<int>(left)) <= 0) continue;
        const ssize_t n = ::read(fd, out, size);
        if (n <= 0) return false;
        out += n;
        size -= static_cast<std::size_t>(n);
    }
    return true;
}

ServerChild start_server_child(const Options& o, const TlsIdentity& identity, const std::string& token,
                               const fs::path& file, int lifetime_s) {
    int report[2], control[2];
    if (::pipe2(report, O_CLOEXEC) != 0 || ::pipe2(control, O_CLOEXEC) != 0) throw std::runtime_error("pipe failed");
    std::fflush(stdout);
    std::fflush(stderr);
    const pid_t parent = ::getpid();
    const pid_t pid = ::fork();
    if (pid < 0) throw std::runtime_error("fork failed");
    if (pid == 0) {
        ::close(report[0]);
        ::close(control[1]);
        // The child never outlives the benchmark, whatever ends it.
        ::prctl(PR_SET_PDEATHSIG, SIGKILL);
        if (::getppid() != parent) ::_exit(1);
        ::alarm(static_cast<unsigned>(lifetime_s));
        try {
            ServiceConfig config = default_service_config(kScreenWidth, kScreenHeight, "load");
            if (o.raise_limits) {
                config.limits.aims_per_s = 100;
                config.limits.grabs_per_min = 1000;
            }
            // The file under the whole screen, a link over its right half
            // (later items lie on top): grabs on the left take the file, on
            // the right the URL.
            Board board;
            board.items.push_back({"Load file", file, std::nullopt, std::nullopt, std::nullopt});
            board.items.push_back({"Load link", std::nullopt, "https://example.org/load", std::nullopt, std::nullopt});
            const std::vector<PixelRect> tiles{{0, 0, kScreenWidth, kScreenHeight},
                                               {kScreenWidth / 2, 0, kScreenWidth / 2, kScreenHeight}};
            auto resolver = std::make_shared<BoardResolver>(board, tiles);
            auto service = std::make_shared<const Service>(config, token,
                                                           std::vector<std::shared_ptr<const Resolver>>{resolver});
            ServerOptions options;
            options.threads = o.server_threads;
            const auto server = make_server(service, identity, options);
            server->start();
            const unsigned short port = server->port();
            if (::write(report[1], &port, sizeof port) != sizeof port) ::_exit(1);
            char c;
            while (::read(control[0], &c, 1) < 0 && errno == EINTR) {
            }
            server->stop(std::chrono::milliseconds(1000));
        } catch (const std::exception& e) {
            std::fprintf(stderr, "server child: %s\n", e.what());
            ::_exit(1);
        }
        ::_exit(0);
    }
    ::close(report[1]);
    ::close(control[0]);
    ServerChild child;
    child.pid = pid;
    child.control_fd = control[1];
    if (!read_exact(report[0], &child.port, sizeof child.port, 15000)) {
        ::kill(pid, SIGKILL);
        ::waitpid(pid, nullptr, 0);
        throw std::runtime_error("the server child did not start");
    }
    ::close(report[0]);
    return child;
}

void stop_server_child(ServerChild& child) {
    if (child.pid <= 0) return;
    ::close(child.control_fd);
    const auto deadline = Clock::now() + std::chrono::seconds(4);
    int status = 0;
    while (Clock::now() < deadline) {
        if (::waitpid(child.pid, &status, WNOHANG) == child.pid) {
            child.pid = -1;
            return;
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(20));
    }
    ::kill(child.pid, SIGKILL);
    ::waitpid(child.pid, &status, 0);
    child.pid = -1;
}

// ---- TLS for the clients ------------------------------------------------------------

using umf::test::pinned_client_context;

// The field points of the two board items, from a welcome's screen region
// (the region is the screen's visible part, mapped linearly).
struct Points {
    p::FieldRect region;
    p::FieldPoint file() const { return {region.u0 + 0.25 * (region.u1 - region.u0), (region.v0 + region.v1) / 2}; }
    p::FieldPoint url() const { return {region.u0 + 0.75 * (region.u1 - region.u0), (region.v0 + region.v1) / 2}; }
};

// ---- the load clients ------------------------------------------------------------------

struct Shared {
    ssl::context* tls = nullptr;
    net::ip::tcp::endpoint endpoint;
    std::string token;
    std::atomic<int> welcomed{0};
    std::atomic<int> finished{0};  // connections over (failed, closed or aborted)
    std::atomic<int> loading{0};
    std::atomic<int> drained{0};   // load sent and every reply in or given up
};

struct ClientStats {
    double connect_ms = std::nan("");
    long aims_sent = 0, aims_answered = 0;
    long grabs_sent = 0, grabs_answered = 0, grabs_file = 0, grabs_url = 0, grabs_other = 0;
    std::vector<double> aim_ms, grab_ms;
    std::map<std::string, long> errors;
};

class LoadClient : public std::enable_shared_from_this<LoadClient> {
public:
    LoadClient(net::io_context& io, Shared& shared, int index)
        : shared_(shared), ws_(net::make_strand(io), *shared.tls), timer_(ws_.get_executor()), rng_(0x5eed + index) {
        ws_.read_message_max(p::kMaxReplyBytes);
    }

    void start() {
        net::post(ws_.get_executor(), [self = shared_from_this()] {
            self->started_ = Clock::now();
            auto& tcp = beast::get_lowest_layer(self->ws_);
            tcp.expires_after(kConnectStepTimeout);
            tcp.async_connect(self->shared_.endpoint, [self](beast::error_code ec) { self->on_connect(ec); });
        });
    }

    void begin_load(Clock::time_point t0, Clock::time_point end, Seconds grab_every) {
        net::post(ws_.get_executor(), [self = shared_from_this(), t0, end, grab_every] {
            if (self->state_ != State::idle) return;
            self->state_ = State::running;
            ++self->shared_.loading;
            self->t0_ = t0;
            self->end_ = end;
            self->grab_every_ = std::chrono::duration_cast<Clock::duration>(grab_every);
            // Random phases spread the clients over the period, as
            // independent phones would be.
            std::uniform_int_distribution<long> aim_phase(0, std::chrono::nanoseconds(kAimPeriod).count());
            std::uniform_real_distribution<double> grab_phase(0, grab_every.count());
            self->aim_offset_ = std::chrono::nanoseconds(aim_phase(self->rng_));
            self->grab_offset_ = std::chrono::duration_cast<Clock::duration>(Seconds(grab_phase(self->rng_)));
            self->next_aim_ = t0 + self->aim_offset_;
            self->next_grab_ = t0 + self->grab_offset_;
            self->schedule();
        });
    }

    // A polite close; the connection's end is then no error.
    void close() {
        net::post(ws_.get_executor(), [self = shared_from_this()] {
            if (self->finished_ || self->closing_) return;
            self->closing_ = true;
            self->timer_.cancel();
            if (self->state_ == State::idle || self->state_ == State::running || self->state_ == State::draining)
                self->ws_.async_close(websocket::close_code::normal, [self](beast::error_code) {});
            else
                beast::get_lowest_layer(self->ws_).close();
        });
    }

    // Ends the connection at once.
    void abort() {
        net::post(ws_.get_executor(), [self = shared_from_this()] {
            if (self->finished_) return;
            self->closing_ = true;
            self->timer_.cancel();
            beast::get_lowest_layer(self->ws_).close();
            if (!self->reading_) self->finish();
        });
    }

    // A client still without its welcome is given up on, as an error.
    void give_up_connecting() {
        net::post(ws_.get_executor(), [self = shared_from_this()] {
            if (self->finished_ || self->state_ >= State::idle) return;
            self->fail("connect: no welcome within 10 s");
        });
    }

    // Read only once the client threads have ended.
    const ClientStats& stats() const { return stats_; }
    const std::optional<Points>& points() const { return points_; }

private:
    enum class State { connecting, hello_sent, idle, running, draining, done };
    struct Outgoing {
        std::string text;
        std::int64_t aim_id = -1;  // -1 and an empty grab_id: no reply to time (the hello)
        std::string grab_id;
    };

    void fail(const char* what) {
        if (!closing_) ++stats_.errors[what];
        closing_ = true;
        beast::get_lowest_layer(ws_).close();
        if (!reading_) finish();
    }

    void finish() {
        if (finished_) return;
        finished_ = true;
        timer_.cancel();
        if (state_ == State::running || state_ == State::draining) ++shared_.drained;
        state_ = State::done;
        ++shared_.finished;
    }

    void on_connect(beast::error_code ec) {
        if (ec) return fail("connect: tcp");
        if (closing_) return fail("connect: tcp");
        ws_.next_layer().async_handshake(ssl::stream_base::client,
                                         [self = shared_from_this()](beast::error_code ec) { self->on_tls(ec); });
    }

    void on_tls(beast::error_code ec) {
        if (ec || closing_) return fail("connect: tls");
        // The websocket keeps its own timeouts from here on.
        beast::get_lowest_layer(ws_).expires_never();
        websocket::stream_base::timeout t{};
        t.handshake_timeout = kConnectStepTimeout;
        t.idle_timeout = websocket::stream_base::none();
        t.keep_alive_pings = false;
        ws_.set_option(t);
        ws_.async_handshake("127.0.0.1:" + std::to_string(shared_.endpoint.port()), "/ws",
                            [self = shared_from_this()](beast::error_code ec) { self->on_handshake(ec); });
    }

    void on_handshake(beast::error_code ec) {
        if (ec || closing_) return fail("connect: websocket");
        state_ = State::hello_sent;
        send({p::encode(p::Hello{p::RequestId{std::int64_t{0}}, shared_.token, "umf_load_benchmark"}), -1, {}});
        read();
    }

    void read() {
        reading_ = true;
        ws_.async_read(buffer_, [self = shared_from_this()](beast::error_code ec, std::size_t) { self->on_read(ec); });
    }

    void on_read(beast::error_code ec) {
        reading_ = false;
        if (ec) {
            if (!closing_) ++stats_.errors[state_ == State::hello_sent ? "connect: closed before welcome"
                                                                       : "unexpected close"];
            closing_ = true;
            finish();
            return;
        }
        const auto now = Clock::now();
        const std::string text = beast::buffers_to_string(buffer_.data());
        buffer_.consume(buffer_.size());
        const auto parsed = p::parse_message(text, p::kRequesterLimits);
        if (state_ == State::hello_sent) {
            const auto* m = std::get_if<p::Message>(&parsed);
            const auto* w = m ? std::get_if<p::Welcome>(m) : nullptr;
            if (!w || w->field.screens.empty()) return fail("connect: hello refused");
            points_ = Points{w->field.screens[0].region};
            stats_.connect_ms = Ms(now - started_).count();
            state_ = State::idle;
            ++shared_.welcomed;
        } else if (const auto* m = std::get_if<p::Message>(&parsed)) {
            on_reply(*m, now);
        } else {
            ++stats_.errors["reply does not parse"];
        }
        if (!finished_) read();
    }

    void on_reply(const p::Message& m, Clock::time_point now) {
        if (const auto* t = std::get_if<p::Target>(&m)) {
            const auto* id = t->id ? std::get_if<std::int64_t>(&*t->id) : nullptr;
            auto it = id ? pending_aims_.find(*id) : pending_aims_.end();
            if (it == pending_aims_.end()) {
                ++stats_.errors["aim: reply after 2 s or unknown id"];
                return;
            }
            stats_.aim_ms.push_back(Ms(now - it->second).count());
            ++stats_.aims_answered;
            pending_aims_.erase(it);
        } else if (const auto* c = std::get_if<p::Content>(&m)) {
            const auto* id = std::get_if<std::string>(&c->id);
            auto it = id ? pending_grabs_.find(*id) : pending_grabs_.end();
            if (it == pending_grabs_.end()) {
                ++stats_.errors["grab: reply after 2 s or unknown id"];
                return;
            }
            stats_.grab_ms.push_back(Ms(now - it->second).count());
            ++stats_.grabs_answered;
            ++(c->kind == p::ContentKind::file ? stats_.grabs_file
               : c->kind == p::ContentKind::url ? stats_.grabs_url
                                                : stats_.grabs_other);
            pending_grabs_.erase(it);
        } else if (const auto* e = std::get_if<p::Error>(&m)) {
            const std::string code = p::to_string(e->code);
            if (e->id && std::holds_alternative<std::string>(*e->id)) {
                pending_grabs_.erase(std::get<std::string>(*e->id));
                ++stats_.errors["grab: error " + code];
            } else if (e->id) {
                pending_aims_.erase(std::get<std::int64_t>(*e->id));
                ++stats_.errors["aim: error " + code];
            } else {
                ++stats_.errors["error " + code];
            }
        } else {
            ++stats_.errors[std::string("unexpected ") + p::type_name(m)];
        }
        maybe_drained(now);
    }

    void send(Outgoing out) {
        queue_.push_back(std::move(out));
        if (queue_.size() == 1) write_next();
    }

    void write_next() {
        // The round trip starts when the message goes to the socket, not
        // while it waits behind another in this client's queue.
        Outgoing& out = queue_.front();
        const auto now = Clock::now();
        if (out.aim_id >= 0) pending_aims_[out.aim_id] = now;
        if (!out.grab_id.empty()) pending_grabs_[out.grab_id] = now;
        ws_.text(true);
        ws_.async_write(net::buffer(out.text), [self = shared_from_this()](beast::error_code ec, std::size_t) {
            if (ec) return self->fail("write failed");
            self->queue_.pop_front();
            if (!self->queue_.empty() && !self->closing_) self->write_next();
        });
    }

    void schedule() {
        if (closing_) return;
        timer_.expires_at(state_ == State::running ? std::min({next_aim_, next_grab_, end_})
                                                   : Clock::now() + std::chrono::milliseconds(50));
        timer_.async_wait([self = shared_from_this()](beast::error_code ec) {
            if (!ec) self->on_tick();
        });
    }

    void on_tick() {
        if (closing_ || finished_) return;
        const auto now = Clock::now();
        expire(now);
        if (state_ == State::running && now >= end_) state_ = State::draining;
        if (state_ == State::draining) {
            if (!maybe_drained(now)) schedule();
            return;
        }
        // A late tick sends one message and skips the slots it missed: a
        // phone that stalls does not catch up, and catching up would trip
        // the server's rate limits.
        if (now >= next_aim_) {
            send_aim();
            while (next_aim_ <= now) next_aim_ = nth_aim(++aim_k_);
        }
        if (now >= next_grab_) {
            send_grab();
            while (next_grab_ <= now) next_grab_ = t0_ + grab_offset_ + grab_every_ * ++grab_k_;
        }
        schedule();
    }

    // Jitter around the nominal time rather than added to the last one, so
    // the rate stays at 10 a second on average and the aim bucket never runs
    // dry.
    Clock::time_point nth_aim(long k) {
        std::uniform_int_distribution<long> jitter(-std::chrono::nanoseconds(kAimJitter).count(),
                                                   std::chrono::nanoseconds(kAimJitter).count());
        return t0_ + aim_offset_ + kAimPeriod * k + std::chrono::nanoseconds(jitter(rng_));
    }

    void send_aim() {
        std::uniform_real_distribution<double> u(points_->region.u0, points_->region.u1);
        std::uniform_real_distribution<double> v(points_->region.v0, points_->region.v1);
        p::Aim aim;
        aim.id = p::RequestId{++aim_id_};
        aim.point = {u(rng_), v(rng_)};
        aim.confidence = 0.9;
        ++stats_.aims_sent;
        send({p::encode(aim), aim_id_, {}});
    }

    void send_grab() {
        const p::FieldPoint point = (grab_k_ % 2 == 0) ? points_->file() : points_->url();
        const std::string id = "g" + std::to_string(grab_k_);
        ++stats_.grabs_sent;
        send({p::encode(p::Grab{p::RequestId{id}, point}), -1, id});
    }

    void expire(Clock::time_point now) {
        for (auto it = pending_aims_.begin(); it != pending_aims_.end();)
            if (now - it->second > kReplyTimeout) {
                ++stats_.errors["aim: no reply within 2 s"];
                it = pending_aims_.erase(it);
            } else {
                ++it;
            }
        for (auto it = pending_grabs_.begin(); it != pending_grabs_.end();)
            if (now - it->second > kReplyTimeout) {
                ++stats_.errors["grab: no reply within 2 s"];
                it = pending_grabs_.erase(it);
            } else {
                ++it;
            }
    }

    bool maybe_drained(Clock::time_point now) {
        if (state_ != State::draining) return false;
        expire(now);
        if (!pending_aims_.empty() || !pending_grabs_.empty() || !queue_.empty()) return false;
        state_ = State::idle;
        ++shared_.drained;
        timer_.cancel();
        return true;
    }

    Shared& shared_;
    websocket::stream<beast::ssl_stream<beast::tcp_stream>> ws_;
    net::steady_timer timer_;
    beast::flat_buffer buffer_;
    std::mt19937_64 rng_;
    State state_ = State::connecting;
    bool reading_ = false, closing_ = false, finished_ = false;
    Clock::time_point started_{}, t0_{}, end_{}, next_aim_{}, next_grab_{};
    Clock::duration aim_offset_{}, grab_offset_{}, grab_every_{};
    long aim_k_ = 0, grab_k_ = 0;
    std::int64_t aim_id_ = 0;
    std::deque<Outgoing> queue_;
    std::unordered_map<std::int64_t, Clock::time_point> pending_aims_;
    std::unordered_map<std::string, Clock::time_point> pending_grabs_;
    std::optional<Points> points_;
    ClientStats stats_;
};

// ---- one requester on the main thread: grabs and downloads --------------------------------

// Each step runs the io_context until it completes or its deadline passes;
// then the connection is closed, which completes the step with an error.
class StepClient {
public:
    StepClient(ssl::context& tls, net::ip::tcp::endpoint endpoint, std::string token)
        : tls_(tls), endpoint_(endpoint), token_(std::move(token)) {}

    struct Grabbed {
        bool ok = false;
        std::string error;
        double ms = 0;
        p::Content content;
    };
    struct Downloaded {
        bool ok = false;
        std::string error;
        std::uint64_t bytes = 0;
        double seconds = 0;
        std::string sha256;  // when hashed
    };

    std::string connect(Clock::time_point deadline) {
        ws_.emplace(io_, tls_);
        auto& tcp = beast::get_lowest_layer(*ws_);
        if (auto ec = step([&](auto h) { tcp.async_connect(endpoint_, h); }, deadline)) return "tcp: " + ec.message();
        if (auto ec = step([&](auto h) { ws_->next_layer().async_handshake(ssl::stream_base::client, h); }, deadline))
            return "tls: " + ec.message();
        ws_->read_message_max(p::kMaxReplyBytes);
        if (auto ec = step([&](auto h) { ws_->async_handshake("127.0.0.1", "/ws", h); }, deadline))
            return "websocket: " + ec.message();
        const std::string hello = p::encode(p::Hello{std::nullopt, token_, "umf_load_benchmark download"});
        if (auto ec = step([&](auto h) { ws_->async_write(net::buffer(hello), h); }, deadline))
            return "hello: " + ec.message();
        beast::flat_buffer buffer;
        if (auto ec = step([&](auto h) { ws_->async_read(buffer, h); }, deadline)) return "welcome: " + ec.message();
        const auto parsed = p::parse_message(beast::buffers_to_string(buffer.data()), p::kRequesterLimits);
        const auto* m = std::get_if<p::Message>(&parsed);
        const auto* w = m ? std::get_if<p::Welcome>(m) : nullptr;
        if (!w || w->field.screens.empty()) return "hello refused";
        points_ = Points{w->field.screens[0].region};
        return {};
    }

    Grabbed grab(p::FieldPoint point, Clock::time_point deadline) {
        Grabbed g;
        const std::string text = p::encode(p::Grab{p::RequestId{"d" + std::to_string(++grabs_)}, point});
        const auto t0 = Clock::now();
        if (auto ec = step([&](auto h) { ws_->async_write(net::buffer(text), h); }, deadline)) {
            g.error = "grab write: " + ec.message();
            return g;
        }
        beast::flat_buffer buffer;
        if (auto ec = step([&](auto h) { ws_->async_read(buffer, h); }, deadline)) {
            g.error = "grab read: " + ec.message();
            return g;
        }
        g.ms = Ms(Clock::now() - t0).count();
        const auto parsed = p::parse_message(beast::buffers_to_string(buffer.data()), p::kRequesterLimits);
        const auto* m = std::get_if<p::Message>(&parsed);
        if (const auto* c = m ? std::get_if<p::Content>(m) : nullptr) {
            g.content = *c;
            g.ok = true;
        } else if (const auto* e = m ? std::get_if<p::Error>(m) : nullptr) {
            g.error = std::string("grab: error ") + p::to_string(e->code) + ": " + e->message;
        } else {
            g.error = "grab: unexpected reply";
        }
        return g;
    }

    void close(Clock::time_point deadline) {
        if (!ws_) return;
        step([&](auto h) { ws_->async_close(websocket::close_code::normal, h); },
             std::min(deadline, Clock::now() + std::chrono::seconds(1)));
        ws_.reset();
    }

    // GET on a connection of its own, the body streamed through a fixed
    // buffer and dropped (hashed when asked), as a requester saving to disk
    // would read it.
    Downloaded download(const std::string& path, bool hash, Clock::time_point deadline) {
        Downloaded d;
        beast::ssl_stream<beast::tcp_stream> stream(io_, tls_);
        auto cancel = [&] { beast::get_lowest_layer(stream).close(); };
        if (auto ec = step([&](auto h) { beast::get_lowest_layer(stream).async_connect(endpoint_, h); }, deadline, cancel)) {
            d.error = "tcp: " + ec.message();
            return d;
        }
        if (auto ec = step([&](auto h) { stream.async_handshake(ssl::stream_base::client, h); }, deadline, cancel)) {
            d.error = "tls: " + ec.message();
            return d;
        }
        http::request<http::empty_body> req(http::verb::get, path, 11);
        req.set(http::field::host, "127.0.0.1");
        // The link is bound to the pairing token of the session that grabbed it.
        req.set(http::field::authorization, "Bearer " + token_);
        const auto t0 = Clock::now();
        if (auto ec = step([&](auto h) { http::async_write(stream, req, h); }, deadline, cancel)) {
            d.error = "request: " + ec.message();
            return d;
        }
        beast::flat_buffer buffer;
        http::response_parser<http::buffer_body> parser;
        // Not boost::none: Boost 1.74 compares the length with the empty optional
        // and refuses every body.
        parser.body_limit(std::numeric_limits<std::uint64_t>::max());
        if (auto ec = step([&](auto h) { http::async_read_header(stream, buffer, parser, h); }, deadline, cancel)) {
            d.error = "response header: " + ec.message();
            return d;
        }
        if (parser.get().result() != http::status::ok) {
            d.error = "HTTP " + std::to_string(parser.get().result_int());
            return d;
        }
        std::unique_ptr<EVP_MD_CTX, decltype(&EVP_MD_CTX_free)> md(EVP_MD_CTX_new(), EVP_MD_CTX_free);
        if (hash) EVP_DigestInit_ex(md.get(), EVP_sha256(), nullptr);
        std::vector<char> chunk(1 << 20);
        while (!parser.is_done()) {
            parser.get().body().data = chunk.data();
            parser.get().body().size = chunk.size();
            parser.get().body().more = true;
            auto ec = step([&](auto h) { http::async_read(stream, buffer, parser, h); }, deadline, cancel);
            if (ec == http::error::need_buffer) ec = {};
            if (ec) {
                d.error = "body: " + ec.message();
                return d;
            }
            const std::size_t n = chunk.size() - parser.get().body().size;
            if (hash) EVP_DigestUpdate(md.get(), chunk.data(), n);
            d.bytes += n;
        }
        d.seconds = Seconds(Clock::now() - t0).count();
        if (hash) {
            unsigned char digest[EVP_MAX_MD_SIZE];
            unsigned int size = 0;
            EVP_DigestFinal_ex(md.get(), digest, &size);
            static constexpr char kHex[] = "0123456789abcdef";
            for (unsigned i = 0; i < size; ++i) {
                d.sha256 += kHex[digest[i] >> 4];
                d.sha256 += kHex[digest[i] & 15];
            }
        }
        beast::get_lowest_layer(stream).close();
        d.ok = true;
        return d;
    }

    const std::optional<Points>& points() const { return points_; }

private:
    // One completion handler type for every step, so that each of Beast's
    // operations is instantiated once however many steps start it.
    struct StepDone {
        bool* done;
        beast::error_code* result;
        void operator()(beast::error_code ec, std::size_t = 0) const {
            *done = true;
            *result = ec;
        }
    };

    template <class Init>
    beast::error_code step(Init init, Clock::time_point deadline) {
        return step(init, deadline, [this] {
            if (ws_) beast::get_lowest_layer(*ws_).close();
        });
    }
    template <class Init, class Cancel>
    beast::error_code step(Init init, Clock::time_point deadline, Cancel cancel) {
        bool done = false;
        beast::error_code result;
        io_.restart();
        init(StepDone{&done, &result});
        while (!done && Clock::now() < deadline) io_.run_one_until(deadline);
        if (!done) {
            cancel();
            io_.restart();
            while (!done && io_.run_one() > 0) {
            }
            return net::error::timed_out;
        }
        return result;
    }

    net::io_context io_;
    ssl::context& tls_;
    net::ip::tcp::endpoint endpoint_;
    std::string token_;
    std::optional<websocket::stream<beast::ssl_stream<beast::tcp_stream>>> ws_;
    std::optional<Points> points_;
    int grabs_ = 0;
};

// ---- the report -----------------------------------------------------------------------------

struct Results {
    Options options;
    std::string machine, started, loadavg_start, loadavg_end;
    long nofile = 0;
    std::string nofile_note;
    int connected = 0;
    double connect_s = 0, connect_p50 = 0, connect_p99 = 0, connect_max = 0;
    long aims_sent = 0, aims_answered = 0, grabs_sent = 0, grabs_answered = 0, grabs_file = 0, grabs_url = 0,
         grabs_other = 0;
    double aim_p50 = 0, aim_p99 = 0, aim_max = 0;
    double grab_p50 = 0, grab_p90 = 0, grab_p99 = 0, grab_max = 0;
    std::map<std::string, long> errors;
    long error_total = 0;
    double load_wall_s = 0, server_cpu_load_s = 0, server_cpu_connect_s = 0, client_cpu_load_s = 0;
    std::vector<double> server_thread_cpu_load;
    long server_rss_before = 0, server_rss_idle = 0, server_rss_after_load = 0, server_hwm = 0;
    long client_rss_before = 0, client_rss_idle = 0;
    double kib_per_idle_client = 0, client_kib_per_client = 0;
    double cold_grab_ms = std::nan(""), warm_grab_ms = std::nan("");
    std::vector<double> download_mbps;
    double download_median_mbps = std::nan(""), download_median_mibps = std::nan("");
    double sha_mbps = std::nan("");
    std::string sha_check;
    double server_cpu_per_gb = std::nan("");
    std::vector<std::string> download_errors;
    double total_s = 0;
};

std::string met(bool ok) { return ok ? "met" : "**missed**"; }

std::string markdown(const Results& r) {
    std::ostringstream o;
    const auto& opt = r.options;
    o << "| measure | value | target | |\n|---|---|---|---|\n";
    o << "| clients welcomed | " << r.connected << " / " << opt.clients << " | | |\n";
    o << "| connect, all " << opt.clients << " at once (TCP + TLS + WebSocket + hello) | " << fmt(r.connect_s * 1000, 0)
      << " ms until the last welcome; per client p50 " << fmt(r.connect_p50, 1) << " ms, p99 " << fmt(r.connect_p99, 1)
      << " ms, max " << fmt(r.connect_max, 1) << " ms | | |\n";
    o << "| aims sent / answered | " << r.aims_sent << " / " << r.aims_answered << " ("
      << fmt(r.aims_sent / std::max(r.load_wall_s, 1e-9), 0) << " a second) | | |\n";
    o << "| aim round trip p50 / p99 / max | " << fmt(r.aim_p50) << " / " << fmt(r.aim_p99) << " / " << fmt(r.aim_max)
      << " ms | | |\n";
    o << "| grabs sent / answered with content (file, url) | " << r.grabs_sent << " / " << r.grabs_answered << " ("
      << r.grabs_file << ", " << r.grabs_url << (r.grabs_other ? ", other " + std::to_string(r.grabs_other) : "")
      << ") | | |\n";
    o << "| grab round trip p50 / p90 / p99 / max | " << fmt(r.grab_p50) << " / " << fmt(r.grab_p90) << " / "
      << fmt(r.grab_p99) << " / " << fmt(r.grab_max) << " ms | p99 ≤ 20 ms | " << met(r.grab_p99 <= 20) << " |\n";
    std::string kinds;
    for (const auto& [k, n] : r.errors) kinds += (kinds.empty() ? "" : "; ") + k + ": " + std::to_string(n);
    o << "| errors | " << r.error_total << (kinds.empty() ? "" : " (" + kinds + ")") << " | 0 | "
      << met(r.error_total == 0) << " |\n";
    std::string threads;
    for (double t : r.server_thread_cpu_load) threads += (threads.empty() ? "" : ", ") + fmt(t);
    o << "| server CPU during the load (/proc/PID/stat utime+stime, all threads) | " << fmt(r.server_cpu_load_s)
      << " s in " << fmt(r.load_wall_s) << " s = " << fmt(100 * r.server_cpu_load_s / std::max(r.load_wall_s, 1e-9), 0)
      << " % of one core (threads that used CPU: " << threads << " s) | | |\n";
    o << "| server CPU for the " << opt.clients << " connects | " << fmt(r.server_cpu_connect_s) << " s | | |\n";
    o << "| client side CPU during the load (getrusage, same cores) | " << fmt(r.client_cpu_load_s) << " s = "
      << fmt(100 * r.client_cpu_load_s / std::max(r.load_wall_s, 1e-9), 0) << " % of one core | | |\n";
    o << "| server RSS: started / " << r.connected << " idle clients / after the load / peak (VmHWM) | "
      << r.server_rss_before << " / " << r.server_rss_idle << " / " << r.server_rss_after_load << " / " << r.server_hwm
      << " KiB | | |\n";
    o << "| server memory per idle client | " << fmt(r.kib_per_idle_client, 1) << " KiB | ≤ 100 KiB | "
      << met(r.kib_per_idle_client <= 100) << " |\n";
    o << "| client side memory per connection (for comparison, not a target) | " << fmt(r.client_kib_per_client, 1)
      << " KiB | | |\n";
    if (opt.download_mb > 0) {
        if (opt.no_warm_up)
            o << "| first grab of the " << opt.download_mb << " MB file (server hashes it) | left to the load clients (--no-warm-up) | | |\n";
        else
            o << "| first grab of the " << opt.download_mb << " MB file, before the load (server hashes it) / next grab (cached) | "
              << fmt(r.cold_grab_ms, 1) << " / " << fmt(r.warm_grab_ms, 1) << " ms | | |\n";
        std::string runs;
        for (double v : r.download_mbps) runs += (runs.empty() ? "" : ", ") + fmt(v, 0);
        o << "| download of " << opt.download_mb << " MB, median of 3 (runs) | " << fmt(r.download_median_mbps, 0)
          << " MB/s = " << fmt(r.download_median_mibps, 0) << " MiB/s (" << runs << ") | ≥ 200 MB/s | "
          << met(r.download_median_mbps >= 200) << " |\n";
        o << "| download with SHA-256 checked while streaming | " << fmt(r.sha_mbps, 0) << " MB/s, " << r.sha_check
          << " | | |\n";
        o << "| server CPU per GB downloaded | " << fmt(r.server_cpu_per_gb) << " s | | |\n";
        if (!r.download_errors.empty()) {
            std::string e;
            for (const auto& s : r.download_errors) e += (e.empty() ? "" : "; ") + s;
            o << "| download errors | " << e << " | | |\n";
        }
    }
    return o.str();
}

std::string json_escape(const std::string& s) {
    std::string out;
    for (char c : s) {
        if (c == '"' || c == '\\') out += '\\';
        if (static_cast<unsigned char>(c) < 0x20) {
            out += ' ';
            continue;
        }
        out += c;
    }
    return out;
}

std::string json(const Results& r) {
    std::ostringstream o;
    auto num = [](double v) { return std::isnan(v) ? std::string("null") : fmt(v, 3); };
    auto arr = [&](const std::vector<double>& v) {
        std::string s = "[";
        for (std::size_t i = 0; i < v.size(); ++i) s += (i ? "," : "") + num(v[i]);
        return s + "]";
    };
    const auto& opt = r.options;
    o << "{\n  \"command\": \"" << json_escape(opt.command_line) << "\",\n"
      << "  \"clients\": " << opt.clients << ", \"seconds\": " << num(opt.seconds)
      << ", \"grab_every\": " << num(opt.grab_every) << ", \"server_threads\": " << opt.server_threads
      << ", \"client_threads\": " << opt.client_threads << ", \"download_mb\": " << opt.download_mb
      << ", \"raised_limits\": " << (opt.raise_limits ? "true" : "false")
      << ", \"no_warm_up\": " << (opt.no_warm_up ? "true" : "false") << ",\n"
      << "  \"connected\": " << r.connected << ", \"connect_s\": " << num(r.connect_s)
      << ", \"connect_ms\": {\"p50\": " << num(r.connect_p50) << ", \"p99\": " << num(r.connect_p99)
      << ", \"max\": " << num(r.connect_max) << "},\n"
      << "  \"aims_sent\": " << r.aims_sent << ", \"aims_answered\": " << r.aims_answered
      << ", \"aim_ms\": {\"p50\": " << num(r.aim_p50) << ", \"p99\": " << num(r.aim_p99) << ", \"max\": " << num(r.aim_max)
      << "},\n"
      << "  \"grabs_sent\": " << r.grabs_sent << ", \"grabs_answered\": " << r.grabs_answered
      << ", \"grabs_file\": " << r.grabs_file << ", \"grabs_url\": " << r.grabs_url
      << ", \"grab_ms\": {\"p50\": " << num(r.grab_p50) << ", \"p90\": " << num(r.grab_p90) << ", \"p99\": "
      << num(r.grab_p99) << ", \"max\": " << num(r.grab_max) << "},\n  \"errors\": {";
    bool first = true;
    for (const auto& [k, n] : r.errors) {
        o << (first ? "" : ", ") << "\"" << json_escape(k) << "\": " << n;
        first = false;
    }
    o << "}, \"error_total\": " << r.error_total << ",\n"
      << "  \"load_wall_s\": " << num(r.load_wall_s) << ", \"server_cpu_load_s\": " << num(r.server_cpu_load_s)
      << ", \"server_thread_cpu_load_s\": " << arr(r.server_thread_cpu_load)
      << ", \"server_cpu_connect_s\": " << num(r.server_cpu_connect_s)
      << ", \"client_cpu_load_s\": " << num(r.client_cpu_load_s) << ",\n"
      << "  \"server_rss_kib\": {\"before\": " << r.server_rss_before << ", \"idle\": " << r.server_rss_idle
      << ", \"after_load\": " << r.server_rss_after_load << ", \"hwm\": " << r.server_hwm << "},\n"
      << "  \"client_rss_kib\": {\"before\": " << r.client_rss_before << ", \"idle\": " << r.client_rss_idle << "},\n"
      << "  \"server_kib_per_idle_client\": " << num(r.kib_per_idle_client)
      << ", \"client_kib_per_client\": " << num(r.client_kib_per_client) << ",\n"
      << "  \"cold_grab_ms\": " << num(r.cold_grab_ms) << ", \"warm_grab_ms\": " << num(r.warm_grab_ms) << ",\n"
      << "  \"download_mbps\": " << arr(r.download_mbps) << ", \"download_median_mbps\": " << num(r.download_median_mbps)
      << ", \"download_median_mibps\": " << num(r.download_median_mibps) << ", \"sha_mbps\": " << num(r.sha_mbps)
      << ", \"sha_check\": \"" << json_escape(r.sha_check) << "\", \"server_cpu_per_gb_s\": " << num(r.server_cpu_per_gb)
      << ",\n  \"nofile\": " << r.nofile << ", \"total_s\": " << num(r.total_s) << ", \"machine\": \""
      << json_escape(r.machine) << "\", \"loadavg_start\": \"" << r.loadavg_start << "\", \"loadavg_end\": \""
      << r.loadavg_end << "\"\n}\n";
    return o.str();
}

// ---- setup helpers ---------------------------------------------------------------------------

struct TempDir {
    fs::path path;
    TempDir() {
        std::string tmpl = (fs::temp_directory_path() / "umf-load-XXXXXX").string();
        if (!mkdtemp(tmpl.data())) throw std::runtime_error("mkdtemp failed");
        path = tmpl;
    }
    ~TempDir() {
        std::error_code ec;
        fs::remove_all(path, ec);
    }
};

void write_random_file(const fs::path& file, std::uint64_t bytes) {
    std::ofstream out(file, std::ios::binary);
    std::vector<unsigned char> chunk(1 << 20);
    for (std::uint64_t left = bytes; left > 0;) {
        const std::size_t n = static_cast<std::size_t>(std::min<std::uint64_t>(left, chunk.size()));
        if (RAND_bytes(chunk.data(), static_cast<int>(n)) != 1) throw std::runtime_error("RAND_bytes failed");
        out.write(reinterpret_cast<const char*>(chunk.data()), static_cast<std::streamsize>(n));
        left -= n;
    }
    if (!out) throw std::runtime_error("cannot write " + file.string());
}

// Each client needs a descriptor here and one in the server child.
long raise_nofile(long needed, std::string& note) {
    rlimit lim{};
    getrlimit(RLIMIT_NOFILE, &lim);
    if (lim.rlim_cur >= static_cast<rlim_t>(needed)) return static_cast<long>(lim.rlim_cur);
    rlimit want = lim;
    want.rlim_cur = std::min<rlim_t>(static_cast<rlim_t>(needed), lim.rlim_max);
    if (setrlimit(RLIMIT_NOFILE, &want) != 0 || want.rlim_cur < static_cast<rlim_t>(needed))
        note = "RLIMIT_NOFILE could only be raised to " + std::to_string(want.rlim_cur) + " of the " +
               std::to_string(needed) + " needed";
    getrlimit(RLIMIT_NOFILE, &lim);
    return static_cast<long>(lim.rlim_cur);
}

std::string shell_line(const char* command) {
    std::string out;
    if (FILE* f = ::popen(command, "r")) {
        char buf[256];
        while (std::fgets(buf, sizeof buf, f)) out += buf;
        ::pclose(f);
    }
    while (!out.empty() && (out.back() == '\n' || out.back() == ' ')) out.pop_back();
    return out;
}

bool wait_for(const std::function<bool()>& done, Clock::time_point deadline) {
    while (!done() && Clock::now() < deadline) std::this_thread::sleep_for(std::chrono::milliseconds(10));
    return done();
}

pid_t g_child = -1;

void on_alarm(int) {
    if (g_child > 0) ::kill(g_child, SIGKILL);
    static const char text[] = "umf_load_benchmark: out of time, stopped\n";
    (void)!::write(2, text, sizeof text - 1);
    ::_exit(3);
}

void log(const std::string& text) {
    std::fprintf(stderr, "[load] %s\n", text.c_str());
    std::fflush(stderr);
}

}  // namespace

int main(int argc, char** argv) {
    const Options opt = parse_options(argc, argv);
    const auto start = Clock::now();
    // The whole run's budget; every phase below takes its deadline from it.
    const auto hard_end = start + std::chrono::duration_cast<Clock::duration>(Seconds(opt.seconds + 30));
    const auto soft_end = hard_end - std::chrono::seconds(3);
    std::signal(SIGALRM, on_alarm);
    std::signal(SIGPIPE, SIG_IGN);
    ::alarm(static_cast<unsigned>(std::ceil(opt.seconds + 30)));

    Results r;
    r.options = opt;
    r.machine = shell_line("nproc") + " CPUs, " + shell_line("lscpu | grep 'Model name' | sed 's/.*: *//'");
    r.started = shell_line("date '+%Y-%m-%d %H:%M'");
    // Clients and server share the cores with whatever else runs: the load
    // average says how much that was.
    r.loadavg_start = shell_line("cut -d' ' -f1-3 /proc/loadavg");
    r.nofile = raise_nofile(opt.clients + 256, r.nofile_note);
    if (!r.nofile_note.empty()) log(r.nofile_note);

    try {
        TempDir dir;
        // With --download-mb 0 the board still needs a file to grab.
        const std::uint64_t file_bytes = opt.download_mb > 0 ? std::uint64_t(opt.download_mb) * 1000000 : 1000000;
        const fs::path file = dir.path / "load.bin";
        write_random_file(file, file_bytes);
        const TlsIdentity identity = create_tls_identity();
        const std::string token = make_token();

        ServerChild child = start_server_child(opt, identity, token, file, static_cast<int>(opt.seconds) + 40);
        g_child = child.pid;
        log("server child " + std::to_string(child.pid) + " on port " + std::to_string(child.port));

        ssl::context tls = pinned_client_context(identity.fingerprint);
        Shared shared;
        shared.tls = &tls;
        shared.endpoint = net::ip::tcp::endpoint(net::ip::make_address("127.0.0.1"), child.port);
        shared.token = token;

        std::this_thread::sleep_for(std::chrono::milliseconds(500));
        r.server_rss_before = proc_status_kib(child.pid, "VmRSS:");
        r.client_rss_before = proc_status_kib(::getpid(), "VmRSS:");

        // ---- connect every client at once --------------------------------------------------
        net::io_context io(opt.client_threads);
        auto work = net::make_work_guard(io);
        std::vector<std::shared_ptr<LoadClient>> clients;
        for (int i = 0; i < opt.clients; ++i) clients.push_back(std::make_shared<LoadClient>(io, shared, i));
        std::vector<std::thread> threads;
        for (int i = 0; i < opt.client_threads; ++i) threads.emplace_back([&io] { io.run(); });

        const double cpu_before_connect = process_cpu(child.pid);
        const auto connect_start = Clock::now();
        for (auto& c : clients) c->start();
        wait_for([&] { return shared.welcomed + shared.finished >= opt.clients; },
                 std::min(soft_end, connect_start + std::chrono::seconds(10)));
        r.connect_s = Seconds(Clock::now() - connect_start).count();
        for (auto& c : clients) c->give_up_connecting();
        r.connected = shared.welcomed;
        log(std::to_string(r.connected) + " clients welcomed in " + fmt(r.connect_s, 2) + " s");

        std::this_thread::sleep_for(kSettle);
        r.server_cpu_connect_s = process_cpu(child.pid) - cpu_before_connect;
        r.server_rss_idle = proc_status_kib(child.pid, "VmRSS:");
        r.client_rss_idle = proc_status_kib(::getpid(), "VmRSS:");
        if (r.connected > 0) {
            r.kib_per_idle_client = double(r.server_rss_idle - r.server_rss_before) / r.connected;
            r.client_kib_per_client = double(r.client_rss_idle - r.client_rss_before) / r.connected;
        }

        // The first grab of the file hashes it on the server, inside the
        // session's handler; it is kept out of the load unless asked for.
        StepClient requester(tls, shared.endpoint, token);
        auto cold_and_warm_grab = [&] {
            if (auto e = requester.connect(std::min(soft_end, Clock::now() + std::chrono::seconds(5))); !e.empty()) {
                r.download_errors.push_back("connect: " + e);
                return;
            }
            const auto cold = requester.grab(requester.points()->file(), std::min(soft_end, Clock::now() + std::chrono::seconds(10)));
            if (cold.ok) r.cold_grab_ms = cold.ms;
            else r.download_errors.push_back("cold grab: " + cold.error);
            const auto warm = requester.grab(requester.points()->file(), std::min(soft_end, Clock::now() + std::chrono::seconds(5)));
            if (warm.ok) r.warm_grab_ms = warm.ms;
            else r.download_errors.push_back("warm grab: " + warm.error);
            requester.close(soft_end);
        };
        if (!opt.no_warm_up) cold_and_warm_grab();

        // ---- the load ---------------------------------------------------------------------
        const auto t0 = Clock::now() + std::chrono::milliseconds(50);
        const auto load_end = t0 + std::chrono::duration_cast<Clock::duration>(Seconds(opt.seconds));
        const double cpu_load0 = process_cpu(child.pid);
        const auto threads0 = thread_cpu(child.pid);
        const double client_cpu0 = self_cpu();
        for (auto& c : clients) c->begin_load(t0, load_end, Seconds(opt.grab_every));
        std::this_thread::sleep_until(std::min(load_end, soft_end));
        const double cpu_load1 = process_cpu(child.pid);
        const auto threads1 = thread_cpu(child.pid);
        const double client_cpu1 = self_cpu();
        r.load_wall_s = Seconds(Clock::now() - t0).count();
        r.server_cpu_load_s = cpu_load1 - cpu_load0;
        r.client_cpu_load_s = client_cpu1 - client_cpu0;
        for (const auto& [tid, cpu] : threads1) {
            const auto it = threads0.find(tid);
            const double used = cpu - (it == threads0.end() ? 0.0 : it->second);
            if (used > 0.005) r.server_thread_cpu_load.push_back(used);
        }
        std::sort(r.server_thread_cpu_load.rbegin(), r.server_thread_cpu_load.rend());
        wait_for([&] { return shared.drained >= shared.loading; },
                 std::min(soft_end, load_end + kReplyTimeout + std::chrono::milliseconds(300)));
        r.server_rss_after_load = proc_status_kib(child.pid, "VmRSS:");
        log("load done");

        // ---- close, then gather ------------------------------------------------------------------
        for (auto& c : clients) c->close();
        wait_for([&] { return shared.finished >= opt.clients; }, std::min(soft_end, Clock::now() + std::chrono::seconds(2)));
        for (auto& c : clients) c->abort();
        wait_for([&] { return shared.finished >= opt.clients; }, std::min(soft_end, Clock::now() + std::chrono::milliseconds(500)));
        work.reset();
        io.stop();
        for (auto& t : threads) t.join();

        std::vector<double> connect_ms, aim_ms, grab_ms;
        for (const auto& c : clients) {
            const ClientStats& s = c->stats();
            if (!std::isnan(s.connect_ms)) connect_ms.push_back(s.connect_ms);
            aim_ms.insert(aim_ms.end(), s.aim_ms.begin(), s.aim_ms.end());
            grab_ms.insert(grab_ms.end(), s.grab_ms.begin(), s.grab_ms.end());
            r.aims_sent += s.aims_sent;
            r.aims_answered += s.aims_answered;
            r.grabs_sent += s.grabs_sent;
            r.grabs_answered += s.grabs_answered;
            r.grabs_file += s.grabs_file;
            r.grabs_url += s.grabs_url;
            r.grabs_other += s.grabs_other;
            for (const auto& [k, n] : s.errors) r.errors[k] += n;
        }
        r.connect_p50 = percentile(connect_ms, 50);
        r.connect_p99 = percentile(connect_ms, 99);
        r.connect_max = percentile(connect_ms, 100);
        r.aim_p50 = percentile(aim_ms, 50);
        r.aim_p99 = percentile(aim_ms, 99);
        r.aim_max = percentile(aim_ms, 100);
        r.grab_p50 = percentile(grab_ms, 50);
        r.grab_p90 = percentile(grab_ms, 90);
        r.grab_p99 = percentile(grab_ms, 99);
        r.grab_max = percentile(grab_ms, 100);

        // ---- downloads: 3 plain, then 1 hashed while streaming -------------------------------------
        if (opt.download_mb > 0) {
            const double cpu_dl0 = process_cpu(child.pid);
            std::uint64_t downloaded = 0;
            if (auto e = requester.connect(std::min(soft_end, Clock::now() + std::chrono::seconds(5))); !e.empty()) {
                r.download_errors.push_back("connect: " + e);
            } else {
                for (int run = 0; run < 4 && Clock::now() < soft_end; ++run) {
                    const bool hash = run == 3;
                    const auto g = requester.grab(requester.points()->file(), std::min(soft_end, Clock::now() + std::chrono::seconds(5)));
                    if (!g.ok || !g.content.download) {
                        r.download_errors.push_back("grab " + std::to_string(run + 1) + ": " + g.error);
                        continue;
                    }
                    const auto d = requester.download(*g.content.download, hash, soft_end);
                    downloaded += d.bytes;
                    if (!d.ok || d.bytes != file_bytes) {
                        r.download_errors.push_back("download " + std::to_string(run + 1) + ": " +
                                                    (d.ok ? std::to_string(d.bytes) + " bytes" : d.error));
                        continue;
                    }
                    const double mbps = double(d.bytes) / 1e6 / d.seconds;
                    log("download " + std::to_string(run + 1) + ": " + fmt(mbps, 0) + " MB/s" + (hash ? " (hashed)" : ""));
                    if (hash) {
                        r.sha_mbps = mbps;
                        r.sha_check = d.sha256 == g.content.sha256.value_or("") ? "matches the content's sha256"
                                                                                : "**does not match** the content's sha256";
                    } else {
                        r.download_mbps.push_back(mbps);
                    }
                }
                requester.close(soft_end);
            }
            if (downloaded > 0) r.server_cpu_per_gb = (process_cpu(child.pid) - cpu_dl0) / (double(downloaded) / 1e9);
            if (!r.download_mbps.empty()) {
                r.download_median_mbps = median(r.download_mbps);
                r.download_median_mibps = r.download_median_mbps * 1e6 / (1 << 20);
            }
            if (r.download_mbps.size() < 3) r.download_errors.push_back("fewer than 3 plain runs finished");
        }
        for (const auto& e : r.download_errors) ++r.errors["download: " + e.substr(0, e.find(':'))];
        for (const auto& [k, n] : r.errors) r.error_total += n;

        r.server_hwm = proc_status_kib(child.pid, "VmHWM:");
        stop_server_child(child);
        g_child = -1;
        clients.clear();
    } catch (const std::exception& e) {
        if (g_child > 0) ::kill(g_child, SIGKILL);
        std::fprintf(stderr, "umf_load_benchmark: %s\n", e.what());
        return 1;
    }
    r.total_s = Seconds(Clock::now() - start).count();
    r.loadavg_end = shell_line("cut -d' ' -f1-3 /proc/loadavg");

    std::ostringstream md;
    md << "Command: `" << opt.command_line << "`  \n";
    md << "Machine: " << r.machine << "; server threads " << opt.server_threads << ", client threads "
       << opt.client_threads << "; limits " << (opt.raise_limits ? "raised (100 aims/s, 1000 grabs/min)" : "the defaults (10 aims/s, 30 grabs/min)")
       << "; RLIMIT_NOFILE " << r.nofile << (r.nofile_note.empty() ? "" : " (" + r.nofile_note + ")") << "; started "
       << r.started << ", took " << fmt(r.total_s, 1) << " s; load average (1, 5, 15 min) " << r.loadavg_start
       << " at the start, " << r.loadavg_end << " at the end\n\n";
    md << markdown(r);
    std::cout << md.str() << std::flush;
    if (!opt.out.empty()) std::ofstream(opt.out) << md.str();
    if (!opt.json.empty()) std::ofstream(opt.json) << json(r);
    return 0;
}
