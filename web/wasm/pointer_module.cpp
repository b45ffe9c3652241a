// The requester core (shared/requester_core) for the phone page, in the same
// WebAssembly module as the detector: one Pointer per handle, driven by JSON
// events (requester_core/pointer_json.hpp), so the page follows the very rules
// umf-requester follows; and the pairing URL's one codec
// (protocol/pairing_url.hpp). web/wasm/pointer.js wraps both.
//
//   h = umf_pointer_create(setup, n);       // null: umf_pointer_error(0) says why
//   a = umf_pointer_event(h, event, n);     // NUL-terminated JSON: the answer, or {"error": "..."}
//   umf_pointer_destroy(h);
//
// The answer's text lives in the handle until its next event. Nothing throws
// into JavaScript.
#include <emscripten/emscripten.h>

#include <memory>
#include <new>
#include <string>

#include "shared/protocol/pairing_url.hpp"
#include "shared/requester_core/pointer_json.hpp"

namespace {

struct PointerInstance {
    umf::requester_core::Pointer pointer;
    std::string answer;
};

// Why the last umf_pointer_create failed; a create has no handle to keep it in.
std::string& create_error() {
    static std::string text;
    return text;
}

std::string error_json(const std::string& why) { return nlohmann::json{{"error", why}}.dump(); }

}  // namespace

extern "C" {

EMSCRIPTEN_KEEPALIVE void* umf_pointer_create(const char* setup_json, int length) {
    create_error().clear();
    try {
        if (!setup_json || length < 0) throw std::invalid_argument("no setup text");
        const auto setup = nlohmann::json::parse(setup_json, setup_json + length);
        return new PointerInstance{umf::requester_core::pointer_from_json(setup), {}};
    } catch (const std::bad_alloc&) {
        create_error() = "out of memory";
    } catch (const std::exception& e) {
        create_error() = e.what();
    }
    return nullptr;
}

EMSCRIPTEN_KEEPALIVE void umf_pointer_destroy(void* handle) { delete static_cast<PointerInstance*>(handle); }

EMSCRIPTEN_KEEPALIVE const char* umf_pointer_event(void* handle, const char* event_json, int length) {
    auto* instance = static_cast<PointerInstance*>(handle);
    if (!instance) return nullptr;
    try {
        if (!event_json || length < 0) throw std::invalid_argument("no event text");
        const auto event = nlohmann::json::parse(event_json, event_json + length);
        instance->answer = umf::requester_core::apply_json_event(instance->pointer, event)
                               .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
    } catch (const std::bad_alloc&) {
        instance->answer = error_json("out of memory");
    } catch (const std::exception& e) {
        instance->answer = error_json(e.what());
    }
    return instance->answer.c_str();
}

// Why the last create failed ("" when it did not), NUL-terminated.
EMSCRIPTEN_KEEPALIVE const char* umf_pointer_error() { return create_error().c_str(); }

// A pairing URL read as the provider and umf-requester read it:
// {"host", "port", "token", "fingerprint", "name"} or {"error"}, NUL-terminated JSON
// valid until the next call.
EMSCRIPTEN_KEEPALIVE const char* umf_parse_pairing_url(const char* url, int length) {
    static std::string answer;
    try {
        if (!url || length < 0) throw umf::protocol::PairingUrlError("no URL");
        const auto parsed = umf::protocol::parse_pairing_url(std::string_view(url, static_cast<std::size_t>(length)));
        answer = nlohmann::json{{"host", parsed.host},
                                {"port", parsed.port},
                                {"token", parsed.token},
                                {"fingerprint", parsed.fingerprint},
                                {"name", parsed.name}}
                     .dump();
    } catch (const std::bad_alloc&) {
        answer = error_json("out of memory");
    } catch (const std::exception& e) {
        answer = error_json(e.what());
    }
    return answer.c_str();
}

}  // extern "C"
