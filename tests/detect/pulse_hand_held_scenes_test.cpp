// The pulse search and the pulse tracker on simulated frames of a hand-held
// phone turning slowly over a web page whose field pulses at a few percent
// (pulse_search.hpp, pulse_tracker.hpp): frames registered onto each other,
// a place found in the frames together, carried, confirmed and followed.
// The camera simulator makes these slow under the sanitizers, which run
// pulse_demodulator_test.cpp instead.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "shared/detect/detector.hpp"
#include "shared/detect/homography.hpp"
#include "shared/detect/pulse_search.hpp"
#include "shared/detect/pulse_tracker.hpp"
#include "shared/overlay/preset.hpp"
#include "shared/overlay/pulse.hpp"
#include "tests/detect/photo.hpp"

using namespace umf;

namespace {

using test::grey_view;

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
