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
    std::deque<EdgelScan>& scans(const GreyView& image) {
        for (auto& s : scans_)
            if (same(s->image, image)) return s->steps;
        scans_.push_back(std::make_unique<Scans>(Scans{image, {}}));
        return scans_.back()->steps;
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
    };
    std::vector<std::unique_ptr<Image>> images_;
    std::vector<std::unique_ptr<Scans>> scans_;
};

}  // namespace umf
