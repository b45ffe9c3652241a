#include "provider/tuning/slider_spin.hpp"

#include <QDoubleSpinBox>
#include <QHBoxLayout>
#include <QSlider>
#include <algorithm>
#include <cmath>

namespace umf::provider {

SliderSpin::SliderSpin(double lo, double hi, double steps_per_unit, int decimals, const QString& suffix,
                       QWidget* parent)
    : QWidget(parent),
      slider_(new QSlider(Qt::Horizontal, this)),
      spin_(new QDoubleSpinBox(this)),
      steps_per_unit_(steps_per_unit) {
    slider_->setRange(static_cast<int>(std::lround(lo * steps_per_unit)),
                      static_cast<int>(std::lround(hi * steps_per_unit)));
    spin_->setRange(lo, hi);
    spin_->setDecimals(decimals);
    spin_->setSingleStep(1.0 / steps_per_unit);
    spin_->setSuffix(suffix);
    // Typing "0.3" should not apply "0" on the way there.
    spin_->setKeyboardTracking(false);
    auto* row = new QHBoxLayout(this);
    row->setContentsMargins(0, 0, 0, 0);
    row->addWidget(slider_, 1);
    row->addWidget(spin_);
    value_ = lo;
    show_value();
    QObject::connect(slider_, &QSlider::valueChanged, this, [this](int pos) {
        if (!showing_) edited(pos / steps_per_unit_);
    });
    QObject::connect(spin_, &QDoubleSpinBox::valueChanged, this, [this](double v) {
        if (!showing_) edited(v);
    });
}

void SliderSpin::set_value(double v) {
    value_ = std::clamp(v, spin_->minimum(), spin_->maximum());
    show_value();
}

void SliderSpin::show_value() {
    showing_ = true;
    slider_->setValue(static_cast<int>(std::lround(value_ * steps_per_unit_)));
    spin_->setValue(value_);
    showing_ = false;
}

void SliderSpin::edited(double v) {
    set_value(v);
    if (on_edit_) on_edit_(value_);
}

}  // namespace umf::provider
