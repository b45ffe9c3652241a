// Resolver 4 for a headless provider: a PNG of the screen image around the
// point (the desktop has its X11 snapshot instead). Never in public mode.
#pragma once

#include <QImage>

#include "provider/content/resolver.hpp"

namespace umf::provider {

class ImageSnapshotResolver : public Resolver {
public:
    // `screen_image`: what the screen shows without the field. A snapshot
    // covers `fraction` of the screen's width and height around the point,
    // clipped to the screen.
    ImageSnapshotResolver(QImage screen_image, int screen = 0, double fraction = 1.0 / 3.0);
    const char* name() const override { return "snapshot"; }
    std::optional<Resolved> resolve(const ScreenPoint& point, Purpose purpose) const override;

private:
    QImage image_;
    int screen_;
    double fraction_;
};

}  // namespace umf::provider
