// The re-layout's geometry (docs/firmware.md, section 5), from a frame
// plan's batches, segments and line placement: which lanes each kind
// receives, where the lines sit on the ring (around it, centred on the
// segment, or skewed rows), the rounds of the input and output sweeps and
// the output displacements, and the lower bound of the re-layout's
// cycles: ring and memory instructions (relayout_bound).
#include <algorithm>
#include <cstdlib>
#include <vector>

#include "plan_internal.hpp"

namespace imap::firmware {

namespace detail {

void arc_pixels(int P, int lo, int hi, int off, int a, int len,
                std::vector<std::pair<int, int>>* iv) {
    // x = a - off + t + k P, t in [0, len), for every k that meets [lo, hi]
    const int x0 = a - off;
    for (int k = floor_div(lo - x0 - len + 1, P); k <= floor_div(hi - x0, P); ++k) {
        const int b0 = std::max(lo, x0 + k * P), b1 = std::min(hi, x0 + k * P + len - 1);
        if (b0 <= b1) iv->push_back({b0, b1});
    }
}

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
// The shorter way round for a displacement d: d mod P in (-P/2, P/2].
int fold(int d, int P) {
    int r = ((d % P) + P) % P;
    return r > P / 2 ? r - P : r;
}

// CP cycles a video line costs beside its vin or vout (relayout.inc,
// LINES4): where up to 8 lines or more may come, 2 caddi a line and the
// loop's 3 cycles a turn of four (rounded up to 3 a line); else 3 caddi and
// the taken loop's 2.
int line_cp(int lines) {
    return lines >= 8 ? 3 : 5;
}

// The stores of n skewed rounds of both kinds (relayout.inc, RSK_RECVG):
// two per kind and round, and one mask block (mif, melse, mend) per group
// of four fused rounds.
int64_t store_cycles(int64_t n) {
    return 4 * n + 3 * ((n + 3) / 4);
}

// The planner's estimate of the direct routes' input rounds (one segment):
// 2u and 2u + 1 hops with two stores (44 and 49 cycles; bidir) or u + 1
// hops with one (27; single).
int64_t direct_rounds(const Relayout& rl, bool bidir, int rh) {
    int64_t c = 0;
    if (bidir) {
        for (int u = 0; u < rl.ur; ++u) c += 44 + 2 * (2 * u + 2) * rh;
        for (int u = 0; u < rl.ul; ++u) c += 49 + 2 * (2 * u + 3) * rh;
    } else {
        for (int u = 0; u < rl.ur + rl.ul; ++u) c += 27 + 2 * (u + 1) * rh;
    }
    return c;
}

// Windowed rows (docs/firmware.md, section 5; bidir): the kind copies'
// skewed rows of the whole line, window by window, pixel x of copy k of line
// y at unrolled lane x + (k ? skb : 0) + wi + span y. Round d (over the
// whole line, max(n0, n1) of them) moves pixel base - d to kind 0 and
// base + 1 - skb - d to kind 1 of every line, d - wi hops (mod P, the
// shorter way round); wi (skew_in) centres them. The lines keep the direct
// placement (base), so the output's direct routes are unchanged. Taken
// where both images' rows fit the memory and the estimate of the input
// (video rows and rounds) is below `limit` (< 0: the direct routes').
// Returns the estimate taken, or -1.
int64_t plan_windows(FramePlan& fp, int span, int mem, const isa::CostTable& costs,
                     int64_t limit = -1) {
    Relayout& rl = fp.rl;
    const ForwardPlan& f = fp.f;
    if (!f.bidir || f.census > 0 || f.agg > 0 || fp.spare || f.tiny || fp.rows_allowed < 3)
        return -1;
    const int P = fp.P, H = fp.hbmax, N = f.N;
    if (rl.base < 0 || rl.base + span * H > P) return -1;
    int a[2], n[2];
    for (int k = 0; k < 2; ++k) in_lanes(f, P, 0, N, k, &a[k], &n[k]);
    if (n[0] == 0 || n[1] == 0) return -1;
    const int skb = a[0] + 1 - a[1];
    const int nmax = std::max(n[0], n[1]);
    // pixel displacements: d = base - x for kind 0's pixel x
    const int d0 = rl.base - a[0] - (nmax - 1), d1 = rl.base - a[0];
    // the estimate (relayout.inc): a video row two vin and its CP cycles
    // (line_cp), about 10 more per window; a round 4 cycles of sending, its
    // stores (store_cycles), 2 |d - wi mod P| of shifts; the direct routes'
    // rounds per segment as plan_skew counts them
    const int vl = costs.video_line, rh = costs.ring_hop;
    if (limit < 0) {
        limit = fp.nseg * (int64_t(H) * (2 * vl + line_cp(H)) + direct_rounds(rl, true, rh));
    }
    struct Pick {
        int wi, wlo[2], whi[2], rc, wsize;
    } best{};
    int64_t best_e = -1;
    const int centre = (d0 + d1) / 2;
    for (int wi = centre - P / 2; wi < centre + P / 2; ++wi) {
        Pick c{};
        c.wi = wi;
        const int off[2] = {wi, skb + wi};
        for (int k = 0; k < 2; ++k) {
            c.wlo[k] = floor_div(a[k] + off[k], P);
            c.whi[k] = floor_div(a[k] + n[k] - 1 + off[k] + span * (H - 1), P);
        }
        // row (q, t) at q - P t + rc; the senders read rows lane + (d - wi) -
        // base + rc
        const int e = a[0] + wi;
        c.rc = std::max({0, P * std::max(c.whi[0], c.whi[1]), e + nmax - 1});
        const int top = std::max(span * H - 1 - P * std::min(c.wlo[0], c.wlo[1]), P - 1 - e) + c.rc;
        c.wsize = top + 1;
        if (f.costl + 2 * c.wsize > mem) continue;
        int64_t est = 0;
        for (int k = 0; k < 2; ++k)
            est += int64_t(c.whi[k] - c.wlo[k] + 1) * (10 + H * (2 * vl + line_cp(H)));
        est += store_cycles(d1 - d0 + 1);
        for (int d = d0; d <= d1; ++d) est += 4 + 2 * std::abs(fold(d - wi, P)) * rh;
        if (best_e < 0 || est < best_e) {
            best_e = est;
            best = c;
        }
    }
    if (best_e < 0 || best_e >= limit) return -1;
    rl.windows = true;
    rl.copies = true;
    rl.skb = skb;
    rl.skew_in = best.wi;
    rl.dmin = d0 - best.wi;
    rl.dmax = d1 - best.wi;
    for (int k = 0; k < 2; ++k) {
        rl.wlo[k] = best.wlo[k];
        rl.whi[k] = best.whi[k];
    }
    rl.wrc = best.rc;
    rl.wsize = best.wsize;
    return best_e;
}

// Windowed output rows (docs/firmware.md, section 5): every line's map
// pixels go out in one set of rounds over the whole line, sigma = base -
// skew_out + kind - x the same on every line, sigma mod P hops; each
// receiver stores every round at its own slot (no mask), so a round costs a
// load, the shifts and a store. skew_out is picked for the least estimate
// (hops against windows, each a vout per line). The lines may sit anywhere
// on the ring (the slots follow from the receiver's lane). Taken where the
// rows fit beside the map and the estimate is below that of the output the
// plan has (skewed rows or direct routes).
void plan_out_windows(FramePlan& fp, int span, int mem, const isa::CostTable& costs) {
    Relayout& rl = fp.rl;
    const ForwardPlan& f = fp.f;
    if (f.tiny || fp.rows_allowed < 3) return;
    const int P = fp.P, H = fp.hbmax, N = f.N, B = rl.base;
    if (span == 2 && P % 2 != 0) return;
    // rounds: x0 = 0, step, ... (bidir: both kinds' pixels in one round; the
    // spare layout: one line PE per span of 2, every pixel)
    const int step = f.bidir ? 2 : 1;
    const int nr = (N + step - 1) / step;
    // the estimate (relayout.inc, ROUT_WIN): a round an ldx, its hops and
    // an stx (4 cycles); a window about 7 CP cycles and a vout and its CP
    // cycles (line_cp) per line
    const int vl = costs.video_line, rh = costs.ring_hop;
    auto windows = [&](int sko) {
        return floor_div(N - 1 + sko + span * (H - 1), P) - floor_div(sko, P) + 1;
    };
    auto estimate = [&](int sko) {
        int64_t h = 0;
        for (int i = 0; i < nr; ++i) h += std::abs(fold(B - sko - step * i, P));
        return int64_t(nr) * 4 + h * rh + int64_t(windows(sko)) * (7 + H * (vl + line_cp(H)));
    };
    // skew_out for the least estimate: hops against windows
    const int centre = B - step * (nr - 1) / 2;
    int sko = centre;
    int64_t win = estimate(centre);
    for (int c = centre - P / 2; c < centre + P / 2; ++c)
        if (const int64_t e = estimate(c); e < win) {
            win = e;
            sko = c;
        }
    const int smax = B - sko, smin = smax - step * (nr - 1);
    const int owlo = floor_div(sko, P), owhi = floor_div(N - 1 + sko + span * (H - 1), P);
    const int per = P / span;  // slots per window
    // The receivers' slots, and where the rows go (after the constant
    // block, else past the map). Where they do not fit and there is one
    // window whose rows' lanes use fewer than 256 slots, the receivers keep
    // the slot's low byte (relayout.inc, SKOWB): every lane writes within
    // 256 + adv bytes and the rows' lanes at their exact slots, at no cost.
    // adv: how far a receiver's slot advances over the rounds (the spare
    // layout's slot is ceil(u / 2): one more).
    const int adv = (nr - 1) * step / span + (fp.spare ? 1 : 0);
    int rlo = 0, osize = 0, out = 0;
    auto place = [&](int lo, int hi, bool wrap) {
        rlo = std::min(floor_div(lo + smin - B, span), -per * owhi);
        const int rhi = std::max(floor_div(hi + smin - B, span) + adv, H - 1 - per * owlo);
        osize = rhi - rlo + 1;
        if (wrap) {
            if (osize > 256) return false;
            osize = 256 + adv;
        }
        out = f.kbs;
        if (out < f.map + N && out + osize > f.map) out = f.map + N;
        return out + osize <= mem;
    };
    bool wrap = false;
    if (!place(0, P - 1, false)) {
        const int lo = sko - P * owlo;
        if (owlo != owhi || !place(lo, lo + N - 1 + span * (H - 1), true)) return;
        wrap = true;
    }
    // the output the plan has, per segment: the skewed rows' rounds (an
    // ldx, its hops, and where the receivers step their row's byte,
    // relayout.inc OSKB, a compare, the masked stx and the step: 8 cycles,
    // an andi more below 256 x span PEs; else the 16-bit row and its
    // compare, 13, 17 with wrapped rows; a second vout per wrapped line),
    // the direct routes' about 18 cycles and their hops. (Where the rows
    // are strided, out_row_stride, the andi is gone but still counted:
    // counted at 8 the skewed output was taken on 32x32 at 64 PEs where
    // the windows are 36 cycles faster; the two estimates are not that
    // exact, and the one cycle kept leaves the picks as they were.)
    const bool oskb = !fp.spare && index_steps_a_byte(P, false, span);
    int64_t now = 0;
    for (int g = 0; g < fp.nseg; ++g) {
        int s0, s1;
        out_displacements(fp, g, &s0, &s1);
        const int fixed = rl.skew ? (oskb ? (P < 256 * span ? 9 : 8) : rl.wrap ? 17 : 13) : 18;
        for (int s = s0; s <= s1; s += step) now += fixed + std::abs(s) * rh;
        now += 7 + H * (vl + line_cp(H));
        if (rl.skew && rl.wrap) now += 7 + std::max(0, H - rl.ywo) * (vl + line_cp(H - rl.ywo));
    }
    if (win >= now) return;
    rl.owindows = true;
    rl.skew_out = sko;
    rl.smin = smin;
    rl.smax = smax;
    rl.owlo = owlo;
    rl.owhi = owhi;
    rl.orc = -rlo;
    rl.osize = osize;
    rl.owrap = wrap;
}

// One-segment frames: the windowed rows (centred by skew_in, no wrapped
// rows to merge) where their estimate is below the skewed rows' the plan
// has, else the direct routes' (`direct`: the plan before plan_skew).
void weigh_windows(FramePlan& fp, const Relayout& direct, int span, int mem,
                   const isa::CostTable& costs) {
    if (fp.rl.windows) return;
    FramePlan alt = fp;
    alt.rl = direct;
    if (plan_windows(alt, span, mem, costs, fp.rl.skew ? fp.rl.skew_estimate : -1) >= 0)
        fp.rl = alt.rl;
}

void plan_skew(FramePlan& fp, int span, int mem, const isa::CostTable& costs,
               bool allow_copies = true) {
    Relayout& rl = fp.rl;
    if (fp.nseg > 1) {
        plan_windows(fp, span, mem, costs);
        plan_out_windows(fp, span, mem, costs);
        return;
    }
    if (fp.rows_allowed < 1) return;
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
    // Kind copies (bidir, no census, no window, both images' rows twice in
    // memory): kind 1's copy shifted by skb aligns its pixels' rounds with
    // kind 0's, both kinds served in every round.
    int a[2] = {0, 0}, n[2] = {0, 0};
    for_each_receiver(fp, 0, [&](int kind, int a0, int n0) {
        a[kind] = a0;
        n[kind] = n0;
    });
    const int skb = a[0] + 1 - a[1];
    // RowLayout::Fastest (3) weighs the placements by the estimate below;
    // Skewed (1) and Wrapped (2) take the skewed rows wherever they apply,
    // as the spare PEs' layout does.
    const bool weigh = fp.rows_allowed >= 3 && !fp.spare;
    bool copies = allow_copies && weigh && fp.f.bidir && fp.f.census == 0 && fp.f.agg == 0 &&
                  !fp.spare && n[0] > 0 && n[1] > 0 && skb <= 0 && fp.f.costl + 4 * H <= mem &&
                  std::max(n[0], n[1]) < hi - lo + 1;
    const int lo2 = -(a[0] + std::max(n[0], n[1]) - 1), hi2 = -a[0];
    const int base = std::max(0, -(((copies ? lo2 : lo) + (copies ? hi2 : hi)) / 2));
    // output: kind - x over the map pixels (pixel x leaves the PE of parity x & 1)
    const int olo = fp.f.bidir ? -((W - 1) - ((W - 1) & 1)) : -(W - 1), ohi = 0;
    const int skew_out = std::max(0, base + (olo + ohi) / 2);
    const int rows = span * (H - 1) + W;  // lanes spanned by the skewed rows
    if (span * H > P || W > P || rows > 2 * P || skew_out + rows > 2 * P) return;
    // The lines' PEs past the ring's end continue at PE 0 (DP_SETUP takes
    // positions mod P), rows past it at lane 0 (wrap); not with the census's
    // codes on skewed rows, nor the spare PEs' layout.
    const bool wrap = rows > P || skew_out + rows > P;
    if ((wrap || base + span * H > P) && (fp.f.census > 0 || fp.spare || fp.rows_allowed < 2))
        return;
    // The planner's estimate of each placement's input (relayout.inc; the
    // cost table's video_line and ring_hop, one cycle for the rest): the
    // skewed rounds as rounds_cost counts them; a video row costs its two
    // vin and its CP cycles (line_cp), a row past the ring's end two vin,
    // 10 cycles of merging and its CP cycles more; the direct routes'
    // rounds as direct_rounds counts them. (Census frames keep older hand
    // counts of the rounds: a skewed round sends in about 14 cycles, 21
    // around the ring, and stores in 15.)
    const int vl = costs.video_line, rh = costs.ring_hop;
    auto wraps = [&](int off) {  // lines whose row from lane off + span y passes P - 1
        int c = 0;
        for (int y = 0; y < H; ++y) c += ((off + span * y) % P + P) % P + W > P;
        return c;
    };
    // a wrapped row's second piece: one more line transfer and 10 CP cycles
    auto wrapped_rows = [&](int64_t n) {
        return n * (2 * vl + 10 + line_cp(int(std::min<int64_t>(n, H))));
    };
    auto rows_cost = [&](int copies_n, int wrapped) {
        return int64_t(copies_n) * H * (2 * vl + line_cp(H)) + wrapped_rows(wrapped);
    };
    // both kinds' copies: kind 1's rows start skb lanes on
    auto copies_rows_cost = [&] { return rows_cost(2, wraps(0)) + wrapped_rows(wraps(skb)); };
    // The rounds d0 .. d1 as relayout.inc runs them (RSK_SEND, RSK_SENDP,
    // RSK_RECV, RSK_RECVG): the kind copies' senders 5 cycles (6 with P below
    // 256, 10 where P is not a power of two and the rows are taken mod P);
    // the single copy's, where its row index steps a byte (plan_prelude.cpp,
    // SKNC 3), in bidir packed (one register a round, below), in single
    // mode two loads, an increment and below 256 PEs a mask (none where the
    // rows are strided, row_stride), else 8 (12
    // around the ring); the kind copies' stores fused four rounds a group
    // (store_cycles), else 7 a round (two, unmasked, in single mode); the
    // shifts, two registers of |d| hops.
    const bool pow2 = index_steps_a_byte(P, true, span);
    const bool one_steps = index_steps_a_byte(P, false, span);
    // one copy's rows rys bytes apart (place_rows): its index steps unmasked
    const bool strided = row_stride(fp, mem) > 1;
    auto rounds_cost = [&](bool cp, int d0, int d1) {
        const int64_t n = d1 - d0 + 1;
        int64_t c = 0;
        if (fp.f.census > 0) {
            for (int d = d0; d <= d1; ++d) c += (wrap ? 21 : 14) + 15 + 2 * std::abs(d) * rh;
            return c;
        }
        if (!cp && one_steps && fp.f.bidir) {
            // packed rounds (RPK_ROUNDG, RPK_RECVG): one kind a round, its
            // index add, one load and the one-hop shift; the first and last
            // rounds load and shift R too and store a third byte
            c += 2 * n + 2 + 3 * ((n + 3) / 4) + 4 * n + (n / 2) * (P < 512 && !strided ? 4 : 2);
            for (int d = d0; d <= d1; ++d) c += std::abs(d) * rh;
            return c + (std::abs(d0) + std::abs(d1)) * rh;
        }
        if (!fp.f.bidir)
            c += 2 * n;
        else if (cp)
            c += store_cycles(n);
        else
            c += 7 * n;
        if (cp)
            c += n * (pow2 ? (P < 256 ? 6 : 5) : 10);
        else if (one_steps)
            c += n * (P < 256 && !strided ? 6 : 5);
        else
            c += n * (wrap ? 12 : 8);
        for (int d = d0; d <= d1; ++d) c += 2 * std::abs(d) * rh;
        return c;
    };
    // The placements are weighed over the frame: every batch runs all the
    // rounds, its own lines' rows (a short last batch few).
    int64_t nb = 0, lines_all = 0, wrap0_all = 0, wrapb_all = 0;
    for (const Batch& b : fp.batches) {
        ++nb;
        lines_all += b.lines;
        for (int y = 0; y < std::min(b.lines, H); ++y) {
            wrap0_all += (span * y) % P + W > P;
            wrapb_all += ((skb + span * y) % P + P) % P + W > P;
        }
    }
    auto frame_rows = [&](int copies_n, int64_t wrapped) {
        return int64_t(copies_n) * lines_all * (2 * vl + line_cp(H)) + wrapped_rows(wrapped);
    };
    const int64_t one_rows = frame_rows(1, wrap ? wrap0_all : 0);
    const int64_t one = nb * rounds_cost(false, base + lo, base + hi) + one_rows;
    const int64_t direct = frame_rows(1, 0) + nb * direct_rounds(rl, fp.f.bidir, rh);
    if (copies) {
        const int64_t two_rows = nb * rounds_cost(true, base + lo2, base + hi2) +
                                 frame_rows(2, wrap0_all) + wrapped_rows(wrapb_all);
        // the base above was centred for the copies; without them the
        // single copy's rounds are centred on their own range
        const int b1 = std::max(0, -((lo + hi) / 2));
        const int64_t one_c = nb * rounds_cost(false, b1 + lo, b1 + hi) + one_rows;
        copies = two_rows < one_c && two_rows < direct;
        if (!copies) {
            // plan again without the copies (their base and output offset)
            plan_skew(fp, span, mem, costs, false);
            return;
        }
        lo = lo2;
        hi = hi2;
    } else if (weigh && direct <= one) {
        return;  // the direct routes are cheaper (few lines, a slow video line)
    }
    rl.modular = false;
    rl.skew = true;
    rl.wrap = wrap;
    rl.copies = copies;
    rl.skb = copies ? skb : 0;
    // the first line whose row passes lane P - 1: input, output, and kind
    // 1's copy (its lines below ybb start past the ring's end, at lane
    // skb + P + span * y, the others at skb + span * y)
    auto first_past = [&](int lane0) {  // first y with lane0 + span * y + W > P
        const int r = P - W - lane0;
        return r < 0 ? 0 : r / span + 1;
    };
    rl.ywi = first_past(0);
    rl.ywo = first_past(skew_out);
    rl.ybb = copies ? std::min(H, (1 - skb) / span) : 0;
    rl.ywb1 = copies ? first_past(skb + P) : 0;
    rl.ywb2 = copies ? first_past(skb) : 0;
    rl.base = base;
    rl.skew_in = 0;
    rl.skew_out = skew_out;
    rl.dmin = base + lo;
    rl.dmax = base + hi;
    // the estimate the windowed rows are weighed against (weigh_windows)
    rl.skew_estimate = (copies ? copies_rows_cost() : rows_cost(1, wrap ? wraps(0) : 0)) +
                       rounds_cost(copies, rl.dmin, rl.dmax);
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
    int soff(int y) const { return fp.rl.skew || fp.rl.windows ? fp.rl.skew_in + span * y : 0; }
    // the copies of the video rows: lane offsets of line y's pixel 0 (kind
    // copies: kind 1's copy skb lanes further)
    int ncopies() const { return fp.rl.copies ? 2 : 1; }
    int coff(int y, int c) const { return c == 0 ? soff(y) : fp.rl.skb + soff(y); }
    // How many pixels of [lo, hi] have a copy in the arc.
    int inside_count(int y, int lo, int hi, int a, int len) const {
        if (lo > hi) return 0;
        std::vector<std::pair<int, int>> iv[2];
        for (int c = 0; c < ncopies(); ++c) arc_pixels(P, lo, hi, coff(y, c), a, len, &iv[c]);
        int n = 0;
        for (int c = 0; c < ncopies(); ++c)
            for (const auto& [b0, b1] : iv[c]) n += b1 - b0 + 1;
        if (ncopies() == 2)
            for (const auto& [p0, p1] : iv[0])
                for (const auto& [q0, q1] : iv[1])
                    n -= std::max(0, std::min(p1, q1) - std::max(p0, q0) + 1);
        return n;
    }
    // Shortest ring distance from any copy of pixel x of line y to PE pe.
    int from_copies(int y, int x, int pe) const {
        int best = INT_MAX;
        for (int c = 0; c < ncopies(); ++c) best = std::min(best, ring(pe, x + coff(y, c)));
        return best;
    }
    int ooff(int y) const { return fp.rl.skew || fp.rl.owindows ? fp.rl.skew_out + span * y : 0; }
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
    // Size of [lo, hi] (lanes, taken mod P: wrapped rows) inside the arc
    // [a, a + len) mod P.
    int overlap(int lo, int hi, int a, int len) const {
        if (lo > hi) return 0;
        if (lo >= P) return overlap(lo - P, hi - P, a, len);
        if (hi >= P) return overlap(lo, P - 1, a, len) + overlap(P, hi, a, len);
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
                    best = std::min(best, r.from_copies(y, x, r.pe_of(y, kind)));
                    ++cnt;
                }
                if (cnt) *hops += best + (cnt - 1);
            }
            int ob = r.ring(r.pe_of(y, 0), x + r.ooff(y));
            if (r.kinds == 2) ob = std::min(ob, r.ring(r.pe_of(y, 1), x + r.ooff(y)));
            *ohops += ob;
        }
}

