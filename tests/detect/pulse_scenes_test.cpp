// The pulse's demodulation on simulated photos of a camera at rest or
// hand-held before busy screens whose field pulses at a few percent (pulse_demodulator.hpp,
// pulse_course.hpp, pulse_search.hpp). The camera simulator makes these
// slow under the sanitizers, which run pulse_demodulator_test.cpp instead.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "shared/detect/detector.hpp"
#include "shared/detect/homography.hpp"
#include "shared/detect/pulse_course.hpp"
#include "shared/detect/pulse_demodulator.hpp"
#include "shared/detect/pulse_search.hpp"
#include "shared/detect/pulse_tracker.hpp"
#include "shared/overlay/preset.hpp"
#include "shared/overlay/pulse.hpp"
#include "shared/overlay/pulse_shape.hpp"
#include "tests/detect/photo.hpp"

using namespace umf;

namespace {

using test::grey_view;

struct PulseCase {
    const char* name;
    sim::ScreenKind screen;
};

class PulseDemodulatorOnBusyScreens : public ::testing::TestWithParam<PulseCase> {};

// A phone held still before a busy screen whose field pulses between
// opacity 0.01 and 0.04 (sine, 1.5 s) at 25 frames a second: over the 19
// frames of the pulse's rise the demodulated image holds the field, and the
// detector finds it there within a twentieth of a module. (The top frame
// alone, at 0.04, is found on the document and the dark code, not on the
// web page or the photo; the demodulated image finds all four down to a
// pulse between 0.002 and 0.01.)
TEST_P(PulseDemodulatorOnBusyScreens, FindsTheFieldOfAFaintPulse) {
    const PulseCase c = GetParam();
    const Field f = test::shipped_field("b4-64x36.json");
    const Detector detector(f);
    const overlay::Preset pulse = test::sine_pulse(0.01, 0.04, 1.5);
    test::Photo p;
    p.camera.resolution = {640, 480};
    p.pose.distance_mm = 300;
    p.pose.pitch_deg = 12;
    p.pose.yaw_deg = -8;
    p.pose.roll_deg = 15;
    p.pose.aim_screen_px = {950, 520};
    const std::vector<cv::Mat> shots = test::film_pulse(f, p, c.screen, pulse, 19);
    PulseDemodulator demodulator;
    std::vector<double> opacities;
    for (std::size_t i = 0; i < shots.size(); ++i) {
        opacities.push_back(overlay::opacity_at(pulse, static_cast<double>(i) / 25.0));
        demodulator.add({shots[i].data, shots[i].cols, shots[i].rows, static_cast<std::ptrdiff_t>(shots[i].step)},
                        opacities.back());
    }
    const GreyView field = demodulator.field_image();
    ASSERT_NE(field.data, nullptr);
    const Detection d = detector.detect(field);
    ASSERT_TRUE(d.found) << c.name << ": " << d.failure;
    const cv::Point2d truth = sim::image_to_field(p.shot, p.placement, {320, 240});
    EXPECT_LT(std::hypot(d.aim_field.x() - truth.x, d.aim_field.y() - truth.y), 0.05)
        << c.name << ": found (" << d.aim_field.x() << ", " << d.aim_field.y() << "), truth (" << truth.x << ", "
        << truth.y << ")";

    // The pulse's course from the frames alone: the opacities up to a
    // factor and a sign; of the two signs, the field is found in one.
    std::vector<GreyView> views;
    for (const cv::Mat& m : shots) views.push_back({m.data, m.cols, m.rows, static_cast<std::ptrdiff_t>(m.step)});
    const PulseCourse course = find_pulse_course(views);
    ASSERT_EQ(course.level.size(), views.size());
    EXPECT_GT(course.share, 0.3) << c.name;
    double along = 0, mean = 0;
    for (double a : opacities) mean += a / static_cast<double>(opacities.size());
    for (std::size_t i = 0; i < views.size(); ++i) along += course.level[i] * (opacities[i] - mean);
    int found = 0;
    for (const double sign : {1.0, -1.0}) {
        PulseDemodulator blind;
        for (std::size_t i = 0; i < views.size(); ++i) blind.add(views[i], 0.5 + 0.5 * sign * course.level[i]);
        const Detection e = detector.detect(blind.field_image(PulseDemodulator::SlopeScale::spread));
        if (!e.found) continue;
        ++found;
        EXPECT_GT(sign * along, 0) << c.name << ": found with the course inverted";
        EXPECT_LT(std::hypot(e.aim_field.x() - truth.x, e.aim_field.y() - truth.y), 0.05) << c.name;
    }
    EXPECT_EQ(found, 1) << c.name;
}

TEST(PulseCourse, NoiseAloneExplainsLittle) {
    // A screen at rest under a steady field: the frames differ by their noise.
    const Field f = test::shipped_field("b4-64x36.json");
    std::vector<cv::Mat> shots;
    std::vector<GreyView> views;
    const test::Photo p = test::photograph_field(f, 0.3, 10, 5, 20, 300, sim::ScreenKind::web_page);
    for (int frame = 0; frame < 12; ++frame) {
        cv::Mat noisy = p.shot.grey.clone();
        cv::Mat noise(noisy.size(), CV_16S);
        cv::randn(noise, 0, 2);
        noisy.convertTo(noisy, CV_16S);
        noisy += noise;
        noisy.convertTo(noisy, CV_8U);
        shots.push_back(noisy);
    }
    for (const cv::Mat& m : shots) views.push_back({m.data, m.cols, m.rows, static_cast<std::ptrdiff_t>(m.step)});
    const PulseCourse course = find_pulse_course(views);
    ASSERT_EQ(course.level.size(), 12u);
    EXPECT_LT(course.share, 0.2);
    EXPECT_TRUE(find_pulse_course(std::span<const GreyView>(views.data(), 2)).level.empty()) << "two frames";
}

INSTANTIATE_TEST_SUITE_P(Screens, PulseDemodulatorOnBusyScreens,
                         ::testing::Values(PulseCase{"document", sim::ScreenKind::document},
                                           PulseCase{"web_page", sim::ScreenKind::web_page},
                                           PulseCase{"photo", sim::ScreenKind::photo},
                                           PulseCase{"code_dark", sim::ScreenKind::code_dark}),
                         [](const ::testing::TestParamInfo<PulseCase>& info) { return std::string(info.param.name); });

// A phone at rest before a web page whose field pulses between 0.01 and
// 0.04 (sine, 1.5 s) at 25 frames a second, from `start_s` into the pulse;
// opacity `steady` >= 0 instead holds the field still.
struct Clip {
    std::vector<cv::Mat> frames;
    cv::Point2d truth;  // the field point under the image centre
};

Clip film(const Field& f, int count, double start_s, double steady = -1) {
    test::Photo p = test::resting_phone();
    const overlay::Preset pulse = steady >= 0 ? test::sine_pulse(steady, steady, 1.5) : test::sine_pulse(0.01, 0.04, 1.5);
    Clip clip;
    clip.frames = test::film_pulse(f, p, sim::ScreenKind::web_page, pulse, count, start_s);
    clip.truth = sim::image_to_field(p.shot, p.placement, {320, 240});
    return clip;
}

class PulseSearchOnAWebPage : public ::testing::Test {
protected:
    static void SetUpTestSuite() {
        field_ = new Field(test::shipped_field("b4-64x36.json"));
        pulsing_ = new Clip(film(*field_, 16, 0.9));  // past the top, falling, and rising again
    }
    static void TearDownTestSuite() {
        delete pulsing_;
        delete field_;
    }
    static inline Field* field_ = nullptr;
    static inline Clip* pulsing_ = nullptr;
};

TEST_F(PulseSearchOnAWebPage, FindsTheFieldOnceEnoughFramesAreKept) {
    const Detector detector(*field_);
    PulseSearchOptions options;
    options.frames = 12;  // the last 12 of 16: the oldest are dropped
    PulseSearch search(options);
    const Eigen::Vector2d aim(320, 240);
    for (int i = 0; i < 16; ++i) {
        search.add(grey_view(pulsing_->frames[static_cast<std::size_t>(i)]));
        if (i == 5) {
            const PulseSearchResult early = search.search(detector, aim);
            EXPECT_FALSE(early.detection.found);
            EXPECT_EQ(early.detection.failure, "too few frames for the pulse");
        }
    }
    EXPECT_EQ(search.frames(), 12);
    const PulseSearchResult r = search.search(detector, aim);
    ASSERT_TRUE(r.detection.found) << r.detection.failure << ", share " << r.share;
    EXPECT_FALSE(r.fitted);
    EXPECT_GT(r.share, 0.2);
    EXPECT_LT(std::hypot(r.detection.aim_field.x() - pulsing_->truth.x, r.detection.aim_field.y() - pulsing_->truth.y),
              0.05);
}

TEST_F(PulseSearchOnAWebPage, FitsTheAnnouncedShape) {
    const Detector detector(*field_);
    PulseSearchOptions options;
    options.shape = overlay::announced_pulse_shape(overlay::Waveform::sine, 1.5);
    PulseSearch search(options);
    for (const cv::Mat& frame : pulsing_->frames) search.add(grey_view(frame));
    const PulseSearchResult r = search.search(detector, {320, 240});
    ASSERT_TRUE(r.detection.found) << r.detection.failure;
    EXPECT_TRUE(r.fitted);
    EXPECT_LT(std::hypot(r.detection.aim_field.x() - pulsing_->truth.x, r.detection.aim_field.y() - pulsing_->truth.y),
              0.05);
    // A shape the frames do not follow (a period of 0.2 s) is not taken.
    options.shape->period_s = 0.2;
    options.frame_rates = {25};
    PulseSearch wrong(options);
    for (const cv::Mat& frame : pulsing_->frames) wrong.add(grey_view(frame));
    const PulseSearchResult w = wrong.search(detector, {320, 240});
    EXPECT_FALSE(w.fitted);
    EXPECT_TRUE(w.detection.found) << "the course itself is used";
}

// The phone's auto-exposure wanders by a few percent while the field pulses
// by as much: the frames' main course over time is the exposure's unless
// each frame is levelled to one exposure first.
TEST_F(PulseSearchOnAWebPage, LevelsTheExposureBeforeDemodulating) {
    const Detector detector(*field_);
    std::vector<cv::Mat> drifting;
    for (std::size_t i = 0; i < pulsing_->frames.size(); ++i) {
        cv::Mat m;
        pulsing_->frames[i].convertTo(m, CV_8U, 1 + 0.05 * std::sin(0.9 * static_cast<double>(i) + 1));
        drifting.push_back(m);
    }
    for (const bool level : {true, false}) {
        PulseSearchOptions options;
        options.level_exposure = level;
        PulseSearch search(options);
        for (const cv::Mat& frame : drifting) search.add(grey_view(frame));
        const PulseSearchResult r = search.search(detector, {320, 240});
        if (!level) {
            EXPECT_FALSE(r.detection.found) << "the course is the exposure's";
            continue;
        }
        ASSERT_TRUE(r.detection.found) << r.detection.failure << ", share " << r.share;
        EXPECT_LT(std::hypot(r.detection.aim_field.x() - pulsing_->truth.x, r.detection.aim_field.y() - pulsing_->truth.y),
                  0.05);
    }
}

TEST_F(PulseSearchOnAWebPage, AFieldThatDoesNotPulseIsNotSearched) {
    const Detector detector(*field_);
    const Clip steady = film(*field_, 10, 0, 0.03);
    PulseSearch search;
    for (const cv::Mat& frame : steady.frames) search.add(grey_view(frame));
    const PulseSearchResult r = search.search(detector, {320, 240});
    EXPECT_FALSE(r.detection.found);
    EXPECT_EQ(r.detection.failure, "no pulse in the frames");
    EXPECT_LT(r.share, 0.2);
    // Another size starts over.
    cv::Mat small(240, 320, CV_8U, cv::Scalar(90));
    search.add(grey_view(small));
    EXPECT_EQ(search.frames(), 1);
}

// A hand-held phone turning slowly over a web page (each frame a third of a
// degree of pitch, half a degree of roll and a few pixels along the screen
// on) whose field pulses between 0.01 and 0.04, or holds at `steady`.
class HandHeldFilm {
public:
    explicit HandHeldFilm(const Field& f, double steady = -1)
        : field_(f),
          pulse_(steady >= 0 ? test::sine_pulse(steady, steady, 1.5) : test::sine_pulse(0.01, 0.04, 1.5)),
          screen_(sim::make_screen(sim::ScreenKind::web_page, {1920, 1080}, 5)) {
        p_.camera.resolution = {640, 480};
    }
    GreyView frame(int i) {
        p_.pose.distance_mm = 300 - i;
        p_.pose.pitch_deg = 10 + i * 0.3;
        p_.pose.yaw_deg = 5 - i * 0.2;
        p_.pose.roll_deg = 20 + i * 0.5;
        p_.pose.aim_screen_px = {950 + 3.0 * i, 520 - 2.0 * i};
        sim::Degradation degradation;
        degradation.noise_sigma = 2;
        degradation.seed = 300 + static_cast<std::uint64_t>(i);
        const double a = overlay::opacity_at(pulse_, i / 25.0);
        p_.shot = sim::photograph(sim::mix_field(screen_, field_, p_.placement, a), p_.geometry, p_.camera, p_.pose,
                                  degradation);
        return grey_view(p_.shot.grey);
    }
    // The field point under the last frame's centre.
    cv::Point2d truth() const { return sim::image_to_field(p_.shot, p_.placement, {320, 240}); }

private:
    const Field& field_;
    overlay::Preset pulse_;
    cv::Mat screen_;
    test::Photo p_;
};

// `d` with its place moved `modules` along the field's u axis.
Detection moved_along_u(const Detection& d, double modules) {
    Detection out = d;
    Eigen::Matrix3d along_u = Eigen::Matrix3d::Identity();
    along_u(0, 2) = modules;
    out.image_to_field = along_u * d.image_to_field;
    out.aim_field.x() += modules;
    return out;
}

// The place carried moved two modules along u, then film frame `frame`
// added and searched.
PulseSearchResult search_with_place_moved(PulseSearch& search, const Detector& detector, HandHeldFilm& film, int frame,
                                          const Eigen::Vector2d& aim) {
    const std::optional<Detection> carried = search.carried(aim);
    EXPECT_TRUE(carried.has_value()) << "nothing carried before frame " << frame;
    if (carried) search.found_elsewhere(moved_along_u(*carried, 2));
    search.add(film.frame(frame));
    return search.search(detector, aim);
}

// A place found at the frame's centre: its map takes the centre a fifth of
// a module away from where the module edges there put it.
Detection found_at_centre(const Eigen::Vector2d& aim_field) {
    Detection d;
    d.found = true;
    d.aim_image = {320, 240};
    d.aim_field = aim_field;
    d.image_to_field << 0.1, 0, aim_field.x() - 32 + 0.2, 0, 0.1, aim_field.y() - 24, 0, 0, 1;
    return d;
}

// Each frame is registered onto the one before, the frames are laid onto
// the newest, and the field is found in the newest frame's place, then
// carried to the frames after.
TEST(PulseSearch, FindsTheFieldOfAFaintPulseInAHandHeldView) {
    const Field f = test::shipped_field("b4-64x36.json");
    const Detector detector(f);
    HandHeldFilm film(f);
    PulseSearch search;
    const auto film_frame = [&](int i) { search.add(film.frame(i)); };
    for (int i = 0; i < 19; ++i) {
        film_frame(i);
        if (i > 0) {
            ASSERT_TRUE(search.motion().has_value()) << "frame " << i;
        }
    }
    EXPECT_FALSE(search.carried({320, 240}).has_value()) << "nothing found yet";
    EXPECT_EQ(search.registration_losses(), 0);
    EXPECT_EQ(search.frames(), 19);
    const PulseSearchResult r = search.search(detector, {320, 240});
    ASSERT_TRUE(r.detection.found) << r.detection.failure << ", share " << r.share;
    const cv::Point2d truth = film.truth();
    EXPECT_LT(std::hypot(r.detection.aim_field.x() - truth.x, r.detection.aim_field.y() - truth.y), 0.1)
        << "found (" << r.detection.aim_field.x() << ", " << r.detection.aim_field.y() << "), truth (" << truth.x
        << ", " << truth.y << ")";
    EXPECT_TRUE(search.due()) << "found: searched again on every frame";

    // Between searches the place found is carried through the registration
    // of each frame onto the last, as the view goes on moving.
    for (int i = 19; i < 25; ++i) {
        film_frame(i);
        const std::optional<Detection> carried = search.carried({320, 240});
        ASSERT_TRUE(carried.has_value()) << "frame " << i;
        EXPECT_TRUE(carried->from_prior);
        const cv::Point2d now = film.truth();
        EXPECT_LT(std::hypot(carried->aim_field.x() - now.x, carried->aim_field.y() - now.y), 0.15)
            << "frame " << i << ": carried to (" << carried->aim_field.x() << ", " << carried->aim_field.y()
            << "), truth (" << now.x << ", " << now.y << ")";
    }

    // A place found in the newest frame some other way (a tracker's lock)
    // is carried from there on in place of the search's.
    const std::optional<Detection> before = search.carried({320, 240});
    ASSERT_TRUE(before.has_value());
    search.found_elsewhere(moved_along_u(*before, 2));
    const std::optional<Detection> after = search.carried({320, 240});
    ASSERT_TRUE(after.has_value());
    EXPECT_NEAR(after->aim_field.x() - before->aim_field.x(), 2, 1e-9);
    EXPECT_NEAR(after->aim_field.y() - before->aim_field.y(), 0, 1e-9);

    // A view that cannot be laid onto the last (a cut to another screen)
    // starts the frames kept over.
    const test::Photo other = test::photograph_field(f, 0.03, -10, 14, -20, 320, sim::ScreenKind::document);
    search.add(grey_view(other.shot.grey));
    EXPECT_EQ(search.registration_losses(), 1);
    EXPECT_EQ(search.frames(), 1);
    EXPECT_FALSE(search.motion().has_value());
    EXPECT_FALSE(search.carried({320, 240}).has_value()) << "not carried across a cut";

    // A place found right after a start is not carried through the first
    // registration, which has no motion to be checked against; through
    // the next, it is.
    search.found_elsewhere(*before);
    search.add(grey_view(other.shot.grey));
    EXPECT_EQ(search.frames(), 2);
    EXPECT_FALSE(search.carried({320, 240}).has_value()) << "carried through an unchecked registration";
    search.found_elsewhere(*before);
    search.add(grey_view(other.shot.grey));
    EXPECT_EQ(search.frames(), 3);
    EXPECT_TRUE(search.carried({320, 240}).has_value());
}

// A place carried into the frames after a search is looked for where it
// is said to be in the next demodulated image (Detector::follow) before
// that image is searched: confirmed there, the place is the follow's
// (from_prior); one carried two modules off is not confirmed, and the
// search finds the field where it is.
TEST(PulseSearch, ConfirmsACarriedPlaceWhereItIsSaidToBe) {
    const Field f = test::shipped_field("b4-64x36.json");
    const Detector detector(f);
    const Eigen::Vector2d aim(320, 240);
    for (const bool follow : {true, false}) {
        SCOPED_TRACE(follow ? "followed" : "not followed");
        HandHeldFilm film(f);
        PulseSearchOptions options;
        options.follow_carried = follow;
        PulseSearch search(options);
        for (int i = 0; i < 19; ++i) search.add(film.frame(i));
        const PulseSearchResult first = search.search(detector, aim);
        ASSERT_TRUE(first.detection.found) << first.detection.failure;
        EXPECT_FALSE(first.detection.from_prior);
        const auto off_truth = [&](const Detection& d) {
            const cv::Point2d truth = film.truth();
            return std::hypot(d.aim_field.x() - truth.x, d.aim_field.y() - truth.y);
        };

        search.add(film.frame(19));
        const PulseSearchResult again = search.search(detector, aim);
        ASSERT_TRUE(again.detection.found) << again.detection.failure;
        EXPECT_EQ(again.detection.from_prior, follow);
        EXPECT_LT(off_truth(again.detection), 0.1);

        const PulseSearchResult searched = search_with_place_moved(search, detector, film, 20, aim);
        ASSERT_TRUE(searched.detection.found) << searched.detection.failure;
        EXPECT_FALSE(searched.detection.from_prior) << "the place two modules off confirmed";
        EXPECT_LT(off_truth(searched.detection), 0.1);
    }
}

// Once a place is found, it is followed in the frames demodulated at half
// size first (PulseSearchOptions::demodulation_level), and given in the
// frame's own pixels, as close to the truth as at the frames' own size; a
// place that is not confirmed there is searched for at their own size.
TEST(PulseSearch, FollowsAPlaceAtHalfSizeFirst) {
    const Field f = test::shipped_field("b4-64x36.json");
    const Detector detector(f);
    const Eigen::Vector2d aim(320, 240);
    HandHeldFilm film(f);
    PulseSearchOptions options;
    options.demodulation_level = 1;
    PulseSearch search(options);
    for (int i = 0; i < 19; ++i) search.add(film.frame(i));
    const auto off_truth = [&](const Detection& d) {
        const cv::Point2d truth = film.truth();
        return std::hypot(d.aim_field.x() - truth.x, d.aim_field.y() - truth.y);
    };
    const PulseSearchResult first = search.search(detector, aim);
    ASSERT_TRUE(first.detection.found) << first.detection.failure;
    EXPECT_EQ(first.detection.size_scale, 1) << "nothing found before: searched at the frames' own size";

    for (int i = 19; i < 23; ++i) {
        search.add(film.frame(i));
        const PulseSearchResult followed = search.search(detector, aim);
        ASSERT_TRUE(followed.detection.found) << "frame " << i << ": " << followed.detection.failure;
        EXPECT_TRUE(followed.detection.from_prior) << "frame " << i;
        EXPECT_EQ(followed.detection.size_scale, 0.5) << "frame " << i;
        EXPECT_LT((followed.detection.aim_image - aim).norm(), 1e-9) << "frame " << i;
        EXPECT_LT(off_truth(followed.detection), 0.05) << "frame " << i;
        // The map too, in the frame's own pixels: it takes the aim to the place.
        const std::optional<Point2> at = apply_homography(followed.detection.image_to_field, aim);
        ASSERT_TRUE(at.has_value());
        EXPECT_LT((*at - followed.detection.aim_field).norm(), 0.1) << "frame " << i;
    }

    const PulseSearchResult searched = search_with_place_moved(search, detector, film, 23, aim);
    ASSERT_TRUE(searched.detection.found) << searched.detection.failure;
    EXPECT_FALSE(searched.detection.from_prior) << "the place two modules off confirmed";
    EXPECT_GE(searched.detection.size_scale, 1) << "searched at the frames' own size";
    EXPECT_LT(off_truth(searched.detection), 0.05);
}

// A place is carried from where the module edges around the aim put it,
// not from where the map fitted to the whole view does (on a tracker's
// lock the two can be a fifth of a module apart), and on from there.
TEST(PulseSearch, CarriesAPlaceFromWhereItsAimWasRead) {
    const Field f = test::shipped_field("b4-64x36.json");
    const Eigen::Vector2d aim(320, 240), place(30, 20);
    HandHeldFilm film(f, 0.03);
    PulseSearch search;
    for (int i = 0; i < 3; ++i) search.add(film.frame(i));
    search.found_elsewhere(found_at_centre(place));
    const std::optional<Detection> now = search.carried(aim);
    ASSERT_TRUE(now.has_value());
    EXPECT_NEAR((now->aim_field - place).norm(), 0, 1e-9) << "carried from the map, not the aim's edges";
    const auto carry = search.carry(aim);
    ASSERT_TRUE(carry.has_value());
    EXPECT_EQ(carry->frames, 0);
    EXPECT_NEAR(carry->travel, 0, 1e-9);
    // The view moves a few pixels a frame: the place goes with it.
    search.add(film.frame(3));
    const std::optional<Detection> next = search.carried(aim);
    ASSERT_TRUE(next.has_value());
    const Eigen::Vector2d moved = next->aim_field - place;
    EXPECT_GT(moved.norm(), 0.01);
    EXPECT_LT(moved.norm(), 1);
    ASSERT_TRUE(search.carry(aim).has_value());
    EXPECT_EQ(search.carry(aim)->frames, 1);
    EXPECT_NEAR(search.carry(aim)->travel, moved.norm(), 1e-9);
}

// The tracker and the pulse search together, as a requester runs them on
// each camera frame: on the pulse's faint frames the tracker alone finds
// nothing, and the field is found in the frames together once enough are kept, then
// every frame after it is locked (near the pulse's top, at 0.04, the
// tracker may lock on a frame alone), searched again or carried; a field
// seen in every frame is the tracker's own, never demodulated.
TEST(PulseTracker, LocksOnAFaintPulseThatNoFrameShows) {
    const Field f = test::shipped_field("b4-64x36.json");
    const Detector detector(f);
    HandHeldFilm film(f);
    PulseTracker tracker(detector);
    int first_lock = -1, demodulated = 0;
    for (int i = 0; i < 32; ++i) {
        const PulseTrackResult r = tracker.update(film.frame(i));
        EXPECT_EQ(r.pulse_frames, std::min(i + 1, 24)) << "frame " << i;
        EXPECT_GT(r.ms, 0);
        if (r.track.state != TrackState::locked) {
            EXPECT_LT(first_lock, 0) << "frame " << i << ": lost again after the first lock";
            continue;
        }
        if (first_lock < 0) {
            first_lock = i;
            EXPECT_TRUE(r.demodulated) << "frame " << i << ": the first lock is the frames' together";
        }
        demodulated += r.demodulated ? 1 : 0;
        const cv::Point2d truth = film.truth();
        EXPECT_LT(std::hypot(r.track.aim_field.x() - truth.x, r.track.aim_field.y() - truth.y), 0.15)
            << "frame " << i << ": (" << r.track.aim_field.x() << ", " << r.track.aim_field.y() << "), truth ("
            << truth.x << ", " << truth.y << ")";
    }
    EXPECT_GE(first_lock, 7) << "found before enough frames were kept";
    EXPECT_LE(first_lock, 20) << "found late or never";
    EXPECT_GE(demodulated, 8) << "near the pulse's top the tracker alone may lock on a frame, not at its foot";

    HandHeldFilm visible(f, 0.3);
    PulseTracker plain(detector);
    for (int i = 0; i < 6; ++i) {
        const PulseTrackResult r = plain.update(visible.frame(i));
        EXPECT_EQ(r.track.state, TrackState::locked) << "frame " << i;
        EXPECT_FALSE(r.demodulated) << "frame " << i;
    }
}

}  // namespace
