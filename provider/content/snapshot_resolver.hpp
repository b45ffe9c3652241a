// A PNG snapshot of the window under a point: the last resolver, for windows
// whose document is unknown (docs/ARCHITECTURE.md, "Content", resolver 4).
// It shows what is on the screen there, so it is private: never in public
// or kiosk mode.
#pragma once

#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <string_view>

#include "provider/content/resolver.hpp"
#include "provider/desktop/desktop.hpp"

namespace umf::provider {

// Larger windows (a desktop spanning many screens) are cut to this, around
// the point.
inline constexpr int kMaxSnapshotSide = 8192;

// The capture as a PNG file's bytes. Throws std::runtime_error when encoding
// fails.
std::string encode_png(const Capture& capture);

// "<title>-snapshot.png" with characters file systems or shells trip over
// replaced and the title shortened; "screen-snapshot.png" without a title.
std::string snapshot_file_name(std::string_view title);

// The part of `window` to capture: within the screen and at most
// max_side x max_side, centred on the point as far as the window allows.
WindowRect snapshot_rect(const WindowRect& window, const WindowRect& screen, double root_x, double root_y,
                         int max_side = kMaxSnapshotSide);

class SnapshotResolver final : public Resolver {
public:
    // enabled false (public and kiosk modes): never answers.
    SnapshotResolver(std::shared_ptr<const Desktop> desktop, WindowFilter filter, bool enabled);
    // Called around each capture, from a server thread: the overlay hides
    // itself (and waits until the screen shows it gone) and comes back, so a
    // snapshot never holds the field.
    void set_around_capture(std::function<void()> before, std::function<void()> after);
    const char* name() const override { return "snapshot"; }
    // An aim only names the window; a grab captures it (the frame included,
    // and whatever covers it, as the screen shows it).
    std::optional<Resolved> resolve(const ScreenPoint& point, Purpose purpose) const override;

private:
    std::shared_ptr<const Desktop> desktop_;
    WindowFilter filter_;
    bool enabled_;
    std::function<void()> before_capture_;
    std::function<void()> after_capture_;
};

}  // namespace umf::provider
