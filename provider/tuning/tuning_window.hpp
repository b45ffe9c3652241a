// The tuning window: one preset edited live. Every edit that leaves the
// preset valid goes to the callback at once (the overlay applies it while
// the user watches); an invalid one is explained in the window and not
// passed on. Nothing is written until Save, Save as, Rename, Delete or
// Reset, which go through the PresetStore.
//
// No Q_OBJECT: edits are reported through a std::function, so the class
// needs no moc. Widgets carry object names (see the .cpp) for tests.
#pragma once

#include <QImage>
#include <QWidget>
#include <functional>
#include <string>

#include "provider/tuning/preset_store.hpp"
#include "shared/overlay/preset.hpp"

class QComboBox;
class QFormLayout;
class QGroupBox;
class QHBoxLayout;
class QLabel;
class QListWidget;
class QPushButton;

namespace umf::provider {

class FieldPreview;
class SliderSpin;

class TuningWindow : public QWidget {
public:
    using PresetChanged = std::function<void(const overlay::Preset&)>;

    // `store` must outlive the window. `screen`: the screen without the
    // field, for the preview and "From screen"; null grabs the primary
    // screen (which shows the overlay's field too, if it is up).
    TuningWindow(PresetStore& store, const std::string& initial_preset, PresetChanged preset_changed,
                 const QImage& screen = {}, QWidget* parent = nullptr);

    // The preset as edited, valid or not.
    const overlay::Preset& preset() const { return preset_; }
    // Loads a preset from the store into the controls (and reports it).
    void choose(const std::string& name);

    // What the buttons do once a name is asked for; each shows its outcome
    // in the message line and returns whether it succeeded.
    bool save();
    bool save_as(const std::string& name);
    bool rename_to(const std::string& name);
    bool remove();
    bool reset();
    // Replaces the palette with `colours` dominant ones of `image`.
    void palette_from(const QImage& image);

    // The inline message: a validation problem or an action's outcome.
    QString message() const;

private:
    void build();
    // The controls of a preset, and what editing each one does.
    QFormLayout* build_form();
    void connect_form();
    // The palette's swatches and their buttons, wired.
    QGroupBox* build_palette();
    // Save, Save as, Rename, Delete, Reset, wired.
    QHBoxLayout* build_preset_buttons();
    void fill_chooser(const std::string& selected);
    void show_preset();
    void edited();
    void show_palette();
    void update_buttons();
    void say(const QString& text, bool problem);
    int palette_size_wanted() const;

    PresetStore& store_;
    PresetChanged preset_changed_;
    QImage screen_;
    overlay::Preset preset_;
    bool loading_ = false;

    QComboBox* chooser_ = nullptr;
    SliderSpin* opacity_min_ = nullptr;
    SliderSpin* opacity_max_ = nullptr;
    SliderSpin* period_ = nullptr;
    SliderSpin* module_ = nullptr;
    SliderSpin* blur_ = nullptr;
    SliderSpin* focus_radius_ = nullptr;
    SliderSpin* fade_ = nullptr;
    QComboBox* waveform_ = nullptr;
    QComboBox* region_ = nullptr;
    QComboBox* activation_ = nullptr;
    QListWidget* palette_ = nullptr;
    FieldPreview* preview_ = nullptr;
    QLabel* message_ = nullptr;
    QPushButton* save_ = nullptr;
    QPushButton* save_as_ = nullptr;
    QPushButton* rename_ = nullptr;
    QPushButton* delete_ = nullptr;
    QPushButton* reset_ = nullptr;
};

}  // namespace umf::provider
