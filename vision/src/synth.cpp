#include "imap/vision/synth.hpp"

#include <algorithm>
#include <stdexcept>
#include <vector>

#include "synth_internal.hpp"

namespace imap::vision {

namespace detail {

namespace {

// Value noise: random values on a grid of `cell` pixels, bilinearly
// interpolated (integer), 0..255.
std::vector<int> value_noise(Rng& rng, int w, int h, int cell) {
    const int gw = w / cell + 2, gh = h / cell + 2;
    std::vector<int> grid(static_cast<size_t>(gw) * gh);
    for (int& g : grid) g = rng.range(0, 255);
    std::vector<int> out(static_cast<size_t>(w) * h);
    const int c2 = cell * cell;
    for (int y = 0; y < h; ++y) {
        const int gy = y / cell, fy = y % cell;
        for (int x = 0; x < w; ++x) {
            const int gx = x / cell, fx = x % cell;
            const int a = grid[static_cast<size_t>(gy) * gw + gx];
            const int b = grid[static_cast<size_t>(gy) * gw + gx + 1];
            const int c = grid[static_cast<size_t>(gy + 1) * gw + gx];
            const int d = grid[static_cast<size_t>(gy + 1) * gw + gx + 1];
            const int v = (cell - fx) * (cell - fy) * a + fx * (cell - fy) * b +
                          (cell - fx) * fy * c + fx * fy * d;
            out[static_cast<size_t>(y) * w + x] = (v + c2 / 2) / c2;
        }
    }
    return out;
}

}  // namespace

cv::Mat make_texture(Rng& rng, int w, int h, int lo, int span) {
    const std::vector<int> n16 = value_noise(rng, w, h, 16);
    const std::vector<int> n6 = value_noise(rng, w, h, 6);
    const std::vector<int> n3 = value_noise(rng, w, h, 3);
    std::vector<int> t(static_cast<size_t>(w) * h);
    for (size_t k = 0; k < t.size(); ++k) {
        const int px = rng.range(0, 255);
        const int mix = (2 * n16[k] + 3 * n6[k] + 2 * n3[k] + px) / 8;  // centred on ~128
        t[k] = clamp255(128 + (mix - 128) * 5 / 2);                     // stretch contrast
    }
    // Sharp-edged blobs: strong edges at random places.
    const int blobs = std::max(1, w * h / 60);
    for (int b = 0; b < blobs; ++b) {
        const int cx = rng.range(0, w - 1), cy = rng.range(0, h - 1);
        const int r = rng.range(1, 3);
        const int delta = rng.range(0, 1) != 0 ? rng.range(40, 90) : -rng.range(40, 90);
        for (int y = std::max(0, cy - r); y <= std::min(h - 1, cy + r); ++y)
            for (int x = std::max(0, cx - r); x <= std::min(w - 1, cx + r); ++x)
                if ((x - cx) * (x - cx) + (y - cy) * (y - cy) <= r * r + 1) {
                    int& v = t[static_cast<size_t>(y) * w + x];
                    v = clamp255(v + delta);
                }
    }
    cv::Mat tex(h, w, CV_8UC1);
    for (int y = 0; y < h; ++y) {
        uint8_t* row = tex.ptr<uint8_t>(y);
        for (int x = 0; x < w; ++x)
            row[x] = static_cast<uint8_t>(lo + t[static_cast<size_t>(y) * w + x] * span / 255);
    }
    return tex;
}

int render_views(const cv::Mat& bg, const std::vector<Object>& objs, Rng& noise, cv::Mat* left,
                 cv::Mat* right, cv::Mat* gt) {
    const int W = bg.cols, H = bg.rows;
    left->create(H, W, CV_8UC1);
    right->create(H, W, CV_8UC1);
    gt->create(H, W, CV_8UC1);
    int max_disp = 0;
    for (int y = 0; y < H; ++y) {
        uint8_t* L = left->ptr<uint8_t>(y);
        uint8_t* R = right->ptr<uint8_t>(y);
        uint8_t* G = gt->ptr<uint8_t>(y);
        const uint8_t* B = bg.ptr<uint8_t>(y);
        for (int x = 0; x < W; ++x) {
            // Left view: the nearest surface at left pixel x.
            int top = -1;
            for (int k = 0; k < static_cast<int>(objs.size()); ++k)
                if (objs[k].contains(x, y)) top = k;
            const int lv = top < 0 ? B[x] : objs[top].colour(x, y);
            L[x] = static_cast<uint8_t>(clamp255(lv + noise.range(-kSynthNoise, kSynthNoise)));
            G[x] = static_cast<uint8_t>(top < 0 ? 0 : objs[top].d);
            max_disp = std::max(max_disp, static_cast<int>(G[x]));

            // Right view: right pixel x sees surface point left x + d of the
            // nearest surface whose left-view position x + d it covers.
            int rtop = -1;
            for (int k = 0; k < static_cast<int>(objs.size()); ++k)
                if (x + objs[k].d < W && objs[k].contains(x + objs[k].d, y)) rtop = k;
            const int rv = rtop < 0 ? B[x] : objs[rtop].colour(x + objs[rtop].d, y);
            R[x] = static_cast<uint8_t>(clamp255(rv + noise.range(-kSynthNoise, kSynthNoise)));
        }
    }
    return max_disp;
}

}  // namespace detail

SynthScene make_synth_scene(uint64_t seed, int width, int height) {
    using namespace detail;
    if (width < 1 || height < 1 || width > 65536 || height > 65536)
        throw std::invalid_argument("make_synth_scene: size " + std::to_string(width) + "x" +
                                    std::to_string(height) + " outside 1..65536");
    Rng rng(seed ^ 0x1A2B3C4D5E6F7081ull);
    const int W = width, H = height;
    const int max_disp = std::min(kSynthMaxDisp, W / 4);

    // Background (disparity 0) texture, then the objects.
    const cv::Mat bg = make_texture(rng, W, H, 30, 150);
    std::vector<Object> objs;
    if (max_disp >= 1) {
        const int n = rng.range(3, 5);
        for (int k = 0; k < n; ++k) {
            Object o{};
            // Disparities spread over 1..max_disp, jittered, the last one = max_disp.
            const int base = (max_disp * (k + 1) + n / 2) / n;
            const int jit = max_disp / (3 * n);
            o.d = k == n - 1 ? max_disp : std::clamp(base + rng.range(-jit, jit), 1, max_disp);
            o.w = rng.range(std::max(1, W / 8), std::max(1, W / 3));
            o.h = rng.range(std::max(1, H / 6), std::max(1, H / 2));
            // x0 >= 2d + 2 where it fits: the background strip left of the
            // object's occlusion (left pixels x0 - d .. x0 - 1) stays at least d
            // wide, so occlusions do not run into the image border. x0 >= d and
            // x0 + w <= W always.
            const int x_min = 2 * o.d + 2;
            o.w = std::max(1, std::min(o.w, W - x_min));
            o.x0 = rng.range(std::max(o.d, std::min(x_min, W - o.w)), W - o.w);
            o.y0 = rng.range(0, H - o.h);
            o.disc = rng.range(0, 1) != 0;
            o.tex = make_texture(rng, o.w, o.h, 80, 160);
            objs.push_back(std::move(o));
        }
        // Nearer (larger disparity) objects are drawn later, on top.
        std::stable_sort(objs.begin(), objs.end(),
                         [](const Object& a, const Object& b) { return a.d < b.d; });
    }

    SynthScene sc;
    sc.max_disp = render_views(bg, objs, rng, &sc.left, &sc.right, &sc.gt);
    return sc;
}

}  // namespace imap::vision
