// The requester core (shared/requester_core/pointer.hpp) under whatever a
// provider may send: each line of the input is one message's text, given
// to a Pointer between frames, taps and the time passing, in grab mode and
// in put mode. Texts that do not parse are what the connection drops; the
// rest go in. The core must never crash, and its view must hold together:
// an outcome exactly in result and failed, put progress only while putting.
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>
#include <variant>

#include "shared/protocol/messages.hpp"
#include "shared/requester_core/pointer.hpp"

namespace p = umf::protocol;
namespace core = umf::requester_core;

namespace {

void check(const core::View& v) {
    const bool over = v.phase == core::Phase::result || v.phase == core::Phase::failed;
    if (over != v.outcome.has_value()) __builtin_trap();
    if (v.put != core::PutProgress::none && v.phase != core::Phase::putting) __builtin_trap();
}

void run(std::string_view input, bool put_mode) {
    p::Welcome welcome;
    welcome.provider = {"desk", "umf-provider/0"};
    core::Pointer pointer(welcome, core::Timing{}, false);
    if (put_mode) {
        core::PutItem item;
        item.kind = p::ContentKind::file;
        item.name = "a.txt";
        item.size = 3;
        item.sha256 = std::string(64, 'a');
        pointer.choose_put(0, item);
    }
    double t = 0;
    std::size_t at = 0;
    int line = 0;
    while (at <= input.size()) {
        const std::size_t end = std::min(input.find('\n', at), input.size());
        const std::string_view text = input.substr(at, end - at);
        at = end + 1;
        t += 0.1 * (1 + line % 7);
        pointer.frame(t, core::Sighting{line % 5 != 4, {1.0 + line % 3, 2.0}, 0.9, {}});
        if (line % 3 == 1) pointer.tap(t);
        const p::ParseResult parsed = p::parse_message(text, p::kRequesterLimits);
        if (const auto* message = std::get_if<p::Message>(&parsed)) {
            const core::Step step = pointer.received(t, *message);
            if (step.download) pointer.downloaded(t, line % 2 == 0, "cut");
            if (step.upload) pointer.uploaded(t, line % 2 == 0 ? 200 : 0, std::nullopt, "broke");
        }
        if (line % 4 == 3) pointer.tick(t + 30);
        if (line % 6 == 5) pointer.dismiss(t);
        check(pointer.view());
        ++line;
        if (end == input.size()) break;
    }
    pointer.closed(t, 1006);
    check(pointer.view());
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    const std::string_view input(reinterpret_cast<const char*>(data), size);
    run(input, false);
    run(input, true);
    return 0;
}
