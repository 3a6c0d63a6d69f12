// The re-layout's geometry (docs/firmware.md, section 5), from a frame
// plan's batches, segments and line placement: which lanes each kind
// receives, where the lines sit on the ring (around it, centred on the
// segment, or skewed rows), the rounds of the input and output sweeps and
// the output displacements, and the lower bound of the re-layout's ring
// cycles (relayout_bound).
#include <algorithm>

#include "plan_internal.hpp"

namespace imap::firmware {

namespace detail {

namespace {

// Calls take(kind, a, n) for every kind that receives source lanes [a, a + n)
// (n > 0) of segment g.
template <class Take>
void for_each_receiver(const FramePlan& fp, int g, Take&& take) {
    const int W = seg_width(fp, g);
    for (int kind = 0; kind < (fp.f.bidir ? 2 : 1); ++kind) {
        int a = 0, n = 0;
        in_lanes(fp.f, fp.P, g, W, kind, &a, &n);
        if (n == 0) continue;
        take(kind, a, n);
    }
}

// Skewed rows (docs/firmware.md, section 5): when the ring holds the lines'
// PEs and a video row per line shifted by `span` lanes per line, every line's
// items share one displacement per pixel: W rounds of at most ~W/2 hops
// instead of rounds over the span of all lines (not for census frames in
// several batches). The lines sit so that the
// input displacements d = base + kind - x are centred on 0, the output
// displacements likewise (skew_out).
void plan_skew(FramePlan& fp, int span) {
    Relayout& rl = fp.rl;
    if (fp.nseg != 1) return;
    // the census on skewed rows clamps its lines at HBMAX - 1 (assembly-time
    // hop counts, census.inc CENSUS_SKEWED), wrong for a shorter last batch
    if (fp.f.census > 0 && fp.batches.size() > 1) return;
    const int P = fp.P, W = seg_width(fp, 0), H = fp.hbmax;
    int lo = INT_MAX, hi = INT_MIN;  // kind - x over the input items
    for_each_receiver(fp, 0, [&](int kind, int a, int n) {
        lo = std::min(lo, kind - (a + n - 1));
        hi = std::max(hi, kind - a);
    });
    if (lo > hi) return;
    const int base = std::max(0, -((lo + hi) / 2));
    // output: kind - x over the map pixels (pixel x leaves the PE of parity x & 1)
    const int olo = fp.f.bidir ? -((W - 1) - ((W - 1) & 1)) : -(W - 1), ohi = 0;
    const int skew_out = std::max(0, base + (olo + ohi) / 2);
    const int rows = span * (H - 1) + W;  // lanes spanned by the skewed rows
    if (base + span * H > P || rows > P || skew_out + rows > P) return;
    rl.skew = true;
    rl.base = base;
    rl.skew_in = 0;
    rl.skew_out = skew_out;
    rl.dmin = base + lo;
    rl.dmax = base + hi;
    rl.smin = base - skew_out + olo;
    rl.smax = base - skew_out + ohi;
    rl.ur = rl.ul = 0;
}

// The re-layout's routes as its lower bound counts them: the ring distance,
// each line's PEs and video rows, the pixels each kind needs.
struct Routes {
    const FramePlan& fp;
    const ForwardPlan& f;
    int P, span, kinds;

    explicit Routes(const FramePlan& plan)
        : fp(plan), f(plan.f), P(plan.P), span(plan.span()), kinds(plan.f.bidir ? 2 : 1) {}

