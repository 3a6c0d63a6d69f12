// The forward plan (ForwardPlan) of one scanline length N, from the
// parameters and the machine: the level range of each kind at every column,
// the passes that compute them and their window sums, and the node's
// constants, after the checks of plan.cpp; its memory comes from
// plan_memory.cpp (fixed regions) and plan_pointers.cpp (pointer columns).
#include <algorithm>
#include <sstream>

#include "imap/golden/estimate.hpp"
#include "plan_internal.hpp"

namespace imap::firmware {

namespace detail {

namespace {

// The level range of each kind at every column (docs/firmware.md, section 1).
void column_ranges(const golden::Params& p, int N, ForwardPlan& f) {
    const int D = p.D;
    if (!f.bidir) {
        f.kinds = 1;
        f.K[0] = N;
        f.lo[0].assign(N + 1, 0);
        f.hi[0].resize(N + 1);
        for (int k = 0; k <= N; ++k) f.hi[0][k] = k == 0 ? D - 1 : std::min(D - 1, N - k);
        f.kmax = N;
        return;
    }
    f.kinds = 2;
    const int s = f.s, ds = f.ds;
    if (f.joint) {
        // SPEC A.9 joint (docs/firmware.md, section 10). Kind 0: A.3 over sites
        // 0..s, single mode's form cut at column s+1 (column k = site k-1).
        f.K[0] = s + 1;
        f.lo[0].assign(s + 2, 0);
        f.hi[0].resize(s + 2);
        for (int k = 0; k <= s + 1; ++k) f.hi[0][k] = k == 0 ? D - 1 : std::min(D - 1, N - k);
        // Kind 1: A.4 from (N-1, 0) down to site s, the bidir left wavefront's
        // mirrored form with the seed column at N and seed disparity 0
        // (column k = site N-1-k, level j' = D-1-j).
        f.K[1] = N - 1 - s;
        f.lo[1].resize(f.K[1] + 1);
        f.hi[1].assign(f.K[1] + 1, D - 1);
        for (int k = 0; k <= f.K[1]; ++k) f.lo[1][k] = std::max(0, D - 1 - k);
        f.kmax = std::max(f.K[0], f.K[1]);
        return;
    }
    // Left wavefront (kind 0): column k is site s-1-k, level mirrored j' = D-1-j.
    f.K[0] = s;
    f.lo[0].resize(s + 1);
    f.hi[0].assign(s + 1, D - 1);
    for (int k = 0; k <= s; ++k) {
        int lo = std::max(0, D - 1 - N + s - k);
        if (ds >= 0) lo = std::max(lo, D - 1 - ds - k);
        f.lo[0][k] = lo;
    }
    // Right wavefront (kind 1): column k is site s+k.
    f.K[1] = N - 1 - s;
    f.lo[1].resize(f.K[1] + 1);
    f.hi[1].resize(f.K[1] + 1);
    for (int k = 0; k <= f.K[1]; ++k) {
        f.lo[1][k] = std::max(0, (ds >= 0 ? ds : 0) - k);
        f.hi[1][k] = std::min(D - 1, N - 1 - s - k);
    }
    f.kmax = std::max(f.K[0], f.K[1]);
}

// Estimated cycles of the forward pass's parts (dp_forward.inc): a slot (the
// node and its share of the group loop), a pass's header and call, a mask
// switch between passes of different kinds, a split pass's late first slot.
constexpr int kSlotCycles = 30, kPassCycles = 14, kMaskCycles = 3, kSplitCycles = 12;

// The passes of every column with the kinds' slot shifts f.lsh: one shared
// pass where the kinds start at the same slot (and agree on D only); where
// they start apart and `split` allows, one split pass over both kinds'
// slots when the estimate favours it over a masked pass per kind; else one
// masked pass per kind. Returns the estimated cycles.
int64_t column_passes(ForwardPlan& f, bool split) {
    f.passes.clear();
    f.slots = 0;
    int64_t est = 0;
    auto pad_bit = [&](int p, int k) { return f.hi[p][k] == f.D - 1 ? 1 << p : 0; };
    // A pass of column k over slots lo .. hi of `kind` (-1: every kind).
    auto add_pass = [&](int k, int kind, int lo, int hi, bool donly, int pad) {
        ForwardPass ps;
        ps.k = k;
        ps.kind = kind;
        ps.jlo = lo;
        ps.n = hi - lo + 1;
        ps.donly = donly;
        ps.pad = pad;
        ps.bytes = ceil_div(ps.n, 4);
        f.passes.push_back(ps);
        f.slots += ps.n;
        est += kPassCycles + int64_t{kSlotCycles} * ps.n;
        return &f.passes.back();
    };
    for (int k = 1; k <= f.kmax; ++k) {
        int act[2], na = 0;
        for (int p = 0; p < f.kinds; ++p)
            if (k <= f.K[p]) act[na++] = p;
        auto donly = [&](int p) { return f.lo[p][k] < f.lo[p][k - 1]; };
        auto first = [&](int p) { return f.lo[p][k] + f.lsh[p]; };
        auto last = [&](int p) { return f.hi[p][k] + f.lsh[p]; };
        if (na == 1) {
            const int p = act[0];
            add_pass(k, f.kinds == 1 ? -1 : p, first(p), last(p), donly(p), pad_bit(p, k));
            continue;
        }
        const int pads = pad_bit(0, k) | pad_bit(1, k);
        const int top = std::max(last(0), last(1));
        if (first(0) == first(1) && donly(0) == donly(1)) {
            add_pass(k, -1, first(0), top, donly(0), pads);
            continue;
        }
        const int e = first(0) <= first(1) ? 0 : 1, l = 1 - e;
        const int64_t separate =
            2 * (kPassCycles + kMaskCycles) +
            int64_t{kSlotCycles} * (last(0) - first(0) + last(1) - first(1) + 2);
        const int64_t merged =
            kPassCycles + kSplitCycles + int64_t{kSlotCycles} * (top - first(e) + 1);
        if (split && first(e) < first(l) && merged < separate) {
            ForwardPass* ps = add_pass(k, -1, first(e), top, donly(e), pads);
            ps->split = first(l) - first(e);
            ps->late = l;
            ps->ldonly = donly(l);
            est += kSplitCycles;
            continue;
        }
        for (int i = 0; i < 2; ++i) {
            add_pass(k, i, first(i), last(i), donly(i), pad_bit(i, k));
            est += kMaskCycles;
        }
    }
    return est;
}

// The kinds' slot shift (f.lsh) for the least estimated forward cycles, in
// bidir and joint frames whose node reads nothing beside the line buffers (the census
// codes, the bt bounds and the window's copies are laid out for equal
// slots): shifting kind 1 by t > 0 (or kind 0 by -t) lines its first slots
// up against the other kind's, so the split passes cover both ranges at
// once where the kinds' level ranges are complementary (D near the width).
// The shift costs cost-plane and L' bytes; the 8-bit backtrack keeps slots
// below 256.
void choose_shift(ForwardPlan& f, bool eligible) {
    f.lsh[0] = f.lsh[1] = 0;
    int64_t best = column_passes(f, false);
    if (!eligible) return;
    int best_t = 0;
    bool best_split = false;
    for (int t = -(f.D - 1); t <= f.D - 1; ++t) {
        if (f.D + 1 + std::abs(t) > 255) continue;
        f.lsh[0] = std::max(0, -t);
        f.lsh[1] = std::max(0, t);
        const int64_t est = column_passes(f, true);
        if (est < best) {
            best = est;
            best_t = t;
            best_split = true;
        }
    }
    f.lsh[0] = std::max(0, -best_t);
    f.lsh[1] = std::max(0, best_t);
    column_passes(f, best_split);
}

// The window's sums (AGG_BODY): a pass updates the previous column's sum at
// the levels every kind of the pass computed there (a horizontal window
// only: the change is two pixel terms, the whole sum 2 agg + 1), and sums
// the others whole: the first column, the level a kind gains at the bottom,
// and in a shared pass the levels above a kind's previous top.
void window_segments(ForwardPlan& f) {
    std::vector<int> plo[2], phi[2];  // levels kind p computed in column k
    for (int p = 0; p < 2; ++p) {
        plo[p].assign(f.kmax + 2, INT_MAX);
        phi[p].assign(f.kmax + 2, INT_MIN);
    }
    for (const ForwardPass& ps : f.passes)
        for (int p = 0; p < f.kinds; ++p)
            if (runs_on(f, ps, p)) {
                plo[p][ps.k] = std::min(plo[p][ps.k], ps.jlo);
                phi[p][ps.k] = std::max(phi[p][ps.k], ps.jlo + ps.n - 1);
            }
    for (ForwardPass& ps : f.passes) {
        ps.rfull = ps.n;
        ps.rinc = 0;
        if (f.agg == 0 || ps.k == 1) continue;
        int lo = ps.jlo, hi = ps.jlo + ps.n - 1;
        for (int p = 0; p < f.kinds; ++p)
            if (runs_on(f, ps, p)) {
                lo = std::max(lo, plo[p][ps.k - 1]);
                hi = std::min(hi, phi[p][ps.k - 1]);
            }
        if (lo > hi) continue;
        ps.rfull = lo - ps.jlo;
        ps.rinc = hi - lo + 1;
    }
}

}  // namespace

ForwardPlan plan_forward_impl(const golden::Params& p, int N, const isa::MachineConfig& cfg,
                              bool tiny, bool census_ok, bool split) {
    golden::validate_for_width(p, N);
    check_options(p, census_ok);
    check_range(p);
    ForwardPlan f;
    f.N = N;
    f.D = p.D;
    f.joint = p.mode == golden::Mode::Joint;
    f.bidir = p.mode == golden::Mode::Bidir || f.joint;
    if (f.joint && tiny)
        throw FirmwareError(
            "firmware: --mode joint with the vote needs at least 3 lines per batch (6 PEs; "
            "the one-line-per-batch mode of 2 to 5 PEs does not keep the meeting level): have " +
            std::to_string(cfg.pes) + " PEs");
    if (f.bidir) {
        f.s = golden::resolve_seed_col(p, N);
        f.ds = p.seed_disp.free ? -1 : p.seed_disp.value;
    }
    column_ranges(p, N, f);
    choose_shift(f, split && f.bidir && !tiny && p.kc == 0 && p.dissim != golden::Dissim::Bt &&
                        p.agg_rx == 0 && p.agg_ry == 0);
    for (int i = 0; i < N; ++i) f.valid_states += golden::levels_at(i, N, p.D);

    const int64_t w = wm_max(p);
    f.xo = static_cast<int>(std::max<int64_t>(1, w - p.Wd - p.Wo + 1));
    f.xd = f.xo;
    f.xm = p.Wd + p.Wo + 1;
    f.kpp = (p.kb * p.gb - p.Wd - p.Wo) & 0xFFFF;

    place_regions(f, p, cfg);
    if (f.rows) window_segments(f);
    place_columns(f, cfg, tiny);
    return f;
}

}  // namespace detail

uint8_t ForwardPlan::pointer(int kind, int k, int j, const std::function<uint8_t(uint32_t)>& mem,
                             const std::function<uint8_t(uint32_t)>& ext) const {
    const PointerColumn& c = ptr[kind][k];
    const int idx = j - c.base;
    const int byte = idx >> 2, field = idx & 3;
    const uint8_t b = c.ext >= 0 ? ext(static_cast<uint32_t>(c.ext + byte))
                                 : mem(static_cast<uint32_t>(c.addr + byte));
    const int bits = (b >> (6 - 2 * field)) & 3;
    return static_cast<uint8_t>((bits & 1) ? 2 : (bits >> 1));
}

golden::Params firmware_part(const golden::Params& p) {
    golden::Params q = golden::paper_part(p);
    q.ad_max = p.ad_max;  // run in the firmware (WM_ADD, DP_MEET)
    q.dissim = p.dissim;  // bt: BT_BOUNDS and WM_ADD
    q.mode = p.mode;
    if (p.kc > 0) q.km = p.km;  // the census keeps the cost valid without |a - b|
    q.kc = p.kc;                // the census (census.inc)
    q.census = p.census;
    q.agg_rx = p.agg_rx;  // the window: its copies (window phase) and row sums (AGG_BODY)
    q.agg_ry = p.agg_ry;
    return q;
}

ForwardPlan plan_forward(const golden::Params& p, int N, const isa::MachineConfig& cfg) {
    return detail::plan_forward_impl(p, N, cfg, false, false);
}

namespace {

// Levels [a, b] (b < a: none).
struct Span {
    int a = 0, b = -1;
    bool none() const { return b < a; }
};

// Kind p's column k split by the boundary m at column 1 (split_cut): the
// lower part and the upper part; no column: both empty.
void split_column(const ForwardPlan& f, int p, int k, int m, Span& lower, Span& upper) {
    lower = upper = Span{};
    if (k < 1 || k > f.K[p] || f.hi[p][k] < f.lo[p][k]) return;
    const int cut = detail::split_cut(f, p, m, k);
    lower = Span{f.lo[p][k], cut - 1};
    upper = Span{cut, f.hi[p][k]};
}

// The address windows of the PE of kind q at every step (levels offset by
// its parts' sigma / tau) for boundaries m and the order of its parts;
// sets sigma[q], tau[q]. Returns false when the parts cannot be ordered so.
bool pe_windows(const ForwardPlan& f, const int m[2], int q, bool upper_first, bool indexed_l,
                int T, std::vector<Span>& win, int& sigma, int& tau) {
    const int o = 1 - q;
    sigma = 0;
    if (!upper_first) {
        tau = m[q] - m[o] - 1;  // the boundary addresses touch: m_q(k) = m_o(k - 1) + tau
    } else {
        // the upper part's every address (and the one above its top, its top
        // node's D source or pad) below every address of the lower part, and
        // so its L' bytes: a node of step k at address x reads L' at k + x,
        // the lower part's L'_q[i] at i + sigma, the upper part's L'_o[i] at
        // i + 1 + tau
        int lo_min = INT_MAX, hi_max = INT_MIN, vlo_min = INT_MAX, vhi_max = INT_MIN;
        for (int k = 1; k <= T; ++k) {
            Span l, u, l2, u2;
            split_column(f, q, k, m[q], l, u);
            split_column(f, o, k - 1, m[o], l2, u2);
            if (!l.none()) {
                lo_min = std::min(lo_min, l.a);
                vlo_min = std::min(vlo_min, k + l.a);
            }
            if (!u2.none()) {
                hi_max = std::max(hi_max, u2.b);
                vhi_max = std::max(vhi_max, k + u2.b);
            }
        }
        if (lo_min == INT_MAX || hi_max == INT_MIN) return false;
        tau = lo_min - hi_max - 2;
        if (!indexed_l) tau = std::min(tau, vlo_min - vhi_max - 1);
    }
    win.assign(size_t(T) + 1, Span{});
    for (int k = 1; k <= T; ++k) {
        Span l, u, l2, u2;
        split_column(f, q, k, m[q], l, u);
        split_column(f, o, k - 1, m[o], l2, u2);
        Span w;
        if (!l.none()) w = Span{l.a + sigma, l.b + sigma};
        if (!u2.none())
            w = w.none() ? Span{u2.a + tau, u2.b + tau}
                         : Span{std::min(w.a, u2.a + tau), std::max(w.b, u2.b + tau)};
        win[size_t(k)] = w;
    }
    return true;
}

// Slots of the passes for PE 1's addresses offset by rho from PE 0's.
int64_t hull_slots(const std::vector<Span> w[2], int T, int rho, int64_t stop) {
    int64_t t = 0;
    for (int k = 1; k <= T && t < stop; ++k) {
        const Span& a = w[0][size_t(k)];
        const Span& b = w[1][size_t(k)];
        if (a.none() && b.none()) continue;
        if (a.none()) {
            t += b.b - b.a + 1;
        } else if (b.none()) {
            t += a.b - a.a + 1;
        } else {
            t += std::max(a.b, b.b + rho) - std::min(a.a, b.a + rho) + 1;
        }
    }
    return t;
}

}  // namespace

PairSchedule pair_schedule(const ForwardPlan& f, bool indexed_l) {
    PairSchedule r;
    r.indexed_l = indexed_l;
    r.passes = r.split = r.balanced = f.slots;
    if (f.kinds != 2) return r;
    const int T = f.kmax + 1;  // steps: column k's lower part at k, its upper part at k + 1
    r.steps = T;
    int64_t states = 0;
    for (int p = 0; p < 2; ++p)
        for (int k = 1; k <= f.K[p]; ++k) states += std::max(0, f.hi[p][k] - f.lo[p][k] + 1);
    r.even = (states + 1) / 2;
    auto size = [](const Span& s) { return s.none() ? 0 : s.b - s.a + 1; };
    int mlo[2], mhi[2];  // m from the whole column on the partner to the whole column at home
    for (int p = 0; p < 2; ++p) {
        const int k = std::min(1, f.K[p]);  // a kind without columns: its boundary is moot
        mlo[p] = f.K[p] >= 1 ? f.lo[p][k] - T : 0;
        mhi[p] = f.K[p] >= 1 ? f.hi[p][k] + 1 + T : 0;
    }
    r.balanced = r.split = INT64_MAX;
    std::vector<Span> w[2];
    for (int a = mlo[0]; a <= mhi[0]; ++a)
        for (int b = mlo[1]; b <= mhi[1]; ++b) {
            const int m[2] = {a, b};
            int64_t bal = 0;
            for (int k = 1; k <= T && bal < r.balanced; ++k) {
                Span l[2], u[2], lp[2], up[2];
                for (int p = 0; p < 2; ++p) {
                    split_column(f, p, k, m[p], l[p], u[p]);
                    split_column(f, p, k - 1, m[p], lp[p], up[p]);
                }
                bal += std::max(size(l[0]) + size(up[1]), size(l[1]) + size(up[0]));
            }
            r.balanced = std::min(r.balanced, bal);
            if (bal >= r.split) continue;  // the hull is never below the node counts
            for (int order = 0; order < 4; ++order) {
                const bool uf[2] = {(order & 1) != 0, (order & 2) != 0};
                int sg[2], ta[2];
                if (!pe_windows(f, m, 0, uf[0], indexed_l, T, w[0], sg[0], ta[0]) ||
                    !pe_windows(f, m, 1, uf[1], indexed_l, T, w[1], sg[1], ta[1]))
                    continue;
                // the hull's slots are convex in rho: integer ternary search,
                // ties to the offset nearest 0 (where the PEs' windows never
                // meet, every offset costs the same: the planes stay small)
                auto key = [&](int rho) {
                    return hull_slots(w, T, rho, INT64_MAX) * (int64_t{1} << 24) + std::abs(rho);
                };
                int lo = -4 * (f.D + T), hi = 4 * (f.D + T);
                while (hi - lo > 2) {
                    const int m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
                    if (key(m1) <= key(m2))
                        hi = m2;
                    else
                        lo = m1;
                }
                int best_rho = lo;
                for (int rho = lo + 1; rho <= hi; ++rho)
                    if (key(rho) < key(best_rho)) best_rho = rho;
                {
                    const int rho = best_rho;
                    const int64_t t = hull_slots(w, T, rho, r.split);
                    if (t < r.split) {
                        r.split = t;
                        r.m[0] = a;
                        r.m[1] = b;
                        r.upper_first[0] = uf[0];
                        r.upper_first[1] = uf[1];
                        r.sigma[0] = sg[0];
                        r.tau[0] = ta[0];
                        r.sigma[1] = sg[1] + rho;
                        r.tau[1] = ta[1] + rho;
                    }
                }
            }
        }
    return r;
}

SplitForward plan_split_forward(const golden::Params& p, const ForwardPlan& f, bool indexed) {
    if (!f.bidir || f.joint || f.ds >= 0 || p.kc > 0 || p.agg_rx > 0 || p.agg_ry > 0 ||
        p.dissim == golden::Dissim::Bt)
        throw FirmwareError(
            "firmware: the split forward runs bidir frames with a free seed disparity and the "
            "plain match cost only");
    SplitForward sf;
    sf.indexed = indexed;
    sf.s = pair_schedule(f, indexed);
    const PairSchedule& s = sf.s;
    const int T = f.kmax + 1;
    // parts in level terms with the schedule's offsets, slots shifted below
    int xmin = INT_MAX, xmax = INT_MIN;
    for (int k = 1; k <= T; ++k) {
        SplitStep st;
        st.k = k;
        int lo = INT_MAX, hi = INT_MIN;
        for (int q = 0; q < 2; ++q) {
            const int o = 1 - q;
            Span l, u, l2, u2;
            split_column(f, q, k, s.m[q], l, u);
            split_column(f, o, k - 1, s.m[o], l2, u2);
            SplitPart& a = st.part[q][0];
            SplitPart& b = st.part[q][1];
            a = SplitPart{q, k, l.a, l.b, s.sigma[q], false};
            b = SplitPart{o, k - 1, u2.a, u2.b, s.tau[q], true};
            for (const SplitPart* sp : {&a, &b})
                if (!sp->none()) {
                    lo = std::min(lo, sp->lo + sp->off);
                    hi = std::max(hi, sp->hi + sp->off);
                }
        }
        if (lo > hi) continue;
        st.x0 = lo;
        st.n = hi - lo + 1;
        xmin = std::min(xmin, lo);
        xmax = std::max(xmax, hi);
        sf.steps.push_back(st);
    }
    // the start column's parts (init) take slots too, and so does the level above a top
    for (int q = 0; q < 2; ++q) {
        const int o = 1 - q;
        xmin = std::min({xmin, f.lo[q][0] + s.sigma[q], f.lo[o][0] + s.tau[q]});
        xmax = std::max({xmax, f.hi[q][0] + s.sigma[q], f.hi[o][0] + s.tau[q]});
    }
    const int shift = -xmin;
    sf.shift = shift;
    int vmin = INT_MAX, vmax = INT_MIN;
    for (SplitStep& st : sf.steps) {
        st.x0 += shift;
        for (auto& pe : st.part)
            for (SplitPart& sp : pe) sp.off += shift;
        vmin = std::min(vmin, st.k + st.x0);
        vmax = std::max(vmax, st.k + st.x0 + st.n - 1);
    }
    sf.slots = xmax + shift + 2;
    // memory: constant block, R' of both kinds, L', the values sent, the planes, pointers
    const int lo_mem = f.kblk + f.kbs;
    sf.rbr = lo_mem + f.kmax;
    sf.rbr2 = sf.rbr + 1 + f.kmax;
    sf.rbl = sf.rbr2 + 1;
    sf.v0 = vmin;
    sf.lbytes = vmax - vmin + 1;
    if (indexed) {
        // each kind's L' in a region of its own (kind p's L'[i] at rl + p * gap +
        // i on every PE), the gap between them (at least a region either way)
        // chosen for the least spread of the four parts' offsets, which must
        // fit a byte
        const int region = f.kmax + f.D + 1;
        const int offl[2] = {s.sigma[0] + shift, s.sigma[1] + shift};
        const int offu[2] = {s.tau[0] + shift, s.tau[1] + shift};
        // offsets less the common base: PE 0 lower (kind 0), PE 0 upper (kind
        // 1), PE 1 lower (kind 1), PE 1 upper (kind 0)
        auto spread = [&](int gap, int* lo_out) {
            const int v[4] = {-offl[0], gap - 1 - offu[0], gap - offl[1], -1 - offu[1]};
            *lo_out = *std::min_element(v, v + 4);
            return *std::max_element(v, v + 4) - *lo_out;
        };
        int best_gap = region, best = INT_MAX, lo_best = 0;
        for (int g = region; g <= region + 1024; ++g)
            for (int gap : {g, -g}) {
                int lo = 0;
                const int sp = spread(gap, &lo);
                if (sp < best) {
                    best = sp;
                    best_gap = gap;
                    lo_best = lo;
                }
            }
        if (best > 255)
            throw FirmwareError("firmware: the split's L' offsets spread over " +
                                std::to_string(best) + " bytes (an ldx offset is one byte)");
        sf.rl = sf.rbl + (best_gap < 0 ? -best_gap : 0);  // kind 0's region
        sf.ru = sf.rl + best_gap;                         // kind 1's
        sf.lbytes = std::abs(best_gap) + region;
        sf.cbase = sf.rl + lo_best;
        for (SplitStep& st : sf.steps)
            for (int q = 0; q < 2; ++q) {
                SplitPart& lower = st.part[q][0];
                SplitPart& upper = st.part[q][1];
                const int own = q == 0 ? sf.rl : sf.ru, other = q == 0 ? sf.ru : sf.rl;
                lower.lx = own - sf.cbase - lower.off;
                upper.lx = other - 1 - sf.cbase - upper.off;
            }
    }
    sf.sent = sf.rbl + sf.lbytes;
    sf.costl = sf.sent + 6;
    sf.costh = sf.costl + sf.slots;
    sf.preg = sf.costh + sf.slots;
    int a = sf.preg;
    for (SplitStep& st : sf.steps) {
        st.addr = a;
        a += 2 * ((st.n + 7) / 8);
    }
    sf.mem_needed = a;
    return sf;
}

}  // namespace imap::firmware
