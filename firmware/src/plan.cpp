#include "imap/firmware/plan.hpp"

#include <algorithm>
#include <climits>
#include <sstream>

#include "imap/golden/cost.hpp"
#include "imap/golden/estimate.hpp"
#include "imap/isa/assembler.hpp"

namespace imap::firmware {

namespace {

// per-PE constant block: K_KIND .. K_END and two re-layout bytes (dp_setup.inc checks it)
constexpr int kKBlockSize = 10;     // 8 constants + 2 bytes of the re-layout
constexpr int kPopTableBytes = 16;  // the census's popcount of a nibble (census.inc)
constexpr int kAggFlagBytes = 2;    // agg-ry: lines above / below in the ROI (dp_setup.inc)
constexpr int kNever = INT_MAX;

int ceil_div(int a, int b) {
    return (a + b - 1) / b;
}

// The largest match cost (SPEC A.9): the window's terms times the largest pixel term.
int64_t wm_max(const golden::Params& p) {
    return golden::window_terms(p) * golden::pixel_cost_max(p);
}

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
    const int D = f.D;
    for (int k = 1; k <= f.kmax; ++k) {
        int act[2], na = 0;
        for (int p = 0; p < f.kinds; ++p)
            if (k <= f.K[p]) act[na++] = p;
        auto donly = [&](int p) { return f.lo[p][k] < f.lo[p][k - 1]; };
        const bool shared = na == 2 && f.lo[0][k] == f.lo[1][k] && donly(0) == donly(1);
        if (f.kinds == 1 || shared) {
            ForwardPass ps;
            ps.k = k;
            ps.kind = -1;
            ps.jlo = f.lo[act[0]][k];
            int hi = f.hi[act[0]][k];
            if (na == 2) hi = std::max(hi, f.hi[act[1]][k]);
            ps.n = hi - ps.jlo + 1;
            ps.donly = donly(act[0]);
            ps.pad = hi == D - 1;
            ps.bytes = ceil_div(ps.n, 4);
            f.passes.push_back(ps);
            f.slots += ps.n;
            continue;
        }
        for (int i = 0; i < na; ++i) {
            const int p = act[i];
            ForwardPass ps;
            ps.k = k;
            ps.kind = p;
            ps.jlo = f.lo[p][k];
            ps.n = f.hi[p][k] - ps.jlo + 1;
            ps.donly = donly(p);
            ps.pad = f.hi[p][k] == D - 1;
            ps.bytes = ceil_div(ps.n, 4);
            f.passes.push_back(ps);
            f.slots += ps.n;
        }
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
            if ((ps.kind == p || ps.kind == -1) && ps.k <= f.K[p]) {
                plo[p][ps.k] = std::min(plo[p][ps.k], ps.jlo);
                phi[p][ps.k] = std::max(phi[p][ps.k], ps.jlo + ps.n - 1);
            }
    for (ForwardPass& ps : f.passes) {
        ps.rfull = ps.n;
        ps.rinc = 0;
        if (f.agg == 0 || ps.k == 1) continue;
        int lo = ps.jlo, hi = ps.jlo + ps.n - 1;
        for (int p = 0; p < f.kinds; ++p)
            if ((ps.kind == p || ps.kind == -1) && ps.k <= f.K[p]) {
                lo = std::max(lo, plo[p][ps.k - 1]);
                hi = std::min(hi, phi[p][ps.k - 1]);
            }
        if (lo > hi) continue;
        ps.rfull = lo - ps.jlo;
        ps.rinc = hi - lo + 1;
    }
}

// Bytes of a pass holding kind p's pointers (a shared pass computes the
// union of the kinds' ranges; a kind's pointers are the bytes up to its top).
int kind_bytes(const ForwardPlan& f, const ForwardPass& ps, int p) {
    if (ps.kind >= 0) return ps.kind == p ? ps.bytes : 0;
    if (ps.k > f.K[p]) return 0;
    return ceil_div(f.hi[p][ps.k] - ps.jlo + 1, 4);
}

struct FreeMap {
    int mem = 0;
    std::vector<int> avail[2];  // first column from which an address may hold pointers
    std::vector<char> used[2];

