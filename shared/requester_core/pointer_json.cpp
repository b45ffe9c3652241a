#include "shared/requester_core/pointer_json.hpp"

#include <stdexcept>

#include "shared/protocol/http_error_body.hpp"

namespace umf::requester_core {

namespace p = protocol;
using nlohmann::json;

namespace {

p::Message parse(const std::string& text, const char* what) {
    p::ParseResult parsed = p::parse_message(text, p::kRequesterLimits);
    if (const auto* problem = std::get_if<p::ProtocolError>(&parsed))
        throw std::invalid_argument(std::string(what) + " is not a protocol message: " + problem->message);
    return std::get<p::Message>(std::move(parsed));
}

json message_json(const p::Message& message) { return json::parse(p::encode(message)); }

double number(const json& event, const char* key, double otherwise) {
    const auto it = event.find(key);
    if (it == event.end()) return otherwise;
    if (!it->is_number()) throw std::invalid_argument(std::string("\"") + key + "\" must be a number");
    return it->get<double>();
}

std::string text(const json& event, const char* key) {
    const auto it = event.find(key);
    if (it == event.end() || it->is_null()) return {};
    if (!it->is_string()) throw std::invalid_argument(std::string("\"") + key + "\" must be a string");
    return it->get<std::string>();
}

p::FieldPoint point(const json& pair) {
    if (!pair.is_array() || pair.size() != 2 || !pair[0].is_number() || !pair[1].is_number())
        throw std::invalid_argument("a point is [u, v]");
    return {pair[0].get<double>(), pair[1].get<double>()};
}

json point_json(const p::FieldPoint& pt) { return json::array({pt.u, pt.v}); }

Sighting sighting(const json& event) {
    Sighting s;
    s.locked = event.value("locked", false);
    if (s.locked) s.point = point(event.at("point"));
    s.confidence = number(event, "confidence", 0.0);
    s.another_field = event.value("another_field", false);
    return s;
}

PutItem put_item(const json& item) {
    if (!item.is_object()) throw std::invalid_argument("a put item is an object");
    PutItem out;
    const std::string kind = text(item, "kind");
    out.title = text(item, "title");
    if (kind == "url") {
        out.kind = p::ContentKind::url;
        out.url = text(item, "url");
    } else if (kind == "file") {
        out.kind = p::ContentKind::file;
        out.name = text(item, "name");
        out.mime = text(item, "mime");
        out.size = static_cast<std::int64_t>(number(item, "size", -1));
        if (const std::string sha = text(item, "sha256"); !sha.empty()) out.sha256 = sha;
    } else {
        throw std::invalid_argument("a put item's kind is url or file");
    }
    return out;
}

// The upload's answer: a put_status, or the error envelope of every HTTP
// error (protocol/http_error_body.hpp); anything else is judged by its status.
std::optional<p::Message> upload_answer(const std::string& body) {
    if (body.empty()) return std::nullopt;
    if (auto error = p::parse_error_body(body)) return p::Message{*error};
    p::ParseResult parsed = p::parse_message(body, p::kRequesterLimits);
    if (auto* message = std::get_if<p::Message>(&parsed)) return std::move(*message);
    return std::nullopt;
}

Timing timing(const json& setup) {
    Timing t;
    const auto it = setup.find("timing");
    if (it == setup.end()) return t;
    const json& j = *it;
    t.steady_s = number(j, "steady_s", t.steady_s);
    t.steady_modules = number(j, "steady_modules", t.steady_modules);
    t.steady_min_frames = static_cast<int>(number(j, "steady_min_frames", t.steady_min_frames));
    t.max_aims_per_s = number(j, "max_aims_per_s", t.max_aims_per_s);
    t.seeking_interval_s = number(j, "seeking_interval_s", t.seeking_interval_s);
    t.hint_after_s = number(j, "hint_after_s", t.hint_after_s);
    t.another_screen_s = number(j, "another_screen_s", t.another_screen_s);
    t.another_gap_s = number(j, "another_gap_s", t.another_gap_s);
    t.grab_timeout_s = number(j, "grab_timeout_s", t.grab_timeout_s);
    t.put_reply_s = number(j, "put_reply_s", t.put_reply_s);
    t.screen_answer_s = number(j, "screen_answer_s", t.screen_answer_s);
    t.put_asking_s = number(j, "put_asking_s", t.put_asking_s);
    t.broken_upload_grace_s = number(j, "broken_upload_grace_s", t.broken_upload_grace_s);
    return t;
}

const char* mode_name(Mode mode) { return mode == Mode::put ? "put" : "grab"; }

}  // namespace

Pointer pointer_from_json(const json& setup) {
    if (!setup.is_object() || !setup.contains("welcome")) throw std::invalid_argument("the setup needs a welcome");
    p::Message welcome = parse(setup.at("welcome").dump(), "the welcome");
    const auto* w = std::get_if<p::Welcome>(&welcome);
    if (!w) throw std::invalid_argument("the setup's welcome is not a welcome");
    return Pointer(*w, timing(setup), setup.value("auto", false));
}

json apply_json_event(Pointer& pointer, const json& event) {
    if (!event.is_object()) throw std::invalid_argument("an event is an object");
    const std::string name = text(event, "event");
    const double t = number(event, "t", 0.0);
    Step step;
    if (name == "frame") step = pointer.frame(t, sighting(event));
    else if (name == "tap") step = pointer.tap(t);
    else if (name == "tick") step = pointer.tick(t);
    else if (name == "message") step = pointer.received(t, parse(event.at("message").dump(), "the message"));
    else if (name == "downloaded") step = pointer.downloaded(t, event.value("ok", false), text(event, "message"));
    else if (name == "uploaded")
        step = pointer.uploaded(t, static_cast<int>(number(event, "status", 0)), upload_answer(text(event, "body")),
                                text(event, "failure"));
    else if (name == "hashed") step = pointer.hashed(t, text(event, "sha256"));
    else if (name == "closed") step = pointer.closed(t, static_cast<int>(number(event, "code", 1006)));
    else if (name == "choose_put") pointer.choose_put(t, put_item(event.at("item")));
    else if (name == "leave_put") pointer.leave_put(t);
    else if (name == "auto") pointer.set_auto(event.value("on", false));
    else if (name == "dismiss") pointer.dismiss(t);
    else throw std::invalid_argument("unknown event \"" + name + "\"");
    json out = step_json(step);
    out["view"] = view_json(pointer.view());
    return out;
}

json step_json(const Step& step) {
    json out = json::object();
    out["send"] = json::array();
    for (const auto& message : step.send) out["send"].push_back(message_json(message));
    if (step.download) out["download"] = message_json(*step.download);
    if (step.upload) out["upload"] = *step.upload;
    out["reconnect"] = step.reconnect;
    if (step.notice) out["notice"] = message_json(*step.notice);
    return out;
}

json view_json(const View& view) {
    json out;
    out["mode"] = mode_name(view.mode);
    out["phase"] = to_string(view.phase);
    out["can_act"] = view.can_act();
    out["steady"] = view.steady;
    out["aim"] = view.aim ? point_json(*view.aim) : json(nullptr);
    out["target"] = view.target_kind ? json{{"kind", p::to_string(*view.target_kind)}, {"title", view.target_title}}
                                     : json(nullptr);
    out["hint"] = view.hint;
    out["another_screen"] = view.another_screen;
    out["put"] = to_string(view.put);
    out["put_deadline"] = view.put_deadline;
    if (view.outcome) {
        const Outcome& o = *view.outcome;
        json outcome{{"ok", o.ok}, {"code", o.code}, {"message", o.message}};
        outcome["content"] = o.content ? message_json(*o.content) : json(nullptr);
        outcome["put"] = o.put ? message_json(*o.put) : json(nullptr);
        out["outcome"] = std::move(outcome);
    } else {
        out["outcome"] = nullptr;
    }
    return out;
}

}  // namespace umf::requester_core
