// What the parts of one detect call share (search_plan.hpp): the frame at
// half size, at double size around the aim and smoothed, and each image's
// edgel scans step by step. A photo's search runs its parts one after the
// other, and twice over in its second pass; without this, each part would
// make again the images and scans of the parts before it (a fifth more time
// on a frame without the field at 640 x 480).
#pragma once

#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>
#include <vector>

#include "shared/detect/edgels.hpp"
#include "shared/detect/image.hpp"

namespace umf {

class SearchCache {
public:
    enum class Derived { half_size, double_size, smoothed };

    // The image made from `source` as `kind` says, when made before in this call.
    const GreyView* find(const GreyView& source, Derived kind) const {
        for (const auto& e : images_)
            if (e->kind == kind && same(e->source, source)) return &e->view;
        return nullptr;
    }
    // Keeps `pixels` (which `view` shows) for the rest of the call.
    const GreyView& add(const GreyView& source, Derived kind, std::vector<std::uint8_t> pixels, const GreyView& view) {
        auto e = std::make_unique<Image>(Image{source, kind, std::move(pixels), view});
        e->view.data = e->pixels.data();  // the same buffer, moved
        images_.push_back(std::move(e));
        return images_.back()->view;
    }

    // The scans of `image` made so far in this call, each step's whole scan
    // (the first, then each rescan added to it), in the order they were made;
    // a deque, so that a step stays where it is while later ones are added.
    std::deque<EdgelScan>& scans(const GreyView& image) { return scans_of(image).steps; }
    // The edgel sets (search_plan.hpp's kAllEdgels, ...) of `image`'s scan
    // at `step` searched so far in this pass over the call's plans: a later
    // part that names the same scan again (at 1280 x 720 part 0, the half
    // size's first scan, after a first scan that searched the whole frame
    // at half size) counts their steps without searching them again.
    unsigned& searched_sets(const GreyView& image, std::size_t step) {
        std::vector<unsigned>& sets = scans_of(image).searched_sets;
        if (sets.size() <= step) sets.resize(step + 1, 0u);
        return sets[step];
    }
    // Whether the part of `image` around the aim (SearchPlan::near_aim_first)
    // was searched in this pass. The second pass takes up each search's
    // labellings by its number in the pass, so it must run the searches the
    // first one ran in the same order: whether the own size's scans were made
    // yet does not say that, as the first pass's later parts made them.
    bool& near_aim_searched(const GreyView& image) { return scans_of(image).near_aim_searched; }
    // A new pass over the plans searches every scan again.
    void start_pass() {
        for (auto& s : scans_) {
            s->searched_sets.clear();
            s->near_aim_searched = false;
        }
    }

private:
    static bool same(const GreyView& a, const GreyView& b) {
        return a.data == b.data && a.width == b.width && a.height == b.height && a.stride == b.stride;
    }
    struct Image {
        GreyView source;
        Derived kind;
        std::vector<std::uint8_t> pixels;
        GreyView view;
    };
    struct Scans {
        GreyView image;
        std::deque<EdgelScan> steps;
        std::vector<unsigned> searched_sets;
        bool near_aim_searched = false;
    };
    Scans& scans_of(const GreyView& image) {
        for (auto& s : scans_)
            if (same(s->image, image)) return *s;
        scans_.push_back(std::make_unique<Scans>(Scans{image, {}, {}, false}));
        return *scans_.back();
    }

    std::vector<std::unique_ptr<Image>> images_;
    std::vector<std::unique_ptr<Scans>> scans_;
};

}  // namespace umf