    bool free_for(int p, int a, int k) const { return !used[p][a] && avail[p][a] <= k; }
    // Lowest address of `len` bytes free for every kind in `kinds` from column k.
    int find(int len, const std::vector<int>& kinds, int k, int from = 0) const {
        for (int a = from; a + len <= mem; ++a) {
            bool ok = true;
            for (int b = a; b < a + len && ok; ++b)
                for (int p : kinds) ok = ok && free_for(p, b, k);
            if (ok) return a;
        }
        return -1;
    }
};

// Places the pointer columns: the first `spill` columns go to the external
// memory (staged at the start of the pointer region), the others on chip;
// false if they do not fit.
bool place_pointers(ForwardPlan& f, int mem, int spill) {
    FreeMap fm;
    fm.mem = mem;
    for (int p = 0; p < 2; ++p) {
        fm.avail[p].assign(mem, kNever);
        fm.used[p].assign(mem, 0);
        for (int a = f.preg; a < mem; ++a) fm.avail[p][a] = 1;
        if (f.agg > 0) {
            // the window copies: Rx[m], Lx[m] (and codes) die after column m + agg
            std::vector<int> offs = {0};
            if (f.kc > 0) offs.push_back(f.cxo);
            if (f.bt) {
                offs.push_back(f.blo);
                offs.push_back(f.bhi);
            }
            for (int off : offs) {
                for (int m = 1 - f.agg; m <= f.kr + f.agg; ++m)
                    fm.avail[p][f.rbr - m + off] = std::max(1, m + f.agg + 1);
                for (int m = 1 - f.agg; m <= f.kl + f.agg; ++m)
                    fm.avail[p][f.rbl + m + off] = std::max(1, m + f.agg + 1);
            }
            continue;
        }
        for (int i = 0; i <= f.kr; ++i)
            fm.avail[p][f.rp_addr(i)] = i + 1;  // R'[i] dies after column i
        for (int i = 0; i <= f.kl; ++i)
            fm.avail[p][f.lp_addr(i)] = i + 1;  // L'[i] dies after column i
    }
    for (int p = 0; p < 2; ++p) f.ptr[p].assign(f.kmax + 1, PointerColumn{});
    f.spills.clear();
    f.reloads.clear();
    const int stage_cap = std::min(mem - f.preg, 4096);
    int stage_off = 0, ext = 0, block_ext = 0;
    size_t i = 0;
    while (i < f.passes.size()) {
        const int k = f.passes[i].k;
        size_t j = i;
        int size = 0;
        while (j < f.passes.size() && f.passes[j].k == k)
            size = std::max(size, f.passes[j++].bytes);
        std::vector<int> kinds;
        for (int p = 0; p < f.kinds; ++p)
            if (k <= f.K[p]) kinds.push_back(p);
        if (k <= spill) {
            if (size > stage_cap) return false;
            if (stage_off + size > stage_cap) {
                f.spills.push_back({f.preg, block_ext, stage_off, static_cast<int>(i) - 1});
                block_ext = ext;
                stage_off = 0;
            }
            for (size_t q = i; q < j; ++q) {
                f.passes[q].addr = f.preg + stage_off;
                for (int p = 0; p < f.kinds; ++p) {
                    const int b = kind_bytes(f, f.passes[q], p);
                    if (b == 0) continue;
                    f.ptr[p][k] = {-1, f.passes[q].jlo, b, ext};
                }
            }
            stage_off += size;
            ext += size;
            if (k == spill) {
                f.spills.push_back({f.preg, block_ext, stage_off, static_cast<int>(j) - 1});
                block_ext = ext;
                stage_off = 0;
            }
        } else {
            const int a = fm.find(size, kinds, k);
            if (a < 0) return false;
            for (size_t q = i; q < j; ++q) {
                f.passes[q].addr = a;
                for (int p = 0; p < f.kinds; ++p) {
                    const int b = kind_bytes(f, f.passes[q], p);
                    if (b == 0) continue;
                    for (int x = a; x < a + b; ++x) fm.used[p][x] = 1;
                    f.ptr[p][k] = {a, f.passes[q].jlo, b, -1};
                }
            }
            // A pass writes `size` bytes for every kind it runs on; bytes
            // beyond a kind's own pointers are free for that kind afterwards.
        }
        i = j;
    }
    f.ext_needed = ext;

    // After the forward pass: the output line (free of every on-chip column),
    // then each spilled column reloaded just before the backtrack reaches it,
    // into memory free of the map and of the on-chip columns still ahead
    // (xld writes every PE, so free for every kind).
    for (int p = 0; p < 2; ++p)
        for (int a = 0; a < mem; ++a) fm.avail[p][a] = a < f.kblk + f.kbs ? kNever : 0;
    const std::vector<int> all = {0, 1};
    f.map = fm.find(f.N, all, 0);
    if (f.map < 0) return false;
    int top = std::max(f.preg, f.map + f.N);
    for (const Transfer& t : f.spills) top = std::max(top, t.local + t.len);
    if (spill > 0) {
        FreeMap rm = fm;  // used: on-chip columns; the map is added below
        for (int p = 0; p < 2; ++p)
            for (int x = f.map; x < f.map + f.N; ++x) rm.used[p][x] = 1;
        // column -> its on-chip bytes per kind (to release them as the backtrack passes)
        for (int k = f.kmax; k >= 1; --k) {
            if (k > spill) {
                for (int p = 0; p < f.kinds; ++p) {
                    const PointerColumn& c = f.ptr[p][k];
                    if (c.bytes == 0 || c.ext >= 0) continue;
                    for (int x = c.addr; x < c.addr + c.bytes; ++x) rm.used[p][x] = 0;
                }
                continue;
            }
            int size = 0, ext_addr = -1;
            for (int p = 0; p < f.kinds; ++p) {
                const PointerColumn& c = f.ptr[p][k];
                if (c.bytes == 0) continue;
                ext_addr = c.ext;
            }
            for (const ForwardPass& ps : f.passes)
                if (ps.k == k) size = std::max(size, ps.bytes);
            if (ext_addr < 0 || size == 0) continue;
            const int a = rm.find(size, all, 0);
            if (a < 0) return false;
            f.reloads.push_back({a, ext_addr, size, k});
            for (int p = 0; p < f.kinds; ++p)
                if (f.ptr[p][k].bytes > 0) f.ptr[p][k].addr = a;
            top = std::max(top, a + size);
        }
    }
    // Highest local address in use by the DP.
    for (int p = 0; p < 2; ++p)
        for (int a = mem - 1; a >= 0; --a)
            if (fm.used[p][a]) {
                top = std::max(top, a + 1);
                break;
            }
    f.mem_needed = top;
    return true;
}

void check_options(const golden::Params& p, bool census_ok) {
    // SPEC A.9 options the firmware does not run (docs/firmware.md, section 10):
    // refused up front, never a wrong map.
    const golden::Params off;
    std::string missing;
    auto add = [&](const std::string& what) { missing += (missing.empty() ? "" : ", ") + what; };
    if (p.dissim != off.dissim && !census_ok)
        add("--dissim " + std::string(golden::to_string(p.dissim)));
    if (p.kc != off.kc && !census_ok) add("--kc " + std::to_string(p.kc));
    if (p.agg_rx != off.agg_rx && (!census_ok || p.agg_rx > 2))
        add("--agg-rx " + std::to_string(p.agg_rx));
    if (p.agg_ry != off.agg_ry && !census_ok) add("--agg-ry " + std::to_string(p.agg_ry));
    if (!missing.empty())
        throw FirmwareError("the DP firmware does not implement the SPEC A.9 option(s) " + missing +
                            (census_ok ? " (it runs SPEC A.1-A.7 with --ad-max, --dissim ad/bt, "
                                         "--kc/--census, --agg-rx 0..2, --agg-ry and --mode "
                                         "joint; needs --agg-rx <= 2; the golden runs all)"
                                       : " (the forward-pass test layout runs SPEC A.1-A.7 with "
                                         "--ad-max and --mode joint; needs --dissim ad, --kc 0, "
                                         "--agg-rx 0, --agg-ry 0)"));
}

void check_range(const golden::Params& p) {
    const int64_t w = wm_max(p);
    const int64_t od = int64_t{p.Wo} + p.Wd;
    if (std::max(w, od) > kMaxSpread) {
        std::ostringstream os;
        os << "firmware: cost spread max((2*agg-rx+1)*(2*agg-ry+1)*(km*min(255, ad-max) + "
              "kb*gb + 8*kc), Wo + Wd) = "
           << std::max(w, od) << " exceeds the 16-bit costs' range (needs <= " << kMaxSpread
           << "; lower --km, --kb, --gb, --kc, --agg-rx, --agg-ry, --Wo or --Wd)";
        throw FirmwareError(os.str());
    }
}

}  // namespace

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

namespace {
ForwardPlan plan_forward_impl(const golden::Params& p, int N, const isa::MachineConfig& cfg,
                              bool tiny, bool census_ok);
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
    return plan_forward_impl(p, N, cfg, false, false);
}

namespace {
// Every pointer table in the external memory (three rotating slots of
// ext_table bytes), the backtrack voting from three reloaded columns
// (docs/firmware.md, section 4: arrays of 2 to 5 PEs).
bool place_tiny(ForwardPlan& f, int mem) {
    if (!place_pointers(f, mem, f.kmax)) return false;
    // place_pointers reloaded each column into the lowest free bytes: now
    // one buffer for the own column and two for the neighbours' columns.
    int size = 0;
    for (const ForwardPass& ps : f.passes) size = std::max(size, ps.bytes);
    f.reloads.clear();
    const int lo = f.kblk + f.kbs;
    auto overlaps_map = [&](int a, int n) { return a < f.map + f.N && f.map < a + n; };
    int a = lo, bufs[3], got = 0;
    while (got < 3 && a + size <= mem) {
        if (overlaps_map(a, size)) {
            a = f.map + f.N;
            continue;
        }
        bufs[got++] = a;
        a += size;
    }
    if (got < 3) return false;
    f.tiny_buf[0] = bufs[0];
    f.tiny_buf[1] = bufs[1];
    f.tiny_buf[2] = bufs[2];
    for (int p = 0; p < f.kinds; ++p)
        for (int k = 1; k <= f.kmax; ++k)
            if (f.ptr[p][k].bytes > 0) f.ptr[p][k].addr = bufs[0];
    f.ext_table = static_cast<int>(f.ext_needed);
    f.ext_needed = 3 * int64_t{f.ext_table};
    f.mem_needed = std::max(f.mem_needed, bufs[2] + size);
    f.tiny = true;
    return true;
}

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

