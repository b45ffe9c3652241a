#include "provider/content/image_snapshot.hpp"

#include <QBuffer>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace umf::provider {

ImageSnapshotResolver::ImageSnapshotResolver(QImage screen_image, int screen, double fraction)
    : image_(std::move(screen_image)), screen_(screen), fraction_(std::clamp(fraction, 0.05, 1.0)) {
    // QImage shares its data copy-on-write and is not safe to detach from
    // several threads: keep a private deep copy that is only ever read.
    image_ = image_.copy();
}

std::optional<Resolved> ImageSnapshotResolver::resolve(const ScreenPoint& point, Purpose purpose) const {
    if (point.screen != screen_ || image_.isNull()) return std::nullopt;
    if (point.x < 0 || point.y < 0 || point.x >= image_.width() || point.y >= image_.height()) return std::nullopt;
    Resolved r;
    r.kind = protocol::ContentKind::snapshot;
    r.title = "Snapshot of the screen";
    r.name = "screen-snapshot.png";
    r.mime = "image/png";
    if (purpose == Purpose::preview) return r;

    const int w = std::max(1, static_cast<int>(std::lround(image_.width() * fraction_)));
    const int h = std::max(1, static_cast<int>(std::lround(image_.height() * fraction_)));
    const int x = std::clamp(static_cast<int>(point.x) - w / 2, 0, image_.width() - w);
    const int y = std::clamp(static_cast<int>(point.y) - h / 2, 0, image_.height() - h);
    const QImage part = image_.copy(x, y, w, h);
    QByteArray png;
    QBuffer buffer(&png);
    buffer.open(QIODevice::WriteOnly);
    if (!part.save(&buffer, "PNG")) throw std::runtime_error("cannot encode the snapshot");
    r.bytes = std::make_shared<const std::string>(png.constData(), static_cast<std::size_t>(png.size()));
    return r;
}

}  // namespace umf::provider
