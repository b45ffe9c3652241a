#include "provider/tuning/tuning_window.hpp"

#include <QColorDialog>
#include <QComboBox>
#include <QDoubleSpinBox>
#include <QFileDialog>
#include <QFormLayout>
#include <QGroupBox>
#include <QHBoxLayout>
#include <QInputDialog>
#include <QLabel>
#include <QListWidget>
#include <QMessageBox>
#include <QPainter>
#include <QPushButton>
#include <QVBoxLayout>
#include <algorithm>

#include "provider/tuning/field_preview.hpp"
#include "provider/tuning/palette_from_image.hpp"
#include "provider/tuning/slider_spin.hpp"

namespace umf::provider {

namespace {

using overlay::Preset;

QString q(const std::string& s) { return QString::fromStdString(s); }

QIcon swatch(const QColor& colour) {
    QPixmap pm(24, 24);
    pm.fill(colour);
    QPainter p(&pm);
    // An outline so a swatch the colour of the window still shows.
    p.setPen(QColor(0x80, 0x80, 0x80));
    p.drawRect(0, 0, 23, 23);
    return QIcon(pm);
}

template <class Enum>
void select_data(QComboBox* box, Enum value) {
    box->setCurrentIndex(box->findData(static_cast<int>(value)));
}

// Tests find the controls by these names.
template <class Widget>
Widget* named(Widget* w, const char* name) {
    w->setObjectName(name);
    return w;
}

}  // namespace

TuningWindow::TuningWindow(PresetStore& store, const std::string& initial_preset, PresetChanged preset_changed,
                           const QImage& screen, QWidget* parent)
    : QWidget(parent),
      store_(store),
      preset_changed_(std::move(preset_changed)),
      screen_(screen.isNull() ? grab_screen_or_synthetic() : screen) {
    setWindowTitle("umf: overlay tuning");
    build();
    const std::string first = store_.contains(initial_preset) ? initial_preset : store_.list().front().name;
    fill_chooser(first);
    choose(first);
    if (first != initial_preset) say("There is no preset \"" + q(initial_preset) + "\"; showing " + q(first), true);
}

void TuningWindow::build() {
    preview_ = named(new FieldPreview(screen_, QSize(384, 216)), "preview");
    auto* right = new QVBoxLayout;
    right->addWidget(preview_);
    right->addWidget(build_palette());
    right->addStretch(1);
    auto* columns = new QHBoxLayout;
    columns->addLayout(build_form(), 1);
    columns->addLayout(right);

    message_ = named(new QLabel, "message");
    message_->setWordWrap(true);
    auto* outer = new QVBoxLayout(this);
    outer->addLayout(columns);
    outer->addWidget(message_);
    outer->addLayout(build_preset_buttons());
}

QFormLayout* TuningWindow::build_form() {
    chooser_ = named(new QComboBox, "chooser");
    opacity_min_ = named(new SliderSpin(0.0, 1.0, 100, 2, ""), "opacity_min");
    opacity_max_ = named(new SliderSpin(0.0, 1.0, 100, 2, ""), "opacity_max");
    period_ = named(new SliderSpin(0.0, overlay::kMaxPeriodS, 10, 1, " s"), "period");
    period_->spin()->setSpecialValueText("static");
    module_ = named(new SliderSpin(overlay::kMinModulePx, overlay::kMaxModulePx, 1, 0, " px"), "module_px");
    blur_ = named(new SliderSpin(0.0, 1.0, 100, 2, ""), "blur");
    focus_radius_ = named(new SliderSpin(1.0, 100.0, 1, 0, " modules"), "focus_radius");
    // The slider covers the useful radii; the spin box takes up to the limit.
    focus_radius_->spin()->setMaximum(overlay::kMaxFocusRadiusModules);
    fade_ = named(new SliderSpin(0.0, 30.0, 10, 1, " s"), "fade");
    fade_->spin()->setMaximum(overlay::kMaxFadeS);
    waveform_ = named(new QComboBox, "waveform");
    waveform_->addItem("sine", static_cast<int>(overlay::Waveform::sine));
    waveform_->addItem("triangle", static_cast<int>(overlay::Waveform::triangle));
    region_ = named(new QComboBox, "region");
    region_->addItem("full screen", static_cast<int>(overlay::Region::full));
    region_->addItem("around the aim point", static_cast<int>(overlay::Region::focus));
    activation_ = named(new QComboBox, "activation");
    activation_->addItem("always", static_cast<int>(overlay::Activation::always));
    activation_->addItem("on demand", static_cast<int>(overlay::Activation::on_demand));

    auto* form = new QFormLayout;
    form->addRow("Preset", chooser_);
    form->addRow("Opacity min", opacity_min_);
    form->addRow("Opacity max", opacity_max_);
    form->addRow("Period", period_);
    form->addRow("Waveform", waveform_);
    form->addRow("Module size", module_);
    form->addRow("Background blur", blur_);
    form->addRow("Region", region_);
    form->addRow("Focus radius", focus_radius_);
    form->addRow("Activation", activation_);
    form->addRow("Fade-out", fade_);
    connect_form();
    return form;
}

void TuningWindow::connect_form() {
    QObject::connect(chooser_, &QComboBox::currentIndexChanged, this, [this](int index) {
        if (!loading_ && index >= 0) choose(chooser_->itemData(index).toString().toStdString());
    });
    opacity_min_->on_edit([this](double v) {
        preset_.opacity_min = v;
        // Raising the floor past the peak lifts the peak: min > max is never shown.
        if (v > preset_.opacity_max) preset_.opacity_max = v, opacity_max_->set_value(v);
        edited();
    });
    opacity_max_->on_edit([this](double v) {
        preset_.opacity_max = v;
        if (v < preset_.opacity_min) preset_.opacity_min = v, opacity_min_->set_value(v);
        edited();
    });
    period_->on_edit([this](double v) {
        // Between static and the fastest safe pulse there is nothing valid:
        // step across the gap in the direction the user moved.
        if (v > 0.0 && v < overlay::kMinPeriodS) {
            v = preset_.period_s == 0.0 ? overlay::kMinPeriodS : 0.0;
            period_->set_value(v);
        }
        preset_.period_s = v;
        edited();
    });
    module_->on_edit([this](double v) { preset_.module_px = v, edited(); });
    blur_->on_edit([this](double v) { preset_.blur = v, edited(); });
    focus_radius_->on_edit([this](double v) { preset_.focus_radius_modules = v, edited(); });
    fade_->on_edit([this](double v) { preset_.fade_s = v, edited(); });
    QObject::connect(waveform_, &QComboBox::currentIndexChanged, this, [this](int) {
        if (loading_) return;
        preset_.waveform = static_cast<overlay::Waveform>(waveform_->currentData().toInt());
        edited();
    });
    QObject::connect(region_, &QComboBox::currentIndexChanged, this, [this](int) {
        if (loading_) return;
        preset_.region = static_cast<overlay::Region>(region_->currentData().toInt());
        edited();
    });
    QObject::connect(activation_, &QComboBox::currentIndexChanged, this, [this](int) {
        if (loading_) return;
        preset_.activation = static_cast<overlay::Activation>(activation_->currentData().toInt());
        edited();
    });
}

QGroupBox* TuningWindow::build_palette() {
    palette_ = named(new QListWidget, "palette");
    palette_->setViewMode(QListView::IconMode);
    palette_->setFlow(QListView::LeftToRight);
    palette_->setWrapping(true);
    palette_->setMaximumHeight(72);
    auto* pick = named(new QPushButton("Pick…"), "pick");
    auto* add = named(new QPushButton("Add…"), "add_colour");
    auto* drop = named(new QPushButton("Remove"), "remove_colour");
    auto* own = named(new QPushButton("Field's own"), "field_colours");
    auto* from_screen = named(new QPushButton("From screen"), "from_screen");
    auto* from_image = named(new QPushButton("From image…"), "from_image");
    auto* palette_buttons = new QHBoxLayout;
    for (auto* b : {pick, add, drop, own, from_screen, from_image}) palette_buttons->addWidget(b);
    auto* palette_box = new QGroupBox("Palette");
    auto* palette_layout = new QVBoxLayout(palette_box);
    palette_layout->addWidget(palette_);
    palette_layout->addLayout(palette_buttons);

    auto pick_colour = [this](int row) {
        const QColor initial = row >= 0 && row < static_cast<int>(preset_.palette.size())
                                   ? QColor(q(preset_.palette[static_cast<std::size_t>(row)]))
                                   : QColor(Qt::gray);
        const QColor c = QColorDialog::getColor(initial, this, "Field colour");
        if (!c.isValid()) return;
        const std::string hex = c.name(QColor::HexRgb).toStdString();
        if (row >= 0 && row < static_cast<int>(preset_.palette.size()))
            preset_.palette[static_cast<std::size_t>(row)] = hex;
        else
            preset_.palette.push_back(hex);
        show_palette();
        edited();
    };
    QObject::connect(pick, &QPushButton::clicked, this, [this, pick_colour] { pick_colour(palette_->currentRow()); });
    QObject::connect(palette_, &QListWidget::itemDoubleClicked, this,
                     [this, pick_colour](QListWidgetItem* item) { pick_colour(palette_->row(item)); });
    QObject::connect(add, &QPushButton::clicked, this, [pick_colour] { pick_colour(-1); });
    QObject::connect(drop, &QPushButton::clicked, this, [this] {
        const int row = palette_->currentRow();
        if (row < 0 || row >= static_cast<int>(preset_.palette.size())) return;
        preset_.palette.erase(preset_.palette.begin() + row);
        show_palette();
        edited();
    });
    QObject::connect(own, &QPushButton::clicked, this, [this] {
        preset_.palette.clear();
        show_palette();
        edited();
    });
    QObject::connect(from_screen, &QPushButton::clicked, this, [this] { palette_from(screen_); });
    QObject::connect(from_image, &QPushButton::clicked, this, [this] {
        const QString path =
            QFileDialog::getOpenFileName(this, "Palette from image", {}, "Images (*.png *.jpg *.jpeg *.bmp *.webp)");
        if (path.isEmpty()) return;
        QImage image(path);
        if (image.isNull()) return say("Cannot read " + path + " as an image", true);
        palette_from(image);
    });
    return palette_box;
}

QHBoxLayout* TuningWindow::build_preset_buttons() {
    save_ = named(new QPushButton("Save"), "save");
    save_as_ = named(new QPushButton("Save as…"), "save_as");
    rename_ = named(new QPushButton("Rename…"), "rename");
    delete_ = named(new QPushButton("Delete"), "delete");
    reset_ = named(new QPushButton("Reset to built-in"), "reset");
    auto* buttons = new QHBoxLayout;
    for (auto* b : {save_, save_as_, rename_, delete_, reset_}) buttons->addWidget(b);
    buttons->addStretch(1);

    QObject::connect(save_, &QPushButton::clicked, this, [this] { save(); });
    QObject::connect(save_as_, &QPushButton::clicked, this, [this] {
        bool ok = false;
        const QString name = QInputDialog::getText(this, "Save preset as", "Name:", QLineEdit::Normal,
                                                   q(preset_.name) + " (mine)", &ok);
        if (ok) save_as(name.toStdString());
    });
    QObject::connect(rename_, &QPushButton::clicked, this, [this] {
        bool ok = false;
        const QString name =
            QInputDialog::getText(this, "Rename preset", "New name:", QLineEdit::Normal, q(preset_.name), &ok);
        if (ok) rename_to(name.toStdString());
    });
    QObject::connect(delete_, &QPushButton::clicked, this, [this] {
        if (QMessageBox::question(this, "Delete preset", "Delete the preset \"" + q(preset_.name) + "\"?") ==
            QMessageBox::Yes)
            remove();
    });
    QObject::connect(reset_, &QPushButton::clicked, this, [this] { reset(); });
    return buttons;
}

void TuningWindow::fill_chooser(const std::string& selected) {
    loading_ = true;
    chooser_->clear();
    for (const auto& p : store_.list()) {
        QString label = q(p.name);
        if (store_.is_overridden(p.name))
            label += " (built-in, changed)";
        else if (store_.is_built_in(p.name))
            label += " (built-in)";
        chooser_->addItem(label, q(p.name));
    }
    chooser_->setCurrentIndex(chooser_->findData(q(selected)));
    loading_ = false;
}

void TuningWindow::choose(const std::string& name) {
    try {
        preset_ = store_.get(name);
    } catch (const PresetStoreError& e) {
        return say(q(e.what()), true);
    }
    loading_ = true;
    chooser_->setCurrentIndex(chooser_->findData(q(name)));
    loading_ = false;
    show_preset();
    say({}, false);
    edited();
}

void TuningWindow::show_preset() {
    loading_ = true;
    opacity_min_->set_value(preset_.opacity_min);
    opacity_max_->set_value(preset_.opacity_max);
    period_->set_value(preset_.period_s);
    module_->set_value(preset_.module_px);
    blur_->set_value(preset_.blur);
    focus_radius_->set_value(preset_.focus_radius_modules);
    fade_->set_value(preset_.fade_s);
    select_data(waveform_, preset_.waveform);
    select_data(region_, preset_.region);
    select_data(activation_, preset_.activation);
    show_palette();
    loading_ = false;
}

void TuningWindow::show_palette() {
    const int row = palette_->currentRow();
    palette_->clear();
    for (const auto& c : preset_.palette) palette_->addItem(new QListWidgetItem(swatch(QColor(q(c))), q(c)));
    if (preset_.palette.empty()) {
        auto* item = new QListWidgetItem("the field's own colours");
        item->setFlags(Qt::NoItemFlags);
        palette_->addItem(item);
    } else {
        palette_->setCurrentRow(std::min(row, static_cast<int>(preset_.palette.size()) - 1));
    }
}

void TuningWindow::edited() {
    const std::string problem = overlay::describe_invalid(preset_);
    focus_radius_->setEnabled(preset_.region == overlay::Region::focus);
    fade_->setEnabled(preset_.activation == overlay::Activation::on_demand);
    preview_->set_preset(preset_);
    update_buttons();
    if (!problem.empty()) return say(q(problem), true);
    // A problem shown before is gone; an action's outcome stays until the next edit.
    if (message_->property("problem").toBool()) say({}, false);
    if (preset_changed_) preset_changed_(preset_);
}

void TuningWindow::update_buttons() {
    const bool valid = overlay::describe_invalid(preset_).empty();
    const bool own = store_.is_user(preset_.name) && !store_.is_built_in(preset_.name);
    save_->setEnabled(valid);
    save_as_->setEnabled(valid);
    rename_->setEnabled(own);
    delete_->setEnabled(own);
    reset_->setEnabled(store_.is_overridden(preset_.name));
}

void TuningWindow::say(const QString& text, bool problem) {
    message_->setText(text);
    message_->setProperty("problem", problem);
    message_->setStyleSheet(problem ? "color: #b00020;" : "");
}

QString TuningWindow::message() const { return message_->text(); }

int TuningWindow::palette_size_wanted() const {
    // Keep the size the user chose; the shipped fields are binary otherwise.
    const int n = preset_.palette.empty() ? 2 : static_cast<int>(preset_.palette.size());
    return std::clamp(n, 2, 10);
}

void TuningWindow::palette_from(const QImage& image) {
    std::vector<std::string> colours = palette_from_image(image, palette_size_wanted());
    if (colours.size() < 2) return say("The image has too few colours for a palette", true);
    preset_.palette = std::move(colours);
    show_palette();
    edited();
}

bool TuningWindow::save() {
    try {
        store_.save(preset_);
    } catch (const std::exception& e) {
        say(q(e.what()), true);
        return false;
    }
    fill_chooser(preset_.name);
    update_buttons();
    say("Saved \"" + q(preset_.name) + "\" to " + q(store_.path()), false);
    return true;
}

bool TuningWindow::save_as(const std::string& name) {
    if (store_.contains(name)) {
        say("There is already a preset \"" + q(name) + "\"; choose another name, or choose it and Save", true);
        return false;
    }
    Preset copy = preset_;
    copy.name = name;
    try {
        store_.save(copy);
    } catch (const std::exception& e) {
        say(q(e.what()), true);
        return false;
    }
    preset_ = copy;
    fill_chooser(name);
    update_buttons();
    say("Saved \"" + q(name) + "\" to " + q(store_.path()), false);
    if (preset_changed_) preset_changed_(preset_);
    return true;
}

bool TuningWindow::rename_to(const std::string& name) {
    const std::string old = preset_.name;
    try {
        store_.rename(old, name);
    } catch (const std::exception& e) {
        say(q(e.what()), true);
        return false;
    }
    preset_.name = name;
    fill_chooser(name);
    update_buttons();
    say("Renamed \"" + q(old) + "\" to \"" + q(name) + "\"", false);
    if (preset_changed_) preset_changed_(preset_);
    return true;
}

bool TuningWindow::remove() {
    const std::string name = preset_.name;
    try {
        store_.remove(name);
    } catch (const std::exception& e) {
        say(q(e.what()), true);
        return false;
    }
    const std::string next = store_.list().front().name;
    fill_chooser(next);
    choose(next);
    say("Deleted \"" + q(name) + "\"", false);
    return true;
}

bool TuningWindow::reset() {
    const std::string name = preset_.name;
    try {
        store_.reset(name);
    } catch (const std::exception& e) {
        say(q(e.what()), true);
        return false;
    }
    fill_chooser(name);
    choose(name);
    say("\"" + q(name) + "\" is the built-in again", false);
    return true;
}

}  // namespace umf::provider
