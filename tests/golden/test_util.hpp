// Shared helpers of the golden tests: random inputs and readable descriptions.
#pragma once

#include <algorithm>
#include <cstdint>
#include <random>
#include <sstream>
#include <string>
#include <vector>

#include "imap/golden/params.hpp"
#include "imap/golden/stereo.hpp"
#include "spec_ref.hpp"

namespace gt {

namespace g = imap::golden;

inline int uni(std::mt19937& rng, int lo, int hi) {
    return std::uniform_int_distribution<int>(lo, hi)(rng);
}

inline std::string row_string(const uint8_t* px, int n) {
    std::ostringstream os;
    os << "{";
    for (int x = 0; x < n; ++x) os << (x ? "," : "") << int(px[x]);
    os << "}";
    return os.str();
}

inline std::string describe(const g::Params& p) {
    std::ostringstream os;
    os << "D=" << p.D << " km=" << p.km << " kb=" << p.kb << " gb=" << p.gb << " Wo=" << p.Wo
       << " Wd=" << p.Wd << " mode=" << g::to_string(p.mode);
    if (p.mode == g::Mode::Bidir) {
        os << " seed_col=";
        if (p.seed_col.kind == g::SeedColKind::Balanced)
            os << "balanced";
        else if (p.seed_col.kind == g::SeedColKind::Center)
            os << "center";
        else
            os << p.seed_col.value;
        os << " seed_disp="
           << (p.seed_disp.free ? std::string("free") : std::to_string(p.seed_disp.value));
    }
    os << " vote=" << p.vote << " frame=" << g::to_string(p.frame);
    return os.str();
}

inline std::string events_string(const std::vector<g::Event>& ev) {
    std::ostringstream os;
    for (const g::Event& e : ev)
        os << "MDO?"[e.step < 3 ? e.step : 3] << "(" << e.i << "," << e.j << ")";
    return os.str();
}

// Random scanline pixels: several distributions (uniform, tiny range for many
// ties, a shifted copy of the other row for realistic matches, constant).
inline void random_rows(std::mt19937& rng, int N, std::vector<uint8_t>& L,
                        std::vector<uint8_t>& R) {
    L.assign(static_cast<size_t>(N), 0);
    R.assign(static_cast<size_t>(N), 0);
    const int kind = uni(rng, 0, 4);
    if (kind == 0) {
        for (int x = 0; x < N; ++x) {
            L[x] = static_cast<uint8_t>(uni(rng, 0, 255));
            R[x] = static_cast<uint8_t>(uni(rng, 0, 255));
        }
    } else if (kind == 1) {
        const int base = uni(rng, 0, 253);
        for (int x = 0; x < N; ++x) {
            L[x] = static_cast<uint8_t>(base + uni(rng, 0, 2));
            R[x] = static_cast<uint8_t>(base + uni(rng, 0, 2));
        }
    } else if (kind == 2) {
        const int d = uni(rng, 0, N - 1);
        for (int x = 0; x < N; ++x) L[x] = static_cast<uint8_t>(uni(rng, 0, 255));
        for (int x = 0; x < N; ++x) {
            const int v = x + d < N ? L[x + d] + uni(rng, -3, 3) : uni(rng, 0, 255);
            R[x] = static_cast<uint8_t>(v < 0 ? 0 : v > 255 ? 255 : v);
        }
    } else if (kind == 3) {
        const int v = uni(rng, 0, 255);
        for (int x = 0; x < N; ++x) L[x] = R[x] = static_cast<uint8_t>(v);
    } else {
        for (int x = 0; x < N; ++x) {
            L[x] = static_cast<uint8_t>(uni(rng, 0, 1) * 200 + uni(rng, 0, 3));
            R[x] = static_cast<uint8_t>(uni(rng, 0, 1) * 200 + uni(rng, 0, 3));
        }
    }
}

// Random valid weights; `big` selects weights near the accepted maximum
// (exercises exact 64-bit costs).
inline void random_weights(std::mt19937& rng, g::Params& p, bool big = false) {
    const int kind = big ? 4 : uni(rng, 0, 3);
    if (kind == 0) {  // tiny weights: many ties
        p.km = uni(rng, 0, 2);
        p.kb = uni(rng, 0, 2);
        p.Wd = uni(rng, 0, 3);
        p.Wo = p.Wd + uni(rng, 0, 3);
    } else if (kind == 1) {  // ordinary
        p.km = uni(rng, 0, 10);
        p.kb = uni(rng, 0, 4);
        p.Wd = uni(rng, 0, 80);
        p.Wo = p.Wd + uni(rng, 0, 80);
    } else if (kind == 2) {  // wide
        p.km = uni(rng, 0, 1000);
        p.kb = uni(rng, 0, 1000);
        p.Wd = uni(rng, 0, 100000);
        p.Wo = p.Wd + uni(rng, 0, 100000);
    } else if (kind == 3) {  // costs around the 32-bit range
        p.km = uni(rng, 0, 200000);
        p.kb = uni(rng, 0, 50000);
        p.Wd = uni(rng, 0, 500000);
        p.Wo = p.Wd + uni(rng, 0, 500000);
    } else {  // near kMaxWeight
        const int mx = static_cast<int>(g::kMaxWeight);
        p.km = uni(rng, mx - 1000, mx);
        p.kb = uni(rng, 0, mx);
        p.Wd = uni(rng, 0, mx);
        p.Wo = uni(rng, p.Wd, mx);
    }
    if (p.km == 0 && p.kb == 0) p.km = 1;
    p.gb = uni(rng, 0, 3) == 0 ? uni(rng, 0, 255) : uni(rng, 0, 80);
}

// Random valid bidir seed settings for width N (N >= 2) and p.D.
inline void random_seed(std::mt19937& rng, g::Params& p, int N) {
    const int k = uni(rng, 0, 2);
    p.seed_col.kind = k == 0   ? g::SeedColKind::Balanced
                      : k == 1 ? g::SeedColKind::Center
                               : g::SeedColKind::Fixed;
    p.seed_col.value = k == 2 ? uni(rng, 1, N - 1) : 0;
    p.seed_disp.free = uni(rng, 0, 1) == 0;
    p.seed_disp.value = 0;
    if (!p.seed_disp.free) {
        const int s = specref::seed_col(p, N);
        const int hi = std::min(p.D - 1, N - 1 - s);
        p.seed_disp.value = uni(rng, 0, hi);
    }
}

}  // namespace gt
