#include "server/console_activity.hpp"

namespace umf::provider {

std::string printable(const std::string& text, std::size_t max_bytes) {
    std::string out;
    for (unsigned char c : text) {
        if (out.size() >= max_bytes) {
            out += "...";
            break;
        }
        out += (c < 0x20 || c == 0x7f) ? '?' : static_cast<char>(c);
    }
    return out;
}

ConsoleActivity::ConsoleActivity(std::ostream& out, std::shared_ptr<ActivityListener> next)
    : out_(out), next_(std::move(next)) {}

void ConsoleActivity::line(const std::string& text) {
    std::lock_guard lock(mutex_);
    out_ << text << "\n" << std::flush;
}

void ConsoleActivity::welcomed(const WelcomeActivity& w) {
    line("requester " + std::to_string(w.session) + " connected: " +
         (w.client.empty() ? std::string("(no name)") : printable(w.client)) +
         (w.peer.empty() ? "" : " from " + printable(w.peer, 64)));
    if (next_) next_->welcomed(w);
}

void ConsoleActivity::seeking(std::uint64_t session) {
    if (next_) next_->seeking(session);
}

void ConsoleActivity::aimed(const AimActivity& aim) {
    if (next_) next_->aimed(aim);
}

void ConsoleActivity::grabbed(const GrabActivity& g) {
    std::string what = protocol::to_string(g.kind);
    if (!g.name.empty()) what += " " + printable(g.name) + ", " + std::to_string(g.size) + " bytes";
    line("requester " + std::to_string(g.session) + " took \"" + printable(g.title) + "\" (" + what + ")");
    if (next_) next_->grabbed(g);
}

void ConsoleActivity::left(std::uint64_t session) {
    line("requester " + std::to_string(session) + " left");
    if (next_) next_->left(session);
}

}  // namespace umf::provider
