// Independent re-implementation of SPEC Part A for the golden tests.
//
// A literal, unoptimised transcription of the SPEC text: int64 costs, explicit
// "reachable" flags instead of an infinity value, std::vector<std::vector<>>
// tables indexed by [site + 1][level] for sites -1..N-1. It shares nothing with
// golden/src except the parameter struct and the pointer encoding (kM, kD, kO,
// kNone) that stereo.hpp defines as part of the API.
#pragma once

#include <algorithm>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <string>
#include <vector>

#include "imap/golden/params.hpp"
#include "imap/golden/stereo.hpp"

namespace specref {

namespace g = imap::golden;

// A.1: Wm(i,j) = km*|a-b| + kb*(gb - min(a,b)), gb - min taken as 0 if negative.
inline int64_t wm(const g::Params& p, int a, int b) {
    const int64_t diff = a > b ? a - b : b - a;
    int64_t dark = static_cast<int64_t>(p.gb) - (a < b ? a : b);
    if (dark < 0) dark = 0;
    return static_cast<int64_t>(p.km) * diff + static_cast<int64_t>(p.kb) * dark;
}

// A.1: valid states satisfy 0 <= j < D and i + j <= N-1; column -1 is the
// virtual start column.
inline bool valid_state(int N, int D, int i, int j) {
    return j >= 0 && j < D && i >= -1 && i <= N - 1 && i + j <= N - 1;
}

// A.4: nodes(site i) = number of valid levels at site i.
inline int nodes(int N, int D, int i) {
    int c = 0;
    for (int j = 0; j < D; ++j)
        if (valid_state(N, D, i, j)) ++c;
    return c;
}

// A.4: seed column. balanced: the s in 1..N-1 minimising
// |nodes(sites < s) - nodes(sites >= s)| (sites 0..N-1), ties the smaller s;
// center: N/2; otherwise the number.
inline int seed_col(const g::Params& p, int N) {
    if (p.seed_col.kind == g::SeedColKind::Fixed) return p.seed_col.value;
    if (p.seed_col.kind == g::SeedColKind::Center) return N / 2;
    std::vector<int64_t> n(static_cast<size_t>(N));
    for (int i = 0; i < N; ++i) n[i] = nodes(N, p.D, i);
    int best = -1;
    int64_t best_diff = 0;
    for (int s = 1; s <= N - 1; ++s) {
        int64_t lo = 0, hi = 0;
        for (int i = 0; i < N; ++i) (i < s ? lo : hi) += n[i];
        const int64_t diff = lo > hi ? lo - hi : hi - lo;
        if (best < 0 || diff < best_diff) {
            best = s;
            best_diff = diff;
        }
    }
    return best;
}

// The match cost of state (i, j) of one line: SPEC A.1's Wm, or the A.9
// aggregated cost (a9_cost below).
using CostFn = std::function<int64_t(int i, int j)>;

struct LineRef {
    int N = 0, D = 0;
    bool bidir = false;
    bool joint = false;  // A.9: forward over sites <= s, cost-to-go over sites >= s
    int s = 0;
    int ds = -1;  // -1 = free
    int js = -1;  // joint: the meeting level
    // [i + 1][j] for i = -1..N-1. E/Er/bp: right wavefront; G/Gr/fp: left.
    std::vector<std::vector<int64_t>> E, G;
    std::vector<std::vector<char>> Er, Gr;
    std::vector<std::vector<int>> bp, fp;
    int64_t right_cost = 0;  // E(N-1, 0)
    int64_t left_cost = 0;   // G(-1, 0)

