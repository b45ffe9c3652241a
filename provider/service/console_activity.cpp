#include "provider/service/console_activity.hpp"

#include "provider/put/put_text.hpp"

namespace umf::provider {

std::string printable(const std::string& text, std::size_t max_bytes) {
    std::string out = printable_text(text);
    if (out.size() <= max_bytes) return out;
    std::size_t cut = max_bytes;
    // printable_text leaves whole UTF-8 sequences only: back up to the start of one.
    while (cut > 0 && (static_cast<unsigned char>(out[cut]) & 0xc0) == 0x80) --cut;
    out.resize(cut);
    return out + "...";
}

namespace {

std::string quoted(const std::string& text) { return "\"" + printable(text) + "\""; }

// What the put is called in its later lines: the file's name, the URL's title or the URL.
std::string put_label(const PutActivity& a) {
    if (a.kind == protocol::ContentKind::url && a.name.empty()) return quoted(a.url);
    return quoted(a.name);
}

std::string with_detail(const std::string& text, const std::string& detail) {
    return detail.empty() ? text : text + " (" + printable(detail, 200) + ")";
}

}  // namespace

std::string put_line(const PutActivity& a) {
    const std::string who = "requester " + std::to_string(a.session);
    const bool url = a.kind == protocol::ContentKind::url;
    const std::string file_and_size = printable(a.name) + " (" + std::to_string(a.size) + " bytes)";
    std::string what = url ? "url " + (a.name.empty() ? std::string() : quoted(a.name) + " ") + "<" +
                                 printable(a.url, 200) + ">"
                           : "file " + quoted(a.name) + " (" + std::to_string(a.size) + " bytes)";
    // The phone's own name for itself; its device id only when it gave none.
    if (!a.client.empty()) what += " from " + quoted(a.client);
    else if (!a.device.empty()) what += " from " + quoted(a.device);
    // The first line of a put says what it is; the later ones name it.
    const std::string first = who + " puts " + what;
    const std::string later = who + "'s put " + put_label(a);
    switch (a.stage) {
    case PutStage::asking: return first + ": asking the screen";
    case PutStage::accepted: {
        std::string how = a.answer;
        if (a.trusted) how += ", a device always accepted";
        if (a.always) how += ", always from now on";
        return (a.asked ? later : first) + ": accepted (" + how + ")";
    }
    case PutStage::refused: return with_detail((a.asked ? later : first) + ": refused", a.detail);
    case PutStage::timed_out: return with_detail(later + ": timed out", a.detail);
    case PutStage::withdrawn: return later + ": withdrawn, the requester left";
    case PutStage::stored: return who + " put " + file_and_size + " \u2192 saved as " + printable(a.path, 512);
    case PutStage::opened:
        if (url) return who + " put url <" + printable(a.url, 200) + "> \u2192 opened";
        return who + " put " + file_and_size + " \u2192 saved as " + printable(a.path, 512) + " and opened";
    case PutStage::failed: return with_detail(later + ": failed", a.detail);
    }
    return later;
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

void ConsoleActivity::refused(const RefusedActivity& r) {
    std::string who = r.client.empty() ? std::string("a requester") : "requester " + quoted(r.client);
    if (!r.device.empty()) who += " (" + quoted(r.device) + ")";
    if (!r.peer.empty()) who += " from " + printable(r.peer, 64);
    line(r.rate_limited ? who + " refused: too many wrong pairing tokens from its address; refusing it for a minute"
                        : who + " refused: its pairing token is not this provider's (pair it again: " +
                              "scan the QR code, or umf-provider pair)");
    if (next_) next_->refused(r);
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

void ConsoleActivity::put(const PutActivity& a) {
    line(put_line(a));
    if (next_) next_->put(a);
}

void ConsoleActivity::left(std::uint64_t session) {
    line("requester " + std::to_string(session) + " left");
    if (next_) next_->left(session);
}

}  // namespace umf::provider
