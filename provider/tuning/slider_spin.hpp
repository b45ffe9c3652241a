// A slider and a spin box showing one number: the slider to sweep while
// watching the preview, the spin box to type an exact value. Either moves the
// other; setting the value from code does not call back, so loading a preset
// into the controls does not read as an edit.
#pragma once

#include <QWidget>
#include <functional>

class QSlider;
class QDoubleSpinBox;

namespace umf::provider {

class SliderSpin : public QWidget {
public:
    // `steps_per_unit`: slider positions per unit of the value (100 for a
    // 0..1 opacity, 1 for whole pixels); `decimals` those the spin box shows.
    SliderSpin(double lo, double hi, double steps_per_unit, int decimals, const QString& suffix,
               QWidget* parent = nullptr);

    double value() const { return value_; }
    // Clamped to the range; no callback.
    void set_value(double v);
    // Called with the new value after a user edit; may call set_value to
    // correct it (a snapped value, say).
    void on_edit(std::function<void(double)> f) { on_edit_ = std::move(f); }

    QSlider* slider() const { return slider_; }
    QDoubleSpinBox* spin() const { return spin_; }

private:
    void show_value();
    void edited(double v);

    QSlider* slider_;
    QDoubleSpinBox* spin_;
    double steps_per_unit_;
    double value_ = 0.0;
    bool showing_ = false;
    std::function<void(double)> on_edit_;
};

}  // namespace umf::provider