    int ring(int a, int b) const {
        int d = ((a - b) % P + P) % P;
        return std::min(d, P - d);
    }
    int pe_of(int y, int kind) const { return ((fp.rl.base + span * y + kind) % P + P) % P; }
    // lane of pixel x of line y in the video rows (input) and the output rows
    int soff(int y) const { return fp.rl.skew ? fp.rl.skew_in + span * y : 0; }
    int ooff(int y) const { return fp.rl.skew ? fp.rl.skew_out + span * y : 0; }
    // Pixels X of image img (0 = left, 1 = right) that kind `kind` needs: [lo, hi].
    void need(int img, int kind, int* lo, int* hi) const {
        *lo = 0;
        *hi = f.N - 1;
        if (!f.bidir) return;
        if (kind == 0)
            *hi = img == 0 ? std::min(f.N - 1, f.s + f.D - (f.joint ? 1 : 2))
                           : (f.joint ? f.s : f.s - 1);
        else
            *lo = f.s + 1;
    }
    // Size of [lo, hi] (lanes, within 0..P-1) inside the arc [a, a + len) mod P.
    int overlap(int lo, int hi, int a, int len) const {
        if (lo > hi) return 0;
        auto lin = [&](int b0, int b1) {
            return std::max(0, std::min(hi, b1 - 1) - std::max(lo, b0) + 1);
        };
        int c = lin(a, std::min(a + len, P));
        if (a + len > P) c += lin(0, a + len - P);
        return c;
    }
};

// The byte-hops of segment g of a batch of H lines: in (every needed pixel
// of both images to the nearest kind that needs it, one hop on to the
// other) and out (each map pixel from the nearer kind).
void segment_hops(const Routes& r, int H, int g, int64_t* hops, int64_t* ohops) {
    const int W = seg_width(r.fp, g), X0 = g * r.P;
    for (int y = 0; y < H; ++y)
        for (int x = 0; x < W; ++x) {
            const int X = X0 + x;
            for (int img = 0; img < 2; ++img) {
                int best = INT_MAX, cnt = 0;
                for (int kind = 0; kind < r.kinds; ++kind) {
                    int lo, hi;
                    r.need(img, kind, &lo, &hi);
                    if (X < lo || X > hi) continue;
                    best = std::min(best, r.ring(r.pe_of(y, kind), x + r.soff(y)));
                    ++cnt;
                }
                if (cnt) *hops += best + (cnt - 1);
            }
            int ob = r.ring(r.pe_of(y, 0), x + r.ooff(y));
            if (r.kinds == 2) ob = std::min(ob, r.ring(r.pe_of(y, 1), x + r.ooff(y)));
            *ohops += ob;
        }
}

// The bytes of segment g (a batch of H lines) that must enter the arc
// [a, a + len) of the ring: in (pixels its PEs need from lanes outside it)
// and out (map pixels of lines outside it whose output lanes are inside).
void arc_bytes(const Routes& r, int H, int g, int a, int len, int64_t* c_in, int64_t* c_out) {
    const ForwardPlan& f = r.f;
    const int W = seg_width(r.fp, g), X0 = g * r.P, P = r.P;
    auto inside = [&](int q) { return ((q - a) % P + P) % P < len; };
    for (int y = 0; y < H; ++y) {
        const int so = r.soff(y);
        bool kin[2] = {inside(r.pe_of(y, 0)), r.kinds == 2 && inside(r.pe_of(y, 1))};
        if (!kin[0] && !kin[1]) {
            *c_out += r.overlap(r.ooff(y), r.ooff(y) + W - 1, a, len);
            continue;
        }
        for (int img = 0; img < 2; ++img) {
            // union of the needed intervals of the kinds inside (as lanes)
            int lo = INT_MAX, hi = INT_MIN;
            for (int kind = 0; kind < r.kinds; ++kind) {
                if (!kin[kind]) continue;
                int l, h;
                r.need(img, kind, &l, &h);
                lo = std::min(lo, l);
                hi = std::max(hi, h);
            }
            // the kinds' intervals of one line meet or overlap (L) or
            // leave out X = s (R): count the hole separately
            lo = std::max(lo, X0) - X0;
            hi = std::min(hi, X0 + W - 1) - X0;
            if (lo > hi) continue;
            int hole = 0;
            if (f.bidir && img == 1 && kin[0] && kin[1]) {
                const int xs = f.s - X0;
                if (xs >= lo && xs <= hi) hole = inside(xs + so) ? 0 : 1;
            }
            *c_in += (hi - lo + 1) - r.overlap(lo + so, hi + so, a, len) - hole;
        }
    }
}

}  // namespace

int seg_width(const FramePlan& fp, int g) {
    return std::min(fp.P, fp.roi.w - g * fp.P);
}

void in_lanes(const ForwardPlan& f, int P, int g, int W, int kind, int* a, int* n) {
    int lo = g * P, hi = g * P + W - 1;
    if (f.bidir) {
        if (kind == 0)
            hi = std::min(hi, f.s);
        else
            lo = std::max(lo, f.s + 1);
    }
    *a = std::max(0, lo - g * P);
    *n = std::max(0, hi - lo + 1);
    if (*n == 0) *a = 0;
}

// The lines fill the ring (and a segment holds at most half of it): the
// routes take the shorter way round; else the lines sit centred on the
// segment and every route is direct, or the rows are skewed (plan_skew).
void plan_relayout(FramePlan& fp) {
    Relayout& rl = fp.rl;
    const int P = fp.P, span = fp.span();
    const bool bidir = fp.f.bidir;
    const int W0 = seg_width(fp, 0);
    rl.modular =
        P % 2 == 0 && span * fp.lpb == P && span * fp.hbmax == P && fp.nseg == 1 && W0 <= P / 2;
    if (rl.modular) {
        rl.base = 0;
        if (bidir) {
            rl.ur = (P / 2 + 1) / 2;
            rl.ul = P / 2 - rl.ur;
        } else {
            rl.ur = (P + 1) / 2;
            rl.ul = P - rl.ur;
        }
        // output displacements sigma = sender - receiver, one per class mod P
        rl.our = P / 2;  // sigma = our_min .. our_min + step*(n-1): stored as min and count
        rl.oul = 0;
        return;
    }
    const int reg = span * fp.hbmax;
    rl.base = (W0 - reg) >= 0 ? (W0 - reg) / 2 : -((reg - W0 + 1) / 2);
    int hr = -1, hl = 0;
    for (int g = 0; g < fp.nseg; ++g)
        for_each_receiver(fp, g, [&](int kind, int a, int n) {
            const int umin = rl.base + kind, umax = rl.base + span * (fp.hbmax - 1) + kind;
            hr = std::max(hr, umax - a);
            hl = std::max(hl, a + n - 1 - umin);
        });
    if (bidir) {
        rl.ur = hr >= 0 ? hr / 2 + 1 : 0;
        rl.ul = hl > 0 ? (hl + 1) / 2 : 0;
    } else {
        rl.ur = hr + 1;
        rl.ul = hl;
    }
    plan_skew(fp, span);
}

void out_displacements(const FramePlan& fp, int g, int* smin, int* smax) {
    const int W = seg_width(fp, g);
    const int span = fp.span();
    *smin = INT_MAX;
    *smax = INT_MIN;
    if (fp.rl.skew) {
        *smin = fp.rl.smin;
        *smax = fp.rl.smax;
    } else if (fp.rl.modular) {
        // one displacement per class mod P (and of one parity in bidir mode)
        if (span == 2) {
            *smin = -fp.P / 2 + 1;
            if (*smin % 2 != 0) ++*smin;  // the items' displacements are even (BP = 0)
            *smax = *smin + fp.P - 2;
        } else {
            *smin = -fp.P / 2 + 1;
            *smax = fp.P / 2;
        }
    } else {
        for (int y = 0; y < fp.hbmax; ++y)
            for (int x = 0; x < W; ++x) {
                const int X = g * fp.P + x;
                const int pos = fp.rl.base + span * y + (span == 2 ? (X & 1) : 0);
                *smin = std::min(*smin, pos - x);
                *smax = std::max(*smax, pos - x);
            }
    }
}

}  // namespace detail

void relayout_bound(const FramePlan& fp, int64_t* in, int64_t* out, int64_t* hop_in,
                    int64_t* hop_out) {
    const detail::Routes r(fp);
    const int P = fp.P;
    // Arc endpoints on a grid of at most 64 points per ring (any arc gives a
    // valid bound; the grid keeps the planner fast).
    const int step = std::max(1, P / 64);
    int64_t tin = 0, tout = 0, hin = 0, hout = 0;
    for (const Batch& b : fp.batches) {
        const int H = b.lines;
        for (int g = 0; g < fp.nseg; ++g) {
            int64_t hops = 0, ohops = 0;
            detail::segment_hops(r, H, g, &hops, &ohops);
            int64_t cut = 0, ocut = 0;
            for (int a = 0; a < P; a += step)
                for (int len = step; len < P; len += step) {
                    int64_t c_in = 0, c_out = 0;
                    detail::arc_bytes(r, H, g, a, len, &c_in, &c_out);
                    cut = std::max(cut, c_in);
                    ocut = std::max(ocut, c_out);
                }
            // census frames: every needed pixel comes with its code (a second
            // pair of rows over the same routes), twice the bytes in
            const int per = fp.f.census > 0 ? 2 : 1;
            hops *= per;
            cut *= per;
            const int64_t hb_in = (hops + P - 1) / P, hb_out = (ohops + P - 1) / P;
            tin += std::max(hb_in, cut);
            tout += std::max(hb_out, ocut);
            hin += hb_in;
            hout += hb_out;
        }
    }
    if (in) *in = tin;
    if (out) *out = tout;
    if (hop_in) *hop_in = hin;
    if (hop_out) *hop_out = hout;
}

}  // namespace imap::firmware