    // Line buffers: R' reversed below rb, L' above it, so that the consumed
    // prefixes of both form one growing region (docs/firmware.md, section 3).
    f.kblk = 0;
    f.kbs = kKBlockSize + (p.kc > 0 ? kPopTableBytes : 0) + (p.agg_ry > 0 ? kAggFlagBytes : 0);
    f.kr = f.kmax;
    int kl = 0;
    for (const ForwardPass& ps : f.passes) kl = std::max(kl, ps.k + ps.jlo + ps.n - 1);
    if (f.joint)
        kl = std::max({kl, f.s + p.D, N + p.D - 2 - f.s});
    else if (f.bidir)
        kl = std::max({kl, f.s + p.D - 1, N - 1 - f.s});
    else
        kl = std::max(kl, N);
    f.kl = kl;
    f.rb = f.kblk + f.kbs + f.kr;
    f.costl = f.rb + 2 + f.kl;
    f.costh = f.costl + p.D + 1;
    f.preg = f.costh + p.D + 1;
    if (p.kc > 0) {
        // census codes beside the line buffers, at their addresses + co
        // (never reused for pointers: the region lies below the pointer region)
        f.census = p.census;
        f.kc = p.kc;
        f.co = f.preg - (f.kblk + f.kbs);
        f.preg += f.kr + f.kl + 2;
    }
    if (p.dissim == golden::Dissim::Bt) {
        // Birchfield-Tomasi bounds lo, hi beside the line buffers, at their
        // addresses + blo / + bhi (below the pointer region, as the codes)
        f.bt = true;
        f.blo = f.preg - (f.kblk + f.kbs);
        f.preg += f.kr + f.kl + 2;
        f.bhi = f.preg - (f.kblk + f.kbs);
        f.preg += f.kr + f.kl + 2;
    }
    f.rbr = f.rb;
    f.rbl = f.rb + 1;
    const int mem0 = static_cast<int>(std::min<uint32_t>(cfg.mem_bytes, 1u << 20));
    if (p.agg_rx > 0) {
        // The node reads extended, clamped copies of the line buffers (and
        // codes): Rx[m], m = 1-a .. kr+a, at rbr - m, Lx[m], m = 1-a .. kl+a, at
        // rbl + m, right after the constant block; then the costs. The
        // re-layout's buffers (and codes) move to the top of the memory: they
        // die when the copies are made (AGG_EXTEND, before the forward pass).
        const int a = p.agg_rx;
        f.agg = a;
        const int lo = f.kblk + f.kbs;
        f.rbr = lo + f.kr + a;
        f.rbl = f.rbr + 2 * a;
        const int se = f.rbl + f.kl + a + 1 - lo;
        f.cxo = p.kc > 0 ? se : 0;
        const int copies = (p.kc > 0 ? 2 : 1);
        if (f.bt) {
            f.blo = se * copies;
            f.bhi = f.blo + se;
        }
        f.costl = lo + se * (copies + (f.bt ? 2 : 0));
        f.costh = f.costl + p.D + 1;
        f.preg = f.costh + p.D + 1;
        const int s0 = f.kr + f.kl + 2;
        f.agg_src = mem0 - s0 * (p.kc > 0 ? 2 : 1);
        f.rb = f.agg_src + f.kr;
        f.co = p.kc > 0 ? s0 : 0;
        if (f.agg_src < f.costl) {
            std::ostringstream os;
            os << "does not fit: --agg-rx " << a << " needs at least "
               << f.costl + s0 * (p.kc > 0 ? 2 : 1)
               << " bytes of local memory per PE for the line buffers and their window copies"
               << (f.bt ? " (with the bt bounds)" : "") << " (have " << mem0 << ", mem_bytes)";
            throw FirmwareError(os.str());
        }
    }
    if (p.agg_rx > 0 || p.agg_ry > 0) {
        // The window: the match cost of every level of the column pass,
        // computed before its nodes (AGG_BODY, dp_forward.inc), in two byte
        // planes after the costs; below the pointer region.
        f.rows = true;
        f.aggy = p.agg_ry;
        f.wl = f.preg;
        f.wh = f.wl + p.D;
        f.preg = f.wh + p.D;
        f.pmax = static_cast<int>(golden::pixel_cost_max(p));  // <= 32,766: check_range
        f.h8 = int64_t{2 * p.agg_rx + 1} * f.pmax <= 255;
        f.d8 = 2 * int64_t{f.pmax} <= 255;
        window_segments(f);
    }
    const int mem = static_cast<int>(std::min<uint32_t>(cfg.mem_bytes, 1u << 20));
    if (f.preg > mem) {
        std::ostringstream os;
        os << "does not fit: needs at least " << f.preg + 1
           << " bytes of local memory per PE for the line buffers"
           << (f.bt ? ", their bt bounds" : "") << " and costs (have " << mem << ", mem_bytes)";
        throw FirmwareError(os.str());
    }
    // The error names the least local memory that would do: found by the
    // same placement (it is monotone in the memory size).
    auto too_small = [&](const char* what, auto&& fits) {
        int lo = mem + 1, hi = 1 << 16;
        std::ostringstream os;
        os << "does not fit: ";
        if (fits(hi)) {
            while (lo < hi) {
                const int mid = lo + (hi - lo) / 2;
                if (fits(mid))
                    hi = mid;
                else
                    lo = mid + 1;
            }
            os << "needs at least " << lo << " bytes of local memory per PE for " << what;
        } else {
            os << "needs more than " << hi << " bytes of local memory per PE for " << what;
        }
        os << " (have " << mem << ", mem_bytes)";
        return FirmwareError(os.str());
    };
    if (tiny) {
        if (!place_tiny(f, mem))
            throw too_small("the line buffers, costs, output line and three pointer columns",
                            [&](int m) { return place_tiny(f, m); });
    } else if (!place_pointers(f, mem, 0)) {
        // The fewest spilled columns (the first ones) that let the rest fit.
        int lo = 1, hi = f.kmax;
        if (!place_pointers(f, mem, hi))
            throw too_small("the line buffers, costs, output line and one pointer column",
                            [&](int m) { return place_pointers(f, m, f.kmax); });
        while (lo < hi) {
            const int mid = lo + (hi - lo) / 2;
            if (place_pointers(f, mem, mid))
                hi = mid;
            else
                lo = mid + 1;
        }
        place_pointers(f, mem, lo);
    }
    if (f.ext_needed > int64_t{cfg.ext_bytes}) {
        std::ostringstream os;
        os << "does not fit: needs " << f.ext_needed
           << " bytes of external memory per PE for the spilled pointer columns (have "
           << cfg.ext_bytes << ", ext_bytes)";
        throw FirmwareError(os.str());
    }
    return f;
}
}  // namespace

