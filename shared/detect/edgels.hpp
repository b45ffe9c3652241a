// Stage 1 of detection: edge points ("edgels") on sparse scanlines. Only
// every step-th row and column is read, so the detector touches a few per
// cent of the pixels; grid edges cross every scanline, text and pictures
// add outliers that later stages reject.
#pragma once

#include <vector>

#include "shared/detect/image.hpp"

namespace umf {

struct Edgel {
    float x = 0, y = 0;    // sub-pixel position on its scanline; pixel (i, j) covers [i, i+1) x [j, j+1)
    float gx = 0, gy = 0;  // Sobel gradient there, pointing from dark to bright
    bool on_row = true;    // found on a row (horizontal) scanline, else on a column
    float step = 0;        // grey levels from one side to the other (two pixels each side)
};

struct EdgelOptions {
    int step = 0;           // pixels between scanlines; 0: a 40th of the larger side, at least 4
    int offset = -1;        // first scanline; -1: half a step in
    // Smallest step in grey levels across an edge (the smoothed difference
    // over two pixels each side). Low, because the field may be faint.
    int min_contrast = 5;
    // Pixels averaged across each scanline (1, 3 or 5): in a noisy image the
    // evidence of a module's edge gathered along it, a few pixels either
    // side, at as many times the reads.
    int across = 1;
    // Deviations of the scanline's noise an edge must stand out by: 4.5
    // keep false peaks rare; fewer find a faint field's edges in noise.
    double noise_deviations = 4.5;
};

struct EdgelScan {
    std::vector<Edgel> edgels;
    long pixels_visited = 0;
    int step = 0;
    double noise_sigma = 0;  // the image's noise in grey levels (median over the scanlines' estimates)
};

EdgelScan find_edgels(const GreyView& image, const EdgelOptions& options = {});

// The pixels between scanlines find_edgels takes for an image this size.
int scanline_step(int width, int height, const EdgelOptions& options = {});

}  // namespace umf
