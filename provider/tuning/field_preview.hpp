// The tuning window's preview: the default field mixed, pulsing, into a
// scaled-down sample of the screen, so a change to a preset is seen before
// it is saved. It draws the pixels the overlay would (overlay::mix_field at
// overlay::opacity_at), shrunk to the preview with the module size scaled
// alike, so the field covers the same share of it as of the screen.
#pragma once

#include <QElapsedTimer>
#include <QImage>
#include <QLabel>
#include <optional>

#include "shared/field/field.hpp"
#include "shared/overlay/preset.hpp"

class QTimer;

namespace umf::provider {

class FieldPreview : public QLabel {
public:
    // `screen`: the screen as shown without the field, at full size.
    FieldPreview(const QImage& screen, QSize size, QWidget* parent = nullptr);

    void set_preset(const overlay::Preset& preset);
    void set_screen(const QImage& screen);
    // The frame t_s seconds into the pulse. A focus region is drawn around
    // the preview's centre, standing in for the last aim point; activation is
    // not shown, the preview being what a requester aiming would see.
    QImage frame(double t_s) const;

private:
    void tick();
    void blur_sample();

    QSize size_;
    double screen_width_ = 1920.0;  // what the preview's width stands for
    QImage sample_;                  // the screen scaled to size_
    QImage blurred_;                 // sample_ blurred under the field at the preset's blur
    std::optional<Field> field_;
    overlay::Preset preset_;
    QTimer* timer_;
    QElapsedTimer clock_;
};

// A desktop-like picture for when no screen can be grabbed (a headless
// session, say): windows, a title bar and lines of text, so the preview and
// a palette taken from it still show something.
QImage synthetic_screen(QSize size);

// The primary screen as shown; synthetic_screen(1920 x 1080) when there is
// none or it grabs as a single colour (as offscreen platforms do).
QImage grab_screen_or_synthetic();

}  // namespace umf::provider
