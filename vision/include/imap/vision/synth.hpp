// Built-in synthetic stereo scene: deterministic for a seed on every platform
// (own PRNG, integer arithmetic only), with exact ground truth.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>

namespace imap::vision {

// Amplitude of the independent additive noise of each view: pixel values
// differ from the noise-free rendering by at most this much.
inline constexpr int kSynthNoise = 2;
// Largest disparity a synthetic scene uses (also limited to width / 4).
inline constexpr int kSynthMaxDisp = 48;

struct SynthScene {
    cv::Mat left;   // CV_8UC1
    cv::Mat right;  // CV_8UC1
    cv::Mat gt;     // CV_8UC1: disparity of the LEFT view, unscaled (gt_scale 1)
    int max_disp;   // largest disparity in gt (search D = max_disp + 1 levels)
};

// Textured background at disparity 0 with several brighter, raised objects
// (rectangles and ellipses, fronto-parallel) at positive disparities up to
// min(width / 4, kSynthMaxDisp). Convention of SPEC A.1: left pixel x + d
// shows the same scene point as right pixel x, where d = gt(x + d). Objects
// lie fully inside the left view and are at least d pixels from its left
// edge, so every object pixel not hidden by a nearer object is seen by the
// right camera; background pixels hidden in the right view keep disparity 0.
// Where the width allows, an object starts at x >= 2d + 2, so the strip it
// hides in the right view does not touch the left image border.
// Requires 1 <= width, height <= 65536 (throws std::invalid_argument).
SynthScene make_synth_scene(uint64_t seed, int width, int height);

}  // namespace imap::vision
