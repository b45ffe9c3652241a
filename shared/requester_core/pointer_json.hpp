// The Pointer's events and steps as JSON: how the phone page drives the same
// rules through the WebAssembly module, and how the scenario files under
// tests/data/requester_core say what happens and what must come of it.
//
// Setup: {"welcome": {...the welcome message...}, "auto": false,
//         "timing": {"steady_s": 0.5, ...}}                       (all but welcome optional)
// Events, each with "t" in seconds:
//   {"event": "frame", "locked": true, "point": [u, v], "confidence": 0.9, "another_field": false}
//   {"event": "tap"}            {"event": "tick"}          {"event": "dismiss"}
//   {"event": "message", "message": {...a provider's message...}}
//   {"event": "downloaded", "ok": true, "message": "why not"}
//   {"event": "uploaded", "status": 200, "body": "the HTTP answer's body", "failure": "why"}
//   {"event": "hashed", "sha256": "..."}
//   {"event": "closed", "code": 1006}
//   {"event": "choose_put", "item": {"kind": "url", "url": "...", "title": "..."}}
//        or {"kind": "file", "name": "...", "mime": "...", "size": n, "sha256": "...", "title": "..."}
//   {"event": "leave_put"}      {"event": "auto", "on": true}
// Answer: {"send": [messages], "download": {content}, "upload": "/up/...",
//          "reconnect": false, "notice": {error}, "view": {...}}
// (download, upload and notice only when there is one).
#pragma once

#include <nlohmann/json.hpp>

#include "shared/requester_core/pointer.hpp"

namespace umf::requester_core {

// Throws std::invalid_argument naming what is wrong.
Pointer pointer_from_json(const nlohmann::json& setup);

// Applies one event and returns the step and the view after it. Throws
// std::invalid_argument for an event it cannot read (a provider's message
// that breaks the protocol among them).
nlohmann::json apply_json_event(Pointer& pointer, const nlohmann::json& event);

nlohmann::json view_json(const View& view);
nlohmann::json step_json(const Step& step);

}  // namespace umf::requester_core
