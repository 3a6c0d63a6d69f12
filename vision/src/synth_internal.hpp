// Internal pieces shared by the synthetic scene (synth.cpp) and the synthetic
// sequences (sequence.cpp): a portable PRNG, procedural textures, raised
// objects and the stereo rendering of a set of objects over a background.
// Integer arithmetic only, so the output is the same on every platform.
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <vector>

#include "imap/vision/splitmix64.hpp"
#include "imap/vision/synth.hpp"

namespace imap::vision::detail {

// The scenes' generator: splitmix64 with the draws the scenes use.
class Rng : public SplitMix64 {
  public:
    using SplitMix64::SplitMix64;
    // Uniform integer in lo..hi (inclusive); lo <= hi.
    int range(int lo, int hi) {
        const uint64_t n = static_cast<uint64_t>(static_cast<int64_t>(hi) - lo + 1);
        return lo + static_cast<int>(((next() >> 32) * n) >> 32);
    }
};

inline int clamp255(int v) {
    return v < 0 ? 0 : (v > 255 ? 255 : v);
}

// Texture of one surface (w x h, surface coordinates): several octaves of
// value noise plus small sharp blobs, mapped to lo..lo+span.
cv::Mat make_texture(Rng& rng, int w, int h, int lo, int span);

// A fronto-parallel raised object: a box or the ellipse inscribed in it.
struct Object {
    int x0, y0, w, h;  // bounding box in the LEFT view
    int d;             // disparity
    bool disc;         // ellipse inscribed in the box, else the box itself
    cv::Mat tex;       // w x h texture in box coordinates
    bool contains(int x, int y) const {
        if (x < x0 || y < y0 || x >= x0 + w || y >= y0 + h) return false;
        if (!disc) return true;
        // (2x - (2x0 + w - 1))^2 / w^2 + (2y - (2y0 + h - 1))^2 / h^2 <= 1
        const int64_t ex = 2 * (x - x0) - (w - 1), ey = 2 * (y - y0) - (h - 1);
        const int64_t W2 = static_cast<int64_t>(w) * w, H2 = static_cast<int64_t>(h) * h;
        return ex * ex * H2 + ey * ey * W2 <= W2 * H2;
    }
    uint8_t colour(int x, int y) const { return tex.at<uint8_t>(y - y0, x - x0); }
};

// Renders both views and the left-view ground truth of `objs` (sorted by
// increasing disparity: later objects are nearer and drawn on top) over the
// zero-disparity background `bg` (CV_8UC1, the image size). Convention of
// SPEC A.1: left pixel x + d shows what right pixel x shows. Each view gets
// independent noise in -kSynthNoise..kSynthNoise drawn from `noise`, in the
// order left pixel, right pixel, row by row. Returns the largest gt value.
int render_views(const cv::Mat& bg, const std::vector<Object>& objs, Rng& noise, cv::Mat* left,
                 cv::Mat* right, cv::Mat* gt);

}  // namespace imap::vision::detail