// ---- frame --------------------------------------------------------------------------------

namespace {

// Source lanes [a, a + n) of segment g whose pixels go to kind `kind` (input).
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

int seg_width(const FramePlan& fp, int g) {
    return std::min(fp.P, fp.roi.w - g * fp.P);
}

// Skewed rows (docs/firmware.md, section 5): when the ring holds the lines'
// PEs and a video row per line shifted by `span` lanes per line, every line's
// items share one displacement per pixel: W rounds of at most ~W/2 hops
// instead of rounds over the span of all lines. The lines sit so that the
// input displacements d = base + kind - x are centred on 0, the output
// displacements likewise (skew_out).
void plan_skew(FramePlan& fp, int span) {
    Relayout& rl = fp.rl;
    if (fp.nseg != 1) return;
    const int P = fp.P, W = seg_width(fp, 0), H = fp.hbmax;
    int lo = INT_MAX, hi = INT_MIN;  // kind - x over the input items
    for (int kind = 0; kind < (fp.f.bidir ? 2 : 1); ++kind) {
        int a = 0, n = 0;
        in_lanes(fp.f, P, 0, W, kind, &a, &n);
        if (n == 0) continue;
        lo = std::min(lo, kind - (a + n - 1));
        hi = std::max(hi, kind - a);
    }
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

}  // namespace

void relayout_bound(const FramePlan& fp, int64_t* in, int64_t* out, int64_t* hop_in,
                    int64_t* hop_out) {
    const ForwardPlan& f = fp.f;
    const int P = fp.P;
    const int span = fp.span(), kinds = f.bidir ? 2 : 1;
    auto ring = [&](int a, int b) {
        int d = ((a - b) % P + P) % P;
        return std::min(d, P - d);
    };
    auto pe_of = [&](int y, int kind) { return ((fp.rl.base + span * y + kind) % P + P) % P; };
    // lane of pixel x of line y in the video rows (input) and the output rows
    auto soff = [&](int y) { return fp.rl.skew ? fp.rl.skew_in + span * y : 0; };
    auto ooff = [&](int y) { return fp.rl.skew ? fp.rl.skew_out + span * y : 0; };
    // Pixels X of image img (0 = left, 1 = right) that kind `kind` needs: [lo, hi].
    auto need = [&](int img, int kind, int* lo, int* hi) {
        *lo = 0;
        *hi = f.N - 1;
        if (!f.bidir) return;
        if (kind == 0)
            *hi = img == 0 ? std::min(f.N - 1, f.s + f.D - (f.joint ? 1 : 2))
                           : (f.joint ? f.s : f.s - 1);
        else
            *lo = f.s + 1;
    };
    // Size of [lo, hi] (lanes, within 0..P-1) inside the arc [a, a + len) mod P.
    auto overlap = [&](int lo, int hi, int a, int len) {
        if (lo > hi) return 0;
        auto lin = [&](int b0, int b1) {
            return std::max(0, std::min(hi, b1 - 1) - std::max(lo, b0) + 1);
        };
        int c = lin(a, std::min(a + len, P));
        if (a + len > P) c += lin(0, a + len - P);
        return c;
    };
    // Arc endpoints on a grid of at most 64 points per ring (any arc gives a
    // valid bound; the grid keeps the planner fast).
    const int step = std::max(1, P / 64);
    int64_t tin = 0, tout = 0, hin = 0, hout = 0;
    for (const Batch& b : fp.batches) {
        const int H = b.lines;
        for (int g = 0; g < fp.nseg; ++g) {
            const int W = seg_width(fp, g);
            const int X0 = g * P;
            int64_t hops = 0, ohops = 0;
            for (int y = 0; y < H; ++y)
                for (int x = 0; x < W; ++x) {
                    const int X = X0 + x;
                    for (int img = 0; img < 2; ++img) {
                        int best = INT_MAX, cnt = 0;
                        for (int kind = 0; kind < kinds; ++kind) {
                            int lo, hi;
                            need(img, kind, &lo, &hi);
                            if (X < lo || X > hi) continue;
                            best = std::min(best, ring(pe_of(y, kind), x + soff(y)));
                            ++cnt;
                        }
                        if (cnt) hops += best + (cnt - 1);
                    }
                    int ob = ring(pe_of(y, 0), x + ooff(y));
                    if (kinds == 2) ob = std::min(ob, ring(pe_of(y, 1), x + ooff(y)));
                    ohops += ob;
                }
            int64_t cut = 0, ocut = 0;
            for (int a = 0; a < P; a += step)
                for (int len = step; len < P; len += step) {
                    auto inside = [&](int q) { return ((q - a) % P + P) % P < len; };
                    int64_t c_in = 0, c_out = 0;
                    for (int y = 0; y < H; ++y) {
                        const int so = soff(y);
                        bool kin[2] = {inside(pe_of(y, 0)), kinds == 2 && inside(pe_of(y, 1))};
                        if (!kin[0] && !kin[1]) {
                            c_out += overlap(ooff(y), ooff(y) + W - 1, a, len);
                            continue;
                        }
                        for (int img = 0; img < 2; ++img) {
                            // union of the needed intervals of the kinds inside (as lanes)
                            int lo = INT_MAX, hi = INT_MIN;
                            for (int kind = 0; kind < kinds; ++kind) {
                                if (!kin[kind]) continue;
                                int l, h;
                                need(img, kind, &l, &h);
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
                            c_in += (hi - lo + 1) - overlap(lo + so, hi + so, a, len) - hole;
                        }
                    }
                    cut = std::max(cut, c_in);
                    ocut = std::max(ocut, c_out);
                }
            // census frames: every needed pixel comes with its code (a second
            // pair of rows over the same routes), twice the bytes in
            const int per = f.census > 0 ? 2 : 1;
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

namespace {

FramePlan plan_frame_impl(const golden::Params& p, const golden::Roi& roi,
                          const isa::MachineConfig& cfg, bool spare) {
    check_options(p, true);
    if (!cfg.indirect)
        throw FirmwareError(
            "the DP firmware needs per-PE (indirect) addressing for its re-layout and "
            "backtrack: set indirect=on");
    FramePlan fp;
    fp.roi = roi;
    fp.P = static_cast<int>(cfg.pes);
    fp.spare = spare;
    const bool bidir = p.mode == golden::Mode::Bidir || p.mode == golden::Mode::Joint;
    const int span = bidir || spare ? 2 : 1, kinds = bidir ? 2 : 1;
    fp.lpb = std::min(fp.P / span, 255);
    // Too few lines per batch for the vote across batches: one line at a
    // time, every pointer table kept in the external memory.
    const bool tiny = p.vote && roi.h > fp.lpb && fp.lpb < 3 && fp.lpb >= 1;
    if (p.kc > 0 && tiny)
        throw FirmwareError(
            "firmware: --kc " + std::to_string(p.kc) +
            " (census) needs the ROI's lines in one batch: " + std::to_string(roi.h) +
            " lines on " + std::to_string(fp.P) + " PEs run one line per batch (needs at least " +
            std::to_string(2 * roi.h) + " PEs, or --kc 0)");
    fp.f = plan_forward_impl(p, roi.w, cfg, tiny, true);  // range and DP memory checks
    if (tiny) fp.lpb = 1;
    if (fp.lpb < 1) {
        std::ostringstream os;
        os << "too few PEs: bidir mode needs 2 PEs per line, have " << fp.P;
        throw FirmwareError(os.str());
    }
    const int H = roi.h;
    if (tiny) {
        for (int y = 0; y < H; ++y) fp.batches.push_back({y, 1, 0, 1});
    } else if (H <= fp.lpb) {
        fp.batches.push_back({0, H, 0, H});
    } else {
        const bool overlap = p.vote;
        const int stride = overlap ? fp.lpb - 2 : fp.lpb;
        if (stride < 1) {
            std::ostringstream os;
            os << "too few PEs for the vote across batches: " << fp.P << " PEs hold " << fp.lpb
               << " line(s) per batch, the vote needs 3 (use >= " << (bidir ? 6 : 3)
               << " PEs, --vote off, or a ROI of at most " << fp.lpb << " lines)";
            throw FirmwareError(os.str());
        }
        for (int o = 0; o < H; o += stride) {
            const int oe = std::min(H, o + stride);
            const int first = overlap ? std::max(0, o - 1) : o;
            const int last = overlap ? std::min(H, oe + 1) : oe;
            fp.batches.push_back({first, last - first, o - first, oe - o});
        }
    }
    for (const Batch& b : fp.batches) fp.hbmax = std::max(fp.hbmax, b.lines);
    fp.nseg = (roi.w + fp.P - 1) / fp.P;
    if (p.agg_ry > 0 && (tiny || fp.batches.size() > 1)) {
        std::ostringstream os;
        os << "firmware: --agg-ry " << p.agg_ry << " (vertical window) needs the ROI's " << H
           << " lines in one batch (the match cost of line y sums the lines y-" << p.agg_ry
           << "..y+" << p.agg_ry << " of the ROI): needs " << span * H << " PEs, have " << fp.P;
        throw FirmwareError(os.str());
    }
    if (p.kc > 0 && fp.batches.size() > 1) {
        std::ostringstream os;
        os << "firmware: --kc " << p.kc << " (census) needs the ROI's " << H
           << " lines in one batch (the codes read the lines y-" << p.census << "..y+" << p.census
           << " of the ROI): needs " << span * H << " PEs, have " << fp.P;
        throw FirmwareError(os.str());
    }
    if (p.kc > 0 && fp.nseg > 1) {
        std::ostringstream os;
        os << "firmware: --kc " << p.kc << " (census) needs the ROI's width in one video segment: "
           << "needs " << roi.w << " PEs, have " << fp.P;
        throw FirmwareError(os.str());
    }

    // Re-layout geometry: the lines fill the ring (and a segment holds at
    // most half of it): the routes take the shorter way round; else the
    // lines sit centred on the segment and every route is direct.
    Relayout& rl = fp.rl;
    const int P = fp.P;
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
    } else {
        const int reg = span * fp.hbmax;
        rl.base = (W0 - reg) >= 0 ? (W0 - reg) / 2 : -((reg - W0 + 1) / 2);
        int hr = -1, hl = 0;
        for (int g = 0; g < fp.nseg; ++g) {
            const int W = seg_width(fp, g);
            for (int kind = 0; kind < kinds; ++kind) {
                int a = 0, n = 0;
                in_lanes(fp.f, P, g, W, kind, &a, &n);
                if (n == 0) continue;
                const int umin = rl.base + kind, umax = rl.base + span * (fp.hbmax - 1) + kind;
                hr = std::max(hr, umax - a);
                hl = std::max(hl, a + n - 1 - umin);
            }
        }
        if (bidir) {
            rl.ur = hr >= 0 ? hr / 2 + 1 : 0;
            rl.ul = hl > 0 ? (hl + 1) / 2 : 0;
        } else {
            rl.ur = hr + 1;
            rl.ul = hl;
        }
        plan_skew(fp, span);
    }

    // Video rows and the output rows: free memory outside the constant
    // block, the line buffers and (for the output) the map.
    const ForwardPlan& f = fp.f;
    const int mem = static_cast<int>(cfg.mem_bytes);
    int end = f.mem_needed;
    // the cost planes and the pointer region are free during the input (with
    // the window: the copies' region too, up to the re-layout's buffers)
    fp.inl = f.agg > 0 ? f.kblk + f.kbs : f.costl;
    if (fp.inl + 2 * fp.hbmax <= mem) {
        fp.inr = fp.inl + fp.hbmax;
        end = std::max(end, fp.inl + 2 * fp.hbmax);
    } else if (fp.inl + fp.hbmax <= mem) {
        fp.split_in = true;
        fp.inr = fp.inl;
        end = std::max(end, fp.inl + fp.hbmax);
    } else {
        std::ostringstream os;
        os << "does not fit: needs " << fp.inl + fp.hbmax
           << " bytes of local memory per PE for the video rows (have " << mem << ", mem_bytes)";
        throw FirmwareError(os.str());
    }
    if (f.census > 0) {
        // census code rows (video layout): beside the pixel rows, clear of the
        // code buffers the code re-layout writes (they end at preg)
        const int rows = fp.split_in ? 1 : 2;
        fp.cinl = f.agg > 0 ? fp.inl + rows * fp.hbmax : std::max(f.preg, fp.inl + rows * fp.hbmax);
        fp.cinr = fp.split_in ? fp.cinl : fp.cinl + fp.hbmax;
        if (fp.cinl + rows * fp.hbmax > mem) {
            std::ostringstream os;
            os << "does not fit: needs " << fp.cinl + rows * fp.hbmax
               << " bytes of local memory per PE for the census code rows (have " << mem
               << ", mem_bytes)";
            throw FirmwareError(os.str());
        }
        end = std::max(end, fp.cinl + rows * fp.hbmax);
    }
    if (f.agg > 0) {
        const int rows_end = f.census > 0 ? fp.cinr + fp.hbmax : fp.inr + fp.hbmax;
        if (rows_end > f.agg_src) {
            std::ostringstream os;
            os << "does not fit: --agg-rx " << f.agg << " needs " << rows_end - f.agg_src + mem
               << " bytes of local memory per PE for the video rows beside the line buffers (have "
               << mem << ", mem_bytes)";
            throw FirmwareError(os.str());
        }
        end = std::max(end, mem);
    }
    // output rows: after the constant block, avoiding the map
    fp.out = f.kbs;
    if (fp.out < f.map + f.N && fp.out + fp.hbmax > f.map) fp.out = f.map + f.N;
    if (fp.out + fp.hbmax > mem) {
        std::ostringstream os;
        os << "does not fit: needs " << fp.out + fp.hbmax
           << " bytes of local memory per PE for the output rows (have " << mem << ", mem_bytes)";
        throw FirmwareError(os.str());
    }
    end = std::max(end, fp.out + fp.hbmax);
    fp.mem_needed = end;
    fp.ext_needed = f.ext_needed;
    relayout_bound(fp, &rl.bound_in, &rl.bound_out, &rl.hop_bound_in, &rl.hop_bound_out);
    return fp;
}

}  // namespace

FramePlan plan_frame(const golden::Params& p, const golden::Roi& roi, const isa::MachineConfig& cfg,
                     SpillLayout layout) {
    FramePlan fp = plan_frame_impl(p, roi, cfg, false);
    if (layout == SpillLayout::External) return fp;
    const bool forced = layout == SpillLayout::Spare;
    const auto infeasible = [&](const char* why) {
        if (forced)
            throw FirmwareError(std::string("the spare-PE spill layout does not apply: ") + why);
        return fp;
    };
    // Spilled pointer columns and idle PEs (single mode, one batch, one video
    // segment, at least two PEs per line): the spare layout keeps them on
    // chip, in the PE above each line's PE (docs/firmware.md, section 3).
    const ForwardPlan& f = fp.f;
    if (f.bidir || f.tiny || f.kc > 0 || f.agg > 0 || f.aggy > 0 || f.bt)
        return infeasible("it needs single mode without census, aggregation or bt dissimilarity");
    if (f.ext_needed == 0) return infeasible("no pointer column spills");
    if (fp.batches.size() != 1 || fp.nseg != 1 || 2 * roi.h > fp.P)
        return infeasible("it needs one batch, one video segment and two PEs per ROI line");
    FramePlan sp;
    try {
        sp = plan_frame_impl(p, roi, cfg, true);
    } catch (const FirmwareError&) {
        return infeasible("the spare layout's plan does not fit the machine");
    }
    if (!sp.rl.skew || sp.batches.size() != 1)
        return infeasible("the spare layout's lines do not take skewed rows in one batch");
    // The spare's memory from the forward pass to the last reload: its
    // constant block and the map (cleared by every PE) stay; the rest is free.
    const int mem = static_cast<int>(std::min<uint32_t>(cfg.mem_bytes, 1u << 20));
    const int lo = sp.f.kblk + sp.f.kbs, ext = static_cast<int>(sp.f.ext_needed);
    if (sp.f.map < lo || lo + ext + sp.f.N > mem)
        return infeasible("the spilled columns do not fit the spare PE's free memory");
    sp.spare_base = lo;  // spill byte e at lo + e, beyond the map's start at lo + e + N
    sp.ext_needed = 0;
    if (forced) return sp;
    // Only where it is cheaper: the external transfers move the bytes of the
    // PEs holding a line (len * lines / ext_bytes_per_cycle per column and
    // direction), the spare's 3 cycles per byte each way, plus one
    // instruction per skewed round and the vote's two hops instead of one (4
    // ring instructions per backtrack step; the steps estimated as 3 * (KMAX
    // + D), 2.6x the headline's). With few lines the external path wins.
    const isa::CostTable& c = cfg.costs;
    const uint64_t A = uint64_t(fp.batches[0].lines) * uint64_t(std::max(1, fp.f.kinds));
    uint64_t ext_cost = 0, spare_cost = 16;  // set-up and the forward pass's mask
    for (const Transfer& t : sp.f.spills) {
        ext_cost += c.xfer_cycles(uint64_t(t.len), A);
        spare_cost += uint64_t(t.len) * (2 * c.mem + c.ring_hop) +
                      uint64_t(ceil_div(t.len, 8) + 1) * 2 * c.mask;
    }
    for (const Transfer& t : sp.f.reloads) {
        ext_cost += c.xfer_cycles(uint64_t(t.len), A);
        spare_cost += uint64_t(t.len) * (2 * c.mem + c.ring_hop) +
                      uint64_t(ceil_div(t.len, 7) + 1) * (c.mem + c.alu + 3 * c.mask);
    }
    spare_cost +=
        uint64_t(c.alu) * uint64_t((sp.rl.dmax - sp.rl.dmin + 1) + (sp.rl.smax - sp.rl.smin + 1));
    if (p.vote) spare_cost += 4ull * c.ring_hop * 3 * uint64_t(sp.f.kmax + p.D);
    return spare_cost < ext_cost ? sp : fp;
}

const std::vector<WaveGroup>& wave_groups() {
    // dp_forward.inc (NODE): the 16-bit shifted costs V of the node being
    // computed, two byte registers each: r1:r2 and r3:r4 take turns as M
    // (V(k-1, j), then the best of M and D) and Q (V(k-1, j+1)); r5:r6 the
    // running V(k, j) of the O chain (docs/firmware.md, section 2).
    static const std::vector<WaveGroup> g = {
        {"fwd_pair1", "forward", {1, 2}},
        {"fwd_pair2", "forward", {3, 4}},
        {"fwd_run", "forward", {5, 6}},
    };
    return g;
}

std::vector<std::pair<int, uint32_t>> param_block(const FramePlan& fp) {
    std::vector<std::pair<int, uint32_t>> v;
    v.emplace_back(0, static_cast<uint32_t>(fp.batches.size()));
    return v;
}

// ---- generated prelude ---------------------------------------------------------------------

namespace {

void equ(std::ostringstream& os, const char* name, int64_t v) {
    os << ".equ " << name << " " << v << "\n";
}

void dp_constants(std::ostringstream& os, const golden::Params& p, const ForwardPlan& f) {
    equ(os, "MODE", f.bidir ? 1 : 0);
    equ(os, "JOINT", f.joint ? 1 : 0);
    equ(os, "JM", f.bidir ? std::min(f.D - 1, f.N - 1 - f.s) : 0);  // top level of site s
    equ(os, "N", f.N);
    equ(os, "D", f.D);
    equ(os, "S", f.s);
    equ(os, "DS", f.ds);
    equ(os, "KM", p.km);
    equ(os, "KB", p.kb);
    equ(os, "GB", p.gb);
    equ(os, "ADMAX", std::min(255, p.ad_max));
    equ(os, "WO", p.Wo);
    equ(os, "WD", p.Wd);
    equ(os, "FRAME",
        p.frame == golden::Frame::Cyclopean ? 0
        : p.frame == golden::Frame::Left    ? 1
                                            : 2);
    equ(os, "VOTE", p.vote ? 1 : 0);
    equ(os, "KMAX", f.kmax);
    equ(os, "KLEFT", f.bidir ? f.K[0] : 0);
    equ(os, "KRIGHT", f.bidir ? f.K[1] : f.K[0]);
    equ(os, "KBLK", f.kblk);
    equ(os, "KBS", f.kbs);
    equ(os, "RB", f.rb);
    equ(os, "KR", f.kr);
    equ(os, "KL", f.kl);
    equ(os, "COSTL", f.costl);
    equ(os, "COSTH", f.costh);
    equ(os, "XO", f.xo);
    equ(os, "XM", f.xm);
    equ(os, "XD", f.xd);
    equ(os, "KPP", f.kpp);
    equ(os, "MAP", f.map);
    equ(os, "TINY", f.tiny ? 1 : 0);
    equ(os, "TTABLE", f.ext_table);
    equ(os, "TBUF0", f.tiny_buf[0]);
    equ(os, "TBUF1", f.tiny_buf[1]);
    equ(os, "TBUF2", f.tiny_buf[2]);
    // the left wavefront's last output position + 1 (the merge band ends there)
    int band = 0;
    if (f.bidir) {
        const int fr = p.frame == golden::Frame::Cyclopean ? 0
                       : p.frame == golden::Frame::Left    ? 1
                                                           : 2;
        const int e = f.joint ? f.s : f.s - 1;  // the left PE's last event site
        const int last = fr == 0 ? e + (f.D - 1) / 2 : fr == 1 ? e + f.D - 1 : e;
        band = std::min(f.N, last + 1);
    }
    equ(os, "BANDE", band);
    equ(os, "KC", f.kc);
    equ(os, "CENSUS", f.census);
    equ(os, "CO", f.co);
    equ(os, "AGG", f.agg);
    equ(os, "RBR", f.rbr);
    equ(os, "RBL", f.rbl);
    equ(os, "CNO", f.agg > 0 ? f.cxo : f.co);
    equ(os, "BT", f.bt ? 1 : 0);
    equ(os, "BLO", f.blo);
    equ(os, "BHI", f.bhi);
    equ(os, "AGGR", f.rows ? 1 : 0);
    equ(os, "AGGY", f.aggy);
    equ(os, "WL", f.wl);
    equ(os, "WH", f.wh);
    equ(os, "PMAX", f.pmax);
    equ(os, "H8", f.h8 ? 1 : 0);
    equ(os, "D8", f.d8 ? 1 : 0);
    equ(os, "EXCHN", f.bidir ? std::max(0, std::min(f.N - 1 - f.s, f.D - (f.joint ? 1 : 2))) : 0);
}

// Site of R'[m] / L'[m] of a kind (docs/firmware.md, sections 1 and 10).
int site_r(const ForwardPlan& f, int kind, int m) {
    if (!f.bidir) return m - 1;
    if (f.joint) return kind == 0 ? m - 1 : f.N - m;
    return kind == 0 ? f.s - m : f.s + m;
}
int site_l(const ForwardPlan& f, int kind, int m) {
    if (!f.bidir) return m - 1;
    if (f.joint) return kind == 0 ? m - 1 : f.N + f.D - 1 - m;
    return kind == 0 ? f.s + f.D - 1 - m : f.s + m;
}
// Where the input re-layout stored pixel X of R / L (the holder kind: X <= s
// on kind 0, X > s on kind 1; relayout.inc, RIN_RECV_INIT).
int holder(const ForwardPlan& f, int X) {
    return f.bidir && X > f.s ? 1 : 0;
}
int addr_r(const ForwardPlan& f, int X) {
    const int h = holder(f, X);
    if (!f.bidir) return f.rb - 1 - X;
    if (f.joint) return h == 0 ? f.rb - 1 - X : f.rb - f.N + X;
    return h == 0 ? f.rb - f.s + X : f.rb + f.s - X;
}
int addr_l(const ForwardPlan& f, int X) {
    const int h = holder(f, X);
    if (!f.bidir) return f.rb + 2 + X;
    if (f.joint) return h == 0 ? f.rb + 2 + X : f.rb + f.N + f.D - X;
    return h == 0 ? f.rb + f.s + f.D - X : f.rb + 1 - f.s + X;
}

// The extended, clamped line buffers of the aggregation window
// (AGG_EXTEND in census.inc): one AGX line per destination byte, with the
// source address of each kind and whether it is the kind's own byte (else
// the partner's, one ring hop away).
void agg_macros(std::ostringstream& os, const ForwardPlan& f) {
    os << ".macro PLAN_AGG\n";
    if (f.agg > 0) {
        auto clampx = [&](int X) { return std::max(0, std::min(f.N - 1, X)); };
        for (int img = 0; img < 2; ++img) {
            const int top = img == 0 ? f.kr : f.kl;
            for (int m = 1 - f.agg; m <= top + f.agg; ++m) {
                const int dest = img == 0 ? f.rbr - m : f.rbl + m;
                os << "        AGX " << dest;
                for (int kind = 0; kind < 2; ++kind) {
                    const int kk = f.kinds == 2 ? kind : 0;
                    const int X = clampx(img == 0 ? site_r(f, kk, m) : site_l(f, kk, m));
                    const int src = img == 0 ? addr_r(f, X) : addr_l(f, X);
                    os << ", " << src << ", " << (holder(f, X) == kk ? 1 : 0);
                }
                os << "\n";
            }
        }
    }
    os << ".endm\n";
}

// The Birchfield-Tomasi bounds (BT_BOUNDS in census.inc): one BTX line per
// byte the node reads (the line buffers, or the window's copies), with the
// three pixels X-1, X, X+1 of its site X (clamped into the ROI, as
// docs/golden.md requires) on each kind: address and whether it is the
// kind's own byte (else the partner's, one ring hop away).
void bt_macros(std::ostringstream& os, const ForwardPlan& f) {
    os << ".macro PLAN_BT\n";
    if (f.bt) {
        auto clampx = [&](int X) { return std::max(0, std::min(f.N - 1, X)); };
        for (int img = 0; img < 2; ++img) {
            const int top = img == 0 ? f.kr : f.kl;
            for (int m = f.agg > 0 ? 1 - f.agg : 0; m <= top + f.agg; ++m) {
                const int dest = img == 0 ? f.rbr - m : f.rbl + m;
                os << "        BTX " << dest;
                for (int kind = 0; kind < 2; ++kind) {
                    const int kk = f.kinds == 2 ? kind : 0;
                    const int X = clampx(img == 0 ? site_r(f, kk, m) : site_l(f, kk, m));
                    for (int u = -1; u <= 1; ++u) {
                        const int Y = clampx(X + u);
                        const int src = img == 0 ? addr_r(f, Y) : addr_l(f, Y);
                        os << ", " << src << ", " << (holder(f, Y) == kk ? 1 : 0);
                    }
                }
                os << "\n";
            }
        }
    }
    os << ".endm\n";
}

// spare_base >= 0: the spilled columns go to the spare PE's memory (RSPILL /
// RRELOAD over one ring hop) instead of xst / xld: spill byte e at
// spare_base + e, skipping the map (cleared by every PE before the backtrack).
void spare_transfer(std::ostringstream& os, const ForwardPlan& f, int spare_base, const char* op,
                    const Transfer& t) {
    const int cut = f.map - spare_base;  // spill bytes below the map
    auto emit = [&](int local, int e, int len) {
        if (len > 0)
            os << "        " << op << " " << local << ", " << spare_base + e + (e >= cut ? f.N : 0)
               << ", " << len << "\n";
    };
    if (t.ext < cut && t.ext + t.len > cut) {
        emit(t.local, t.ext, cut - t.ext);
        emit(t.local + cut - t.ext, cut, t.ext + t.len - cut);
    } else {
        emit(t.local, t.ext, t.len);
    }
}

void dp_macros(std::ostringstream& os, const ForwardPlan& f, int spare_base = -1) {
    agg_macros(os, f);
    bt_macros(os, f);
    os << ".macro PLAN_FORWARD\n";
    size_t si = 0;
    for (size_t i = 0; i < f.passes.size(); ++i) {
        const ForwardPass& ps = f.passes[i];
        os << "        FCOL " << ps.k << ", " << ps.kind << ", " << ps.jlo << ", " << ps.n << ", "
           << (ps.donly ? 1 : 0) << ", " << (ps.pad ? 1 : 0) << ", " << ps.addr << ", " << ps.rfull
           << ", " << ps.rinc << "\n";
        while (si < f.spills.size() && f.spills[si].after == static_cast<int>(i)) {
            const Transfer& t = f.spills[si++];
            if (spare_base >= 0)
                spare_transfer(os, f, spare_base, "RSPILL", t);
            else
                os << "        FSPILL " << t.local << ", " << t.ext << ", " << t.len << "\n";
        }
    }
    os << "        FEND\n.endm\n";
    os << ".macro PLAN_RELOAD\n.endm\n";
    os << ".macro PLAN_BACK\n";
    for (int k = f.kmax; k >= 1; --k) {
        if (f.tiny) {
            int size = 0, ext_addr = -1;
            for (int p = 0; p < f.kinds; ++p)
                if (f.ptr[p][k].bytes > 0) ext_addr = f.ptr[p][k].ext;
            for (const ForwardPass& ps : f.passes)
                if (ps.k == k) size = std::max(size, ps.bytes);
            if (ext_addr >= 0) os << "        TRELOAD " << ext_addr << ", " << size << "\n";
        }
        for (const Transfer& t : f.reloads) {
            if (t.after != k) continue;
            if (spare_base >= 0)
                spare_transfer(os, f, spare_base, "RRELOAD", t);
            else
                os << "        FRELOAD " << t.local << ", " << t.ext << ", " << t.len << "\n";
        }
        int addr = -1, maxb = 0, base[2] = {0, 0}, act[2] = {0, 0};
        for (int p = 0; p < f.kinds; ++p) {
            const PointerColumn& c = f.ptr[p][k];
            if (k > f.K[p] || c.bytes == 0) continue;
            addr = c.addr;
            base[p] = c.base;
            act[p] = 1;
            maxb = std::max(maxb, c.bytes);
        }
        os << "        BCOL " << k << ", " << addr << ", " << base[0] << ", " << base[1] << ", "
           << maxb - 1 << ", " << act[0] << ", " << act[1] << "\n";
    }
    os << ".endm\n";
}

}  // namespace

std::string frame_source(const golden::Params& p, const FramePlan& fp) {
    std::ostringstream os;
    os << "; Generated by the firmware planner (firmware/src/plan.cpp) for one parameter set:\n"
          "; the constants and the per-column plan of dp.s (docs/firmware.md).\n";
    dp_constants(os, p, fp.f);
    equ(os, "P", fp.P);
    equ(os, "HROI", fp.roi.h);
    equ(os, "X0", fp.roi.x0);
    equ(os, "Y0", fp.roi.y0);
    equ(os, "NSEG", fp.nseg);
    equ(os, "LPB", fp.lpb);
    // The batches (dp.s BATCH_LINES / BATCH_OUT): every batch but the last
    // outputs BSTRIDE lines; with BOVERLAP it also holds one line either side.
    const bool multi = !fp.f.tiny && fp.batches.size() > 1;
    equ(os, "BSTRIDE", multi ? fp.batches[0].out_count : fp.roi.h);
    equ(os, "BOVERLAP", multi && fp.batches[1].out_first == 1 ? 1 : 0);
    equ(os, "HBMAX", fp.hbmax);
    equ(os, "INL", fp.inl);
    equ(os, "INR", fp.inr);
    equ(os, "OUT", fp.out);
    equ(os, "SPLIT_IN", fp.split_in ? 1 : 0);
    equ(os, "CINL", fp.cinl);
    equ(os, "CINR", fp.cinr);
    equ(os, "RMOD", fp.rl.modular ? 1 : 0);
    equ(os, "BP", fp.rl.base);
    equ(os, "UR", fp.rl.ur);
    equ(os, "UL", fp.rl.ul);
    equ(os, "SKEW", fp.rl.skew ? 1 : 0);
    equ(os, "SKI", fp.rl.skew_in);
    equ(os, "SKO", fp.rl.skew_out);
    equ(os, "SKX", fp.rl.base - fp.rl.skew_in - fp.rl.dmin);
    equ(os, "DMIN", fp.rl.dmin);
    equ(os, "DMAX", fp.rl.dmax);
    equ(os, "SPARE", fp.spare ? 1 : 0);
    dp_macros(os, fp.f, fp.spare ? fp.spare_base : -1);
    // Per-segment re-layout calls: segment, width, receiver lanes of both kinds.
    os << ".macro PLAN_IN\n";
    for (int g = 0; g < fp.nseg; ++g) {
        const int W = seg_width(fp, g);
        int a0, n0, a1 = 0, n1 = 0;
        in_lanes(fp.f, fp.P, g, W, 0, &a0, &n0);
        if (fp.f.bidir) in_lanes(fp.f, fp.P, g, W, 1, &a1, &n1);
        os << (fp.f.census > 0 ? "        RELAYOUT_IN_CENSUS " : "        RELAYOUT_IN ") << g
           << ", " << W << ", " << a0 << ", " << n0 << ", " << a1 << ", " << n1 << "\n";
    }
    os << ".endm\n";
    os << ".macro PLAN_OUT\n";
    for (int g = 0; g < fp.nseg; ++g) {
        const int W = seg_width(fp, g);
        // displacement sigma = sender - receiver of the output items
        int smin = INT_MAX, smax = INT_MIN;
        const int span = fp.span();
        if (fp.rl.skew) {
            smin = fp.rl.smin;
            smax = fp.rl.smax;
        } else if (fp.rl.modular) {
            // one displacement per class mod P (and of one parity in bidir mode)
            if (span == 2) {
                smin = -fp.P / 2 + 1;
                if (smin % 2 != 0) ++smin;  // the items' displacements are even (BP = 0)
                smax = smin + fp.P - 2;
            } else {
                smin = -fp.P / 2 + 1;
                smax = fp.P / 2;
            }
        } else {
            for (int y = 0; y < fp.hbmax; ++y)
                for (int x = 0; x < W; ++x) {
                    const int X = g * fp.P + x;
                    const int pos = fp.rl.base + span * y + (span == 2 ? (X & 1) : 0);
                    smin = std::min(smin, pos - x);
                    smax = std::max(smax, pos - x);
                }
        }
        os << "        RELAYOUT_OUT " << g << ", " << W << ", " << smin << ", " << smax << "\n";
    }
    os << ".endm\n";
    os << ".include \"dp.s\"\n";
    return os.str();
}

isa::Program assemble_frame(const golden::Params& p, const FramePlan& fp) {
    isa::AsmOptions o;
    o.files = &firmware_sources();
    return isa::assemble_string(frame_source(p, fp), firmware_dir() + "/dp_plan.s", o);
}

isa::Program assemble_test(const golden::Params& p, const ForwardPlan& f, const std::string& file,
                           int lines, int P) {
    std::ostringstream os;
    dp_constants(os, p, f);
    equ(os, "P", P);
    equ(os, "HB", lines);
    equ(os, "HROI", lines);
    dp_macros(os, f);
    os << ".include \"" << file << "\"\n";
    isa::AsmOptions o;
    o.files = &firmware_sources();
    return isa::assemble_string(os.str(), firmware_dir() + "/test_plan.s", o);
}

}  // namespace imap::firmware