// The memory instructions of segment g of a batch of H lines: a byte moves
// between PEs only over the ring, so it leaves its sender's memory by a load
// and enters the receiver's by a store (one byte per PE per instruction).
// In: every PE stores each byte it needs that no video row put on its own
// lane; the lane holding a needed byte loads it once (a byte with two copies
// may be loaded at either: those count toward the loads spread over all P
// lanes). Out: the lane a map pixel leaves through stores it unless it is one
// of the line's PEs; the line's PEs load its pixels between them.
// Segments g0 .. g1 together (the windowed rows' rounds move the whole
// line's pixels; the output per segment).
void segment_mem(const Routes& r, int H, int g0, int g1, int64_t* in, int64_t* out) {
    const int P = r.P;
    std::vector<int> recv(P, 0), load(P, 0), ostore(P, 0);
    int64_t remote = 0, oload = 0;
    for (int y = 0; y < H; ++y) {
        int pes[2] = {r.pe_of(y, 0), r.pe_of(y, r.kinds - 1)};
        int oremote = 0;
        for (int g = g0; g <= g1; ++g) {
            const int W = seg_width(r.fp, g), X0 = g * r.P;
            for (int x = 0; x < W; ++x) {
                const int X = X0 + x;
                int lane[2] = {0, 0};
                for (int c = 0; c < r.ncopies(); ++c) lane[c] = ((x + r.coff(y, c)) % P + P) % P;
                auto local = [&](int pe) {
                    for (int c = 0; c < r.ncopies(); ++c)
                        if (lane[c] == pe) return true;
                    return false;
                };
                for (int img = 0; img < 2; ++img) {
                    bool far = false;
                    for (int kind = 0; kind < r.kinds; ++kind) {
                        int lo, hi;
                        r.need(img, kind, &lo, &hi);
                        if (X < lo || X > hi || local(pes[kind])) continue;
                        ++recv[pes[kind]];
                        far = true;
                    }
                    if (!far) continue;
                    ++remote;
                    if (r.ncopies() == 1) ++load[lane[0]];
                }
                const int ol = ((x + r.ooff(y)) % P + P) % P;
                if (ol != pes[0] && ol != pes[1]) {
                    ++ostore[ol];
                    ++oremote;
                }
            }
        }
        oload = std::max<int64_t>(oload, (oremote + r.kinds - 1) / r.kinds);
    }
    const int64_t loads =
        std::max<int64_t>(*std::max_element(load.begin(), load.end()), (remote + P - 1) / P);
    *in = loads + *std::max_element(recv.begin(), recv.end());
    *out = oload + *std::max_element(ostore.begin(), ostore.end());
}