    bool valid(int i, int j) const { return valid_state(N, D, i, j); }
    // A state of the right wavefront that is valid and reachable.
    bool right_ok(int i, int j) const {
        if (!valid(i, j)) return false;
        if (bidir && i < s) return false;
        if (joint && i > s) return false;
        return Er[i + 1][j] != 0;
    }
    // A state of the left wavefront that is valid and reachable.
    bool left_ok(int i, int j) const {
        if (joint) return valid(i, j) && i >= s && Gr[i + 1][j] != 0;
        if (!bidir || !valid(i, j) || i > s - 1) return false;
        return Gr[i + 1][j] != 0;
    }
    int bpv(int i, int j) const { return bp[i + 1][j]; }
    int fpv(int i, int j) const { return fp[i + 1][j]; }
};

namespace detail {

// One candidate of the min(): absent when its source/target is not ok; tried
// in the order of the calls; replaces the current best only if strictly smaller.
struct Best {
    bool have = false;
    int64_t cost = 0;
    int step = g::kNone;
    void consider(bool present, int64_t c, int st) {
        if (!present) return;
        if (!have || c < cost) {
            have = true;
            cost = c;
            step = st;
        }
    }
};

// A.3 recurrence for sites first..last (right wavefront).
inline void right_pass(const g::Params& p, const CostFn& wmf, LineRef& t, int first, int last) {
    for (int i = first; i <= last; ++i) {
        for (int j = 0; j < t.D; ++j) {  // increasing j: O reads the same site
            if (!t.valid(i, j)) continue;
            Best b;
            b.consider(t.right_ok(i - 1, j), t.right_ok(i - 1, j) ? t.E[i][j] + wmf(i, j) : 0,
                       g::kM);
            b.consider(t.right_ok(i - 1, j + 1),
                       t.right_ok(i - 1, j + 1) ? t.E[i][j + 1] + p.Wd : 0, g::kD);
            b.consider(t.right_ok(i, j - 1), t.right_ok(i, j - 1) ? t.E[i + 1][j - 1] + p.Wo : 0,
                       g::kO);
            t.Er[i + 1][j] = b.have ? 1 : 0;
            t.E[i + 1][j] = b.have ? b.cost : 0;
            t.bp[i + 1][j] = b.have ? b.step : g::kNone;
        }
    }
}

// A.4 cost-to-go recurrence for sites hi-1 down to lo, levels in decreasing j.
inline void left_pass(const g::Params& p, const CostFn& wmf, LineRef& t, int hi, int lo) {
    for (int i = hi - 1; i >= lo; --i) {
        for (int j = t.D - 1; j >= 0; --j) {
            if (!t.valid(i, j)) continue;
            Best b;
            const bool m = t.left_ok(i + 1, j);
            b.consider(m, m ? t.G[i + 2][j] + wmf(i + 1, j) : 0, g::kM);
            const bool d = t.left_ok(i + 1, j - 1);
            b.consider(d, d ? t.G[i + 2][j - 1] + p.Wd : 0, g::kD);
            const bool o = t.left_ok(i, j + 1);
            b.consider(o, o ? t.G[i + 1][j + 1] + p.Wo : 0, g::kO);
            t.Gr[i + 1][j] = b.have ? 1 : 0;
            t.G[i + 1][j] = b.have ? b.cost : 0;
            t.fp[i + 1][j] = b.have ? b.step : g::kNone;
        }
    }
}

}  // namespace detail

// Forward pass(es) of A.3 / A.4 (and A.9 joint) for one scanline of length N
// whose match cost of state (i, j) is wmf(i, j).
inline LineRef forward(const g::Params& p, int N, const CostFn& wmf) {
    LineRef t;
    t.N = N;
    t.D = p.D;
    t.bidir = p.mode == g::Mode::Bidir;
    const size_t rows = static_cast<size_t>(N) + 1;
    const size_t D = static_cast<size_t>(p.D);
    t.E.assign(rows, std::vector<int64_t>(D, 0));
    t.G.assign(rows, std::vector<int64_t>(D, 0));
    t.Er.assign(rows, std::vector<char>(D, 0));
    t.Gr.assign(rows, std::vector<char>(D, 0));
    t.bp.assign(rows, std::vector<int>(D, g::kNone));
    t.fp.assign(rows, std::vector<int>(D, g::kNone));

    if (!t.bidir) {
        // A.3: E(-1, j) = j*Wo for valid j.
        for (int j = 0; j < t.D; ++j) {
            if (!t.valid(-1, j)) continue;
            t.E[0][j] = static_cast<int64_t>(j) * p.Wo;
            t.Er[0][j] = 1;
        }
        if (p.mode != g::Mode::Joint) {
            detail::right_pass(p, wmf, t, 0, N - 1);
            t.right_cost = t.E[N][0];
            return t;
        }
    }

    const int s = seed_col(p, N);
    if (p.mode == g::Mode::Joint) {
        // A.9 joint: E over sites 0..s (from column -1 above), G from the end
        // state (N-1, 0) down to site s, meeting at argmin E + G (smallest j;
        // the seed disparity when fixed).
        t.joint = true;
        t.s = s;
        t.ds = p.seed_disp.free ? -1 : p.seed_disp.value;
        detail::right_pass(p, wmf, t, 0, s);
        t.G[N][0] = 0;
        t.Gr[N][0] = 1;
        t.fp[N][0] = g::kM;
        detail::left_pass(p, wmf, t, N - 1, s);
        bool have = false;
        for (int j = 0; j < t.D; ++j) {
            if (!t.right_ok(s, j) || !t.left_ok(s, j)) continue;
            if (t.ds >= 0 && j != t.ds) continue;
            const int64_t c = t.E[s + 1][j] + t.G[s + 1][j];
            if (!have || c < t.right_cost) {
                have = true;
                t.right_cost = c;
                t.js = j;
            }
        }
        return t;
    }
    const int ds = p.seed_disp.free ? -1 : p.seed_disp.value;
    t.s = s;
    t.ds = ds;

    // A.4 right wavefront, site s.
    for (int j = 0; j < t.D; ++j) {
        if (!t.valid(s, j)) continue;
        if (ds < 0) {
            t.E[s + 1][j] = 0;
            t.Er[s + 1][j] = 1;
            t.bp[s + 1][j] = g::kM;  // stereo.hpp: kM at every level when free
        } else if (j == ds) {
            t.E[s + 1][j] = 0;
            t.Er[s + 1][j] = 1;
            t.bp[s + 1][j] = g::kM;  // stereo.hpp: kM at the seed
        } else if (j > ds) {
            t.E[s + 1][j] = static_cast<int64_t>(j - ds) * p.Wo;
            t.Er[s + 1][j] = 1;
            t.bp[s + 1][j] = g::kO;
        }  // j < ds: unreachable
    }
    detail::right_pass(p, wmf, t, s + 1, N - 1);
    t.right_cost = t.E[N][0];

    // A.4 left wavefront, site s-1.
    for (int j = 0; j < t.D; ++j) {
        if (!t.valid(s - 1, j)) continue;
        if (ds < 0 || j == ds) {
            t.G[s][j] = 0;
            t.Gr[s][j] = 1;
            t.fp[s][j] = g::kM;  // not specified by SPEC/stereo.hpp; never followed
        } else if (j < ds) {
            t.G[s][j] = static_cast<int64_t>(ds - j) * p.Wo;
            t.Gr[s][j] = 1;
            t.fp[s][j] = g::kO;
        }  // j > ds: unreachable
    }
    // i < s-1, for i = s-2 down to -1, levels in decreasing j.
    detail::left_pass(p, wmf, t, s - 1, -1);
    t.left_cost = t.G[0][0];
    return t;
}

// Forward pass(es) with SPEC A.1's Wm on pixel rows L and R (N pixels each).
inline LineRef forward(const g::Params& p, const uint8_t* L, const uint8_t* R, int N) {
    return forward(p, N, [&](int i, int j) { return wm(p, R[i], L[i + j]); });
}

// Source state of a step that arrives at (i, j) (A.2).
inline void source_of(int step, int i, int j, int& si, int& sj) {
    si = i;
    sj = j;
    if (step == g::kM) {
        si = i - 1;
    } else if (step == g::kD) {
        si = i - 1;
        sj = j + 1;
    } else if (step == g::kO) {
        sj = j - 1;
    }
}

// Target state of a left-wavefront step taken from (i, j) (A.4).
inline void target_of(int step, int i, int j, int& ti, int& tj) {
    ti = i;
    tj = j;
    if (step == g::kM) {
        ti = i + 1;
    } else if (step == g::kD) {
        ti = i + 1;
        tj = j - 1;
    } else if (step == g::kO) {
        tj = j + 1;
    }
}

inline bool is_step(int v) {
    return v == g::kM || v == g::kD || v == g::kO;
}

// A.5 + A.6 fallback, right wavefront (bp).
inline int voted_bp(const LineRef* above, const LineRef& self, const LineRef* below, int i, int j) {
    const int own = self.bpv(i, j);
    if (above == nullptr || below == nullptr) return own;
    const int v = above->bpv(i, j);
    if (v != below->bpv(i, j)) return own;
    if (v == own) return own;
    if (!is_step(v)) return own;
    int si = 0, sj = 0;
    source_of(v, i, j, si, sj);
    return self.right_ok(si, sj) ? v : own;
}

// A.5 + A.6 fallback, left wavefront (fp).
inline int voted_fp(const LineRef* above, const LineRef& self, const LineRef* below, int i, int j) {
    const int own = self.fpv(i, j);
    if (above == nullptr || below == nullptr) return own;
    const int v = above->fpv(i, j);
    if (v != below->fpv(i, j)) return own;
    if (v == own) return own;
    if (!is_step(v)) return own;
    int ti = 0, tj = 0;
    target_of(v, i, j, ti, tj);
    return self.left_ok(ti, tj) ? v : own;
}

struct Ev {
    int i, j, step;
};

// A.6 backtrack; events in output order (bidir: left first, then right).
inline std::vector<Ev> backtrack(const LineRef* above, const LineRef& self, const LineRef* below,
                                 bool vote) {
    if (!vote) above = below = nullptr;
    std::vector<Ev> ev;
    const int guard = 4 * (self.N + self.D) + 8;
    if (self.joint) {
        // A.9: forward from (s, js) along fp to the end state (N-1, 0), the
        // events reversed (backtrack order), then back from (s, js) along bp.
        int i = self.s, j = self.js;
        for (int n = 0; n < guard && i < self.N - 1; ++n) {
            const int v = voted_fp(above, self, below, i, j);
            int ti = 0, tj = 0;
            target_of(v, i, j, ti, tj);
            i = ti;
            j = tj;
            ev.push_back({i, j, v});
        }
        std::vector<Ev> rev(ev.rbegin(), ev.rend());
        ev = rev;
        i = self.s;
        j = self.js;
        for (int n = 0; n < guard && i > -1; ++n) {
            const int v = voted_bp(above, self, below, i, j);
            ev.push_back({i, j, v});
            int si = 0, sj = 0;
            source_of(v, i, j, si, sj);
            i = si;
            j = sj;
        }
        return ev;
    }
    if (self.bidir) {
        int i = -1, j = 0;
        for (int n = 0; n < guard; ++n) {
            if (i == self.s - 1 && (self.ds < 0 || j == self.ds)) break;
            const int v = voted_fp(above, self, below, i, j);
            int ti = 0, tj = 0;
            target_of(v, i, j, ti, tj);
            i = ti;
            j = tj;
            ev.push_back({i, j, v});
        }
    }
    const int stop = self.bidir ? self.s : -1;
    int i = self.N - 1, j = 0;
    for (int n = 0; n < guard && i > stop; ++n) {
        const int v = voted_bp(above, self, below, i, j);
        ev.push_back({i, j, v});
        int si = 0, sj = 0;
        source_of(v, i, j, si, sj);
        i = si;
        j = sj;
    }
    if (self.bidir) {
        for (int n = 0; n < guard && self.ds >= 0 && j > self.ds; ++n) {
            const int v = voted_bp(above, self, below, i, j);  // the O pointers above the seed
            ev.push_back({i, j, v});
            --j;
        }
        ev.push_back({i, j, g::kM});
    }
    return ev;
}

// A.7 output map of one line.
inline std::vector<uint8_t> render(const std::vector<Ev>& ev, g::Frame f, int N) {
    std::vector<uint8_t> out(static_cast<size_t>(N), 255);
    for (const Ev& e : ev) {
        if (e.step != g::kM) continue;
        int x = 0;
        if (f == g::Frame::Right) {
            x = e.i;
        } else if (f == g::Frame::Left) {
            x = e.i + e.j;
        } else {
            const int c = 2 * e.i + e.j;
            x = c >> 1;
        }
        if (x >= 0 && x < N) out[static_cast<size_t>(x)] = static_cast<uint8_t>(e.j);
    }
    return out;
}

// A.7 fill: each 255 becomes the smaller of the nearest non-occluded values
// left and right on the original row (one side: that one; none: 0).
inline std::vector<uint8_t> fill(const std::vector<uint8_t>& row) {
    std::vector<uint8_t> out = row;
    const int n = static_cast<int>(row.size());
    for (int x = 0; x < n; ++x) {
        if (row[x] != 255) continue;
        int l = -1, r = -1;
        for (int k = x - 1; k >= 0; --k)
            if (row[k] != 255) {
                l = row[k];
                break;
            }
        for (int k = x + 1; k < n; ++k)
            if (row[k] != 255) {
                r = row[k];
                break;
            }
        int v = 0;
        if (l >= 0 && r >= 0)
            v = l < r ? l : r;
        else if (l >= 0)
            v = l;
        else if (r >= 0)
            v = r;
        out[x] = static_cast<uint8_t>(v);
    }
    return out;
}

// ---- SPEC A.9 match cost (docs/golden.md, "Options"), literally ----------

// Pixel (x, y) of the ROI with replicated borders (coordinates clamped).
inline int roi_px(const std::vector<uint8_t>& img, int W, const g::Roi& roi, int x, int y) {
    x = x < 0 ? 0 : (x > roi.w - 1 ? roi.w - 1 : x);
    y = y < 0 ? 0 : (y > roi.h - 1 ? roi.h - 1 : y);
    return img[static_cast<size_t>(roi.y0 + y) * W + roi.x0 + x];
}

// Census: bit k for the k-th neighbour (dx, dy) * r of the order
// (-1,-1) (0,-1) (1,-1) (-1,0) (1,0) (-1,1) (0,1) (1,1): set when darker.
inline int census(const std::vector<uint8_t>& img, int W, const g::Roi& roi, int x, int y, int r) {
    static const int dx[8] = {-1, 0, 1, -1, 1, -1, 0, 1};
    static const int dy[8] = {-1, -1, -1, 0, 0, 1, 1, 1};
    const int c = roi_px(img, W, roi, x, y);
    int code = 0;
    for (int k = 0; k < 8; ++k)
        if (roi_px(img, W, roi, x + dx[k] * r, y + dy[k] * r) < c) code |= 1 << k;
    return code;
}

inline int hamming(int a, int b) {
    int n = 0;
    for (int v = a ^ b; v != 0; v >>= 1) n += v & 1;
    return n;
}

// Distance from a to the Birchfield-Tomasi interval of pixel x of a row:
// the smallest |a - v| over every v between the least and the greatest of
// I(x), (I(x) + I(x-1)) / 2, (I(x) + I(x+1)) / 2 (halves rounded down).
inline int bt_half(int a, const std::vector<uint8_t>& img, int W, const g::Roi& roi, int x, int y) {
    const int v = roi_px(img, W, roi, x, y);
    const int l = (v + roi_px(img, W, roi, x - 1, y)) / 2;
    const int r = (v + roi_px(img, W, roi, x + 1, y)) / 2;
    const int lo = std::min({v, l, r}), hi = std::max({v, l, r});
    int best = 256;
    for (int u = lo; u <= hi; ++u) best = std::min(best, std::abs(a - u));
    return best;
}

// The A.9 cost of the pixel pair right (xr, y), left (xl, y). A position
// outside the ROI has the terms (value, census code, BT interval) of the
// nearest ROI position.
inline int64_t a9_pixel(const g::Params& p, const std::vector<uint8_t>& left,
                        const std::vector<uint8_t>& right, int W, const g::Roi& roi, int xr, int xl,
                        int y) {
    xr = std::min(std::max(xr, 0), roi.w - 1);
    xl = std::min(std::max(xl, 0), roi.w - 1);
    const int a = roi_px(right, W, roi, xr, y), b = roi_px(left, W, roi, xl, y);
    int dis = std::abs(a - b);
    if (p.dissim == g::Dissim::Bt)
        dis = std::min(bt_half(a, left, W, roi, xl, y), bt_half(b, right, W, roi, xr, y));
    dis = std::min(dis, p.ad_max);
    int64_t c = static_cast<int64_t>(p.km) * dis +
                static_cast<int64_t>(p.kb) * std::max(0, p.gb - std::min(a, b));
    if (p.kc > 0)
        c += static_cast<int64_t>(p.kc) *
             hamming(census(right, W, roi, xr, y, p.census), census(left, W, roi, xl, y, p.census));
    return c;
}

// A.9 Wm(i, j) of ROI line y: the pixel costs of right x = i+u and left
// x = i+u+j (each clamped into the ROI) of lines y+v (clamped), summed over
// |u| <= agg_rx, |v| <= agg_ry.
inline int64_t a9_cost(const g::Params& p, const std::vector<uint8_t>& left,
                       const std::vector<uint8_t>& right, int W, const g::Roi& roi, int y, int i,
                       int j) {
    int64_t sum = 0;
    for (int v = -p.agg_ry; v <= p.agg_ry; ++v) {
        const int yy = std::min(std::max(y + v, 0), roi.h - 1);
        for (int u = -p.agg_rx; u <= p.agg_rx; ++u)
            sum += a9_pixel(p, left, right, W, roi, i + u, i + u + j, yy);
    }
    return sum;
}

inline bool a9_cost_on(const g::Params& p) {
    return p.dissim != g::Dissim::Ad || p.ad_max < 255 || p.kc > 0 || p.agg_rx > 0 || p.agg_ry > 0;
}

// The whole of Part A (and A.9) on images of width W (row stride W), ROI roi.
inline std::vector<uint8_t> compute(const g::Params& p, const std::vector<uint8_t>& left,
                                    const std::vector<uint8_t>& right, int W, const g::Roi& roi,
                                    bool do_fill) {
    std::vector<LineRef> lines;
    for (int y = 0; y < roi.h; ++y) {
        const size_t off = static_cast<size_t>(roi.y0 + y) * W + roi.x0;
        if (a9_cost_on(p))
            lines.push_back(forward(
                p, roi.w, [&](int i, int j) { return a9_cost(p, left, right, W, roi, y, i, j); }));
        else
            lines.push_back(forward(p, left.data() + off, right.data() + off, roi.w));
    }
    std::vector<uint8_t> out;
    for (int y = 0; y < roi.h; ++y) {
        const LineRef* above = y > 0 ? &lines[y - 1] : nullptr;
        const LineRef* below = y + 1 < roi.h ? &lines[y + 1] : nullptr;
        std::vector<uint8_t> row =
            render(backtrack(above, lines[y], below, p.vote), p.frame, roi.w);
        if (do_fill) row = fill(row);
        out.insert(out.end(), row.begin(), row.end());
    }
    return out;
}

}  // namespace specref
