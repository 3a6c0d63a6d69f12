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

// The passes of every column: one shared pass where the kinds agree on the
// first slot, else one masked pass per kind.
void column_passes(ForwardPlan& f) {
    f.passes.clear();
    f.slots = 0;
    // A pass of column k over levels jlo .. hi of `kind` (-1: every kind).
    auto add_pass = [&](int k, int kind, int jlo, int hi, bool donly) {
        ForwardPass ps;
        ps.k = k;
        ps.kind = kind;
        ps.jlo = jlo;
        ps.n = hi - jlo + 1;
        ps.donly = donly;
        ps.pad = hi == f.D - 1;
        ps.bytes = ceil_div(ps.n, 4);
        f.passes.push_back(ps);
        f.slots += ps.n;
    };
    for (int k = 1; k <= f.kmax; ++k) {
        int act[2], na = 0;
        for (int p = 0; p < f.kinds; ++p)
            if (k <= f.K[p]) act[na++] = p;
        auto donly = [&](int p) { return f.lo[p][k] < f.lo[p][k - 1]; };
        const bool shared = na == 2 && f.lo[0][k] == f.lo[1][k] && donly(0) == donly(1);
        if (f.kinds == 1 || shared) {
            int hi = f.hi[act[0]][k];
            if (na == 2) hi = std::max(hi, f.hi[act[1]][k]);
            add_pass(k, -1, f.lo[act[0]][k], hi, donly(act[0]));
            continue;
        }
        for (int i = 0; i < na; ++i)
            add_pass(k, act[i], f.lo[act[i]][k], f.hi[act[i]][k], donly(act[i]));
    }
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
                              bool tiny, bool census_ok) {
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
    column_passes(f);
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

}  // namespace imap::firmware