// The bytes of segment g (a batch of H lines) that must enter the arc
// [a, a + len) of the ring: in (pixels its PEs need from lanes outside it)
// and out (map pixels of lines outside it whose output lanes are inside).
void arc_bytes(const Routes& r, int H, int g, int a, int len, int64_t* c_in, int64_t* c_out) {
    const ForwardPlan& f = r.f;
    const int W = seg_width(r.fp, g), X0 = g * r.P, P = r.P;
    auto inside = [&](int q) { return ((q - a) % P + P) % P < len; };
    for (int y = 0; y < H; ++y) {
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
                if (xs >= lo && xs <= hi) hole = r.inside_count(y, xs, xs, a, len) > 0 ? 0 : 1;
            }
            *c_in += (hi - lo + 1) - r.inside_count(y, lo, hi, a, len) - hole;
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
void plan_relayout(FramePlan& fp, int mem, const isa::CostTable& costs) {
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
        const Relayout direct = rl;
        plan_skew(fp, span, mem, costs);
        weigh_windows(fp, direct, span, mem, costs);
        plan_out_windows(fp, span, mem, costs);
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
    const Relayout direct = rl;
    plan_skew(fp, span, mem, costs);
    if (fp.nseg == 1) {
        weigh_windows(fp, direct, span, mem, costs);
        plan_out_windows(fp, span, mem, costs);
    }
}

void out_displacements(const FramePlan& fp, int g, int* smin, int* smax) {
    const int W = seg_width(fp, g);
    const int span = fp.span();
    *smin = INT_MAX;
    *smax = INT_MIN;
    if (fp.rl.skew || fp.rl.owindows) {
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

void relayout_bound(FramePlan& fp, const isa::CostTable& costs) {
    const detail::Routes r(fp);
    const int P = fp.P;
    // Arc endpoints on a grid of at most 64 points per ring (any arc gives a
    // valid bound; the grid keeps the planner fast).
    const int step = std::max(1, P / 64);
    Relayout& rl = fp.rl;
    rl.ring_bound_in = rl.ring_bound_out = rl.hop_bound_in = rl.hop_bound_out = 0;
    rl.mem_bound_in = rl.mem_bound_out = 0;
    for (const Batch& b : fp.batches) {
        const int H = b.lines;
        // The windowed rows move the whole line in one set of rounds (in,
        // out): their cut and memory bounds over all segments at once (the
        // arc's bytes summed, then the maximum); the direct routes run
        // segment by segment.
        const int ng = fp.nseg;
        std::vector<int64_t> arc_in, arc_out;
        int64_t hops_all = 0, ohops_all = 0, m_in_all = 0, m_out_all = 0;
        for (int g = 0; g < ng; ++g) {
            int64_t hops = 0, ohops = 0;
            detail::segment_hops(r, H, g, &hops, &ohops);
            int64_t cut = 0, ocut = 0;
            size_t ai = 0;
            for (int a = 0; a < P; a += step)
                for (int len = step; len < P; len += step, ++ai) {
                    int64_t c_in = 0, c_out = 0;
                    detail::arc_bytes(r, H, g, a, len, &c_in, &c_out);
                    cut = std::max(cut, c_in);
                    ocut = std::max(ocut, c_out);
                    if (ai == arc_in.size()) {
                        arc_in.push_back(0);
                        arc_out.push_back(0);
                    }
                    arc_in[ai] += c_in;
                    arc_out[ai] += c_out;
                }
            // census frames: every needed pixel comes with its code (a second
            // pair of rows over the same routes), twice the bytes in; the
            // memory instructions count the pixels only
            const int per = fp.f.census > 0 ? 2 : 1;
            hops *= per;
            cut *= per;
            const int64_t hb_in = (hops + P - 1) / P, hb_out = (ohops + P - 1) / P;
            if (!rl.windows) {
                rl.ring_bound_in += std::max(hb_in, cut) * costs.ring_hop;
                rl.hop_bound_in += hb_in * costs.ring_hop;
            }
            if (!rl.owindows) {
                rl.ring_bound_out += std::max(hb_out, ocut) * costs.ring_hop;
                rl.hop_bound_out += hb_out * costs.ring_hop;
            }
            hops_all += hops;
            ohops_all += ohops;
            int64_t m_in = 0, m_out = 0;
            detail::segment_mem(r, H, g, g, &m_in, &m_out);
            m_in_all += m_in;
            m_out_all += m_out;
        }
        auto most = [](const std::vector<int64_t>& v) {
            return v.empty() ? int64_t{0} : *std::max_element(v.begin(), v.end());
        };
        int64_t m_in = 0, m_out = 0;
        if (rl.windows || rl.owindows) detail::segment_mem(r, H, 0, ng - 1, &m_in, &m_out);
        if (rl.windows) {
            const int64_t hb_in = (hops_all + P - 1) / P;
            rl.ring_bound_in += std::max(hb_in, most(arc_in)) * costs.ring_hop;
            rl.hop_bound_in += hb_in * costs.ring_hop;
            m_in_all = m_in;
        }
        if (rl.owindows) {
            const int64_t hb_out = (ohops_all + P - 1) / P;
            rl.ring_bound_out += std::max(hb_out, most(arc_out)) * costs.ring_hop;
            rl.hop_bound_out += hb_out * costs.ring_hop;
            m_out_all = m_out;
        }
        rl.mem_bound_in += m_in_all * costs.mem;
        rl.mem_bound_out += m_out_all * costs.mem;
    }
    rl.bound_in = rl.ring_bound_in + rl.mem_bound_in;
    rl.bound_out = rl.ring_bound_out + rl.mem_bound_out;
}

}  // namespace imap::firmware
