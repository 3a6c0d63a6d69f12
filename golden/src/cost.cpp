#include "imap/golden/cost.hpp"

#include <algorithm>

namespace imap::golden {
namespace {

int clampi(int v, int lo, int hi) {
    return v < lo ? lo : (v > hi ? hi : v);
}

// Census neighbour offsets (dx, dy) in bit order, in units of the radius.
constexpr int kCensusDx[8] = {-1, 0, 1, -1, 1, -1, 0, 1};
constexpr int kCensusDy[8] = {-1, -1, -1, 0, 0, 1, 1, 1};

}  // namespace

bool uses_cost_volume(const Params& p) {
    return p.dissim != Dissim::Ad || p.ad_max < 255 || p.kc != 0 || p.agg_rx != 0 || p.agg_ry != 0;
}

int64_t pixel_cost_max(const Params& p) {
    return int64_t{p.km} * std::min(255, p.ad_max) + int64_t{p.kb} * p.gb + int64_t{p.kc} * 8;
}

int64_t window_terms(const Params& p) {
    return int64_t{2 * p.agg_rx + 1} * (2 * p.agg_ry + 1);
}

std::vector<uint8_t> census_codes(ImageView img, const Roi& roi, int radius) {
    std::vector<uint8_t> out(static_cast<size_t>(roi.w) * roi.h);
    for (int y = 0; y < roi.h; ++y) {
        for (int x = 0; x < roi.w; ++x) {
            const int c = img.row(roi.y0 + y)[roi.x0 + x];
            unsigned code = 0;
            for (int k = 0; k < 8; ++k) {
                const int yy = clampi(y + kCensusDy[k] * radius, 0, roi.h - 1);
                const int xx = clampi(x + kCensusDx[k] * radius, 0, roi.w - 1);
                if (img.row(roi.y0 + yy)[roi.x0 + xx] < c) code |= 1u << k;
            }
            out[static_cast<size_t>(y) * roi.w + x] = static_cast<uint8_t>(code);
        }
    }
    return out;
}

void bt_bounds(const uint8_t* row, int n, uint8_t* lo, uint8_t* hi) {
    for (int x = 0; x < n; ++x) {
        const int v = row[x];
        const int l = (v + row[x > 0 ? x - 1 : 0]) >> 1;
        const int r = (v + row[x + 1 < n ? x + 1 : n - 1]) >> 1;
        lo[x] = static_cast<uint8_t>(std::min({v, l, r}));
        hi[x] = static_cast<uint8_t>(std::max({v, l, r}));
    }
}

template <class C>
CostVolume<C>::CostVolume(const Params& p, ImageView left, ImageView right, const Roi& roi)
    : p_(p),
      L_(left),
      R_(right),
      roi_(roi),
      N_(roi.w),
      D_(p.D),
      rx_(p.agg_rx),
      ry_(p.agg_ry),
      W_(roi.w + 2 * p.agg_rx) {
    if (p.kc > 0) {
        cl_ = census_codes(left, roi, p.census);
        cr_ = census_codes(right, roi, p.census);
    }
    if (p.dissim == Dissim::Bt) {
        const size_t n = static_cast<size_t>(roi.w) * roi.h;
        llo_.resize(n);
        lhi_.resize(n);
        rlo_.resize(n);
        rhi_.resize(n);
        for (int y = 0; y < roi.h; ++y) {
            const size_t o = static_cast<size_t>(y) * roi.w;
            bt_bounds(left.row(roi.y0 + y) + roi.x0, roi.w, &llo_[o], &lhi_[o]);
            bt_bounds(right.row(roi.y0 + y) + roi.x0, roi.w, &rlo_[o], &rhi_[o]);
        }
    }
    const size_t row = static_cast<size_t>(W_) * D_;
    ring_.assign(row * (2 * ry_ + 1), 0);
    ring_line_.assign(static_cast<size_t>(2 * ry_ + 1), -1);
    vsum_.assign(row, 0);
    out_.assign(static_cast<size_t>(N_) * D_, 0);
}

namespace {

// Bits set in each byte value (census Hamming distance without a CPU popcount).
struct PopTable {
    uint8_t n[256];
    PopTable() {
        for (int v = 0; v < 256; ++v) n[v] = static_cast<uint8_t>(__builtin_popcount(v));
    }
};
const PopTable kPop;

// One pixel row: out[(x + rx) * D + j] for x = -rx..N-1+rx, j = 0..D-1, from
// left-row data padded so that index x + j + rx needs no clamp.
template <class C, bool kBt, bool kCensus, bool kDark>
void pixel_row_typed(const Params& p, int N, int rx, const uint8_t* Rr, const uint8_t* cr,
                     const uint8_t* rlo, const uint8_t* rhi, const uint8_t* lp, const uint8_t* lcp,
                     const uint8_t* llop, const uint8_t* lhip, C* out) {
    const int D = p.D;
    const C km = p.km, kb = p.kb, kc = p.kc;
    const int gb = p.gb, ad_max = p.ad_max;
    for (int x = -rx; x < N + rx; ++x) {
        const int xr = clampi(x, 0, N - 1);
        const int a = Rr[xr];
        const int ca = kCensus ? cr[xr] : 0;
        const int alo = kBt ? rlo[xr] : 0, ahi = kBt ? rhi[xr] : 0;
        const size_t k0 = static_cast<size_t>(x + rx);
        C* dst = out + k0 * D;
        const uint8_t* bl = lp + k0;
        for (int j = 0; j < D; ++j) {
            const int b = bl[j];
            int dis = a > b ? a - b : b - a;
            if constexpr (kBt) dis = bt_dissim(a, alo, ahi, b, llop[k0 + j], lhip[k0 + j]);
            C c = km * (dis < ad_max ? dis : ad_max);
            if constexpr (kDark) {
                const int dark = gb - (a < b ? a : b);
                c += kb * (dark > 0 ? dark : 0);
            }
            if constexpr (kCensus) c += kc * kPop.n[ca ^ lcp[k0 + j]];
            dst[j] = c;
        }
    }
}

template <class C, bool kBt, bool kCensus>
auto pick_dark(bool dark) {
    return dark ? &pixel_row_typed<C, kBt, kCensus, true>
                : &pixel_row_typed<C, kBt, kCensus, false>;
}

}  // namespace

template <class C>
void CostVolume<C>::pixel_row(int y, C* out) const {
    const uint8_t* Lr = L_.row(roi_.y0 + y) + roi_.x0;
    const uint8_t* Rr = R_.row(roi_.y0 + y) + roi_.x0;
    const size_t o = static_cast<size_t>(y) * N_;
    const bool bt = p_.dissim == Dissim::Bt;
    const bool census = p_.kc > 0;
    // Left-row data at x + j for x = -rx..N-1+rx, j < D: padded copies
    // (index x + j + rx), positions outside the ROI take the nearest pixel's.
    const int len = N_ + 2 * rx_ + D_;
    thread_local std::vector<uint8_t> lp, lcp, llop, lhip;
    lp.resize(static_cast<size_t>(len));
    lcp.resize(static_cast<size_t>(len));
    llop.resize(static_cast<size_t>(len));
    lhip.resize(static_cast<size_t>(len));
    for (int k = 0; k < len; ++k) {
        const int xl = clampi(k - rx_, 0, N_ - 1);
        lp[k] = Lr[xl];
        lcp[k] = census ? cl_[o + xl] : 0;
        llop[k] = bt ? llo_[o + xl] : 0;
        lhip[k] = bt ? lhi_[o + xl] : 0;
    }
    const uint8_t* cr = census ? &cr_[o] : nullptr;
    const uint8_t* rlo = bt ? &rlo_[o] : nullptr;
    const uint8_t* rhi = bt ? &rhi_[o] : nullptr;
    const bool dark = p_.kb != 0;
    auto fn = bt ? (census ? pick_dark<C, true, true>(dark) : pick_dark<C, true, false>(dark))
                 : (census ? pick_dark<C, false, true>(dark) : pick_dark<C, false, false>(dark));
    fn(p_, N_, rx_, Rr, cr, rlo, rhi, lp.data(), lcp.data(), llop.data(), lhip.data(), out);
}

template <class C>
const C* CostVolume<C>::line(int y) {
    const size_t row = static_cast<size_t>(W_) * D_;
    const int slots = 2 * ry_ + 1;
    // Vertical sum over lines y-ry..y+ry (clamped into the ROI).
    const C* vs = nullptr;
    for (int v = -ry_; v <= ry_; ++v) {
        const int yy = clampi(y + v, 0, roi_.h - 1);
        const int slot = yy % slots;
        C* pr = ring_.data() + row * slot;
        if (ring_line_[slot] != yy) {
            pixel_row(yy, pr);
            ring_line_[slot] = yy;
        }
        if (ry_ == 0) {
            vs = pr;
        } else if (v == -ry_) {
            std::copy(pr, pr + row, vsum_.begin());
        } else {
            C* d = vsum_.data();
            for (size_t k = 0; k < row; ++k) d[k] += pr[k];
        }
    }
    if (ry_ > 0) vs = vsum_.data();
    // Horizontal box over sites i-rx..i+rx (padded row index i + rx + u), as
    // a running sum: out(i) = out(i-1) + V(i + 2rx) - V(i - 1).
    const size_t D = static_cast<size_t>(D_);
    C* first = out_.data();
    std::fill(first, first + D, C{0});
    for (int u = 0; u <= 2 * rx_; ++u) {
        const C* src = vs + static_cast<size_t>(u) * D;
        for (size_t j = 0; j < D; ++j) first[j] += src[j];
    }
    for (int i = 1; i < N_; ++i) {
        C* dst = out_.data() + static_cast<size_t>(i) * D;
        const C* prev = dst - D;
        const C* in = vs + static_cast<size_t>(i + 2 * rx_) * D;
        const C* gone = vs + static_cast<size_t>(i - 1) * D;
        for (size_t j = 0; j < D; ++j) dst[j] = prev[j] + in[j] - gone[j];
    }
    return out_.data();
}

template class CostVolume<int32_t>;
template class CostVolume<int64_t>;

}  // namespace imap::golden
