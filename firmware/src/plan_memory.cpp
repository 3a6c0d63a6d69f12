// The fixed regions of a forward plan's per-PE memory (docs/firmware.md,
// section 3), from the parameters, the passes and mem_bytes: the constant
// block, the line buffers R' and L', the census codes and Birchfield-Tomasi
// bounds beside them, the window's extended copies (the re-layout's buffers
// then move to the top of the memory), the cost planes and the window's
// match-cost planes. The pointer region starts after them (f.preg);
// plan_pointers.cpp fills it.
#include <algorithm>
#include <sstream>

#include "imap/golden/cost.hpp"
#include "plan_internal.hpp"

namespace imap::firmware::detail {

namespace {

// per-PE constant block: K_KIND .. K_END and two re-layout bytes (dp_setup.inc checks it)
constexpr int kKBlockSize = 10;     // 8 constants + 2 bytes of the re-layout
constexpr int kPopTableBytes = 16;  // the census's popcount of a nibble (census.inc)
constexpr int kAggFlagBytes = 2;    // agg-ry: lines above / below in the ROI (dp_setup.inc)

// Line buffers: R' reversed below rb, L' above it, so that the consumed
// prefixes of both form one growing region (docs/firmware.md, section 3);
// then the cost planes.
void line_buffers(ForwardPlan& f, const golden::Params& p) {
    const int N = f.N;
    f.kblk = 0;
    f.kbs = kKBlockSize + (p.kc > 0 ? kPopTableBytes : 0) + (p.agg_ry > 0 ? kAggFlagBytes : 0);
    f.kr = f.kmax;
    // L' offsets the node reads (k + slot, whichever kind) and the ones the
    // re-layout fills (each kind's data, at its lsh)
    int kl = 0;
    for (const ForwardPass& ps : f.passes) kl = std::max(kl, ps.k + ps.jlo + ps.n - 1);
    if (f.joint)
        kl = std::max({kl, f.s + p.D + f.lsh[0], N + p.D - 2 - f.s + f.lsh[1]});
    else if (f.bidir)
        kl = std::max({kl, f.s + p.D - 1 + f.lsh[0], N - 1 - f.s + f.lsh[1]});
    else
        kl = std::max(kl, N);
    f.kl = kl;
    f.rb = f.kblk + f.kbs + f.kr;
    // cost planes: every slot a pass computes and the one above it (the
    // top slot's D source; the pad where a kind reaches level D-1)
    int planes = p.D + 1;
    for (const ForwardPass& ps : f.passes) planes = std::max(planes, ps.jlo + ps.n + 1);
    f.costl = f.rb + 2 + f.kl;
    f.costh = f.costl + planes;
    f.preg = f.costh + planes;
}

// The census codes and the bt bounds: regions the size of the line buffers,
// at their addresses + co / + blo / + bhi, below the pointer region.
void beside_buffers(ForwardPlan& f, const golden::Params& p) {
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
}

// The node reads extended, clamped copies of the line buffers (and codes):
// Rx[m], m = 1-a .. kr+a, at rbr - m, Lx[m], m = 1-a .. kl+a, at rbl + m,
// right after the constant block; then the costs. The re-layout's buffers
// (and codes) move to the top of the memory: they die when the copies are
// made (AGG_EXTEND, before the forward pass).
void window_copies(ForwardPlan& f, const golden::Params& p, int mem) {
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
    f.agg_src = mem - s0 * (p.kc > 0 ? 2 : 1);
    f.rb = f.agg_src + f.kr;
    f.co = p.kc > 0 ? s0 : 0;
    if (f.agg_src < f.costl) {
        std::ostringstream os;
        os << "does not fit: --agg-rx " << a << " needs at least "
           << f.costl + s0 * (p.kc > 0 ? 2 : 1)
           << " bytes of local memory per PE for the line buffers and their window copies"
           << (f.bt ? " (with the bt bounds)" : "") << " (have " << mem << ", mem_bytes)";
        throw FirmwareError(os.str());
    }
}

// The window: the match cost of every level of the column pass, computed
// before its nodes (AGG_BODY, dp_forward.inc), in two byte planes after the
// costs; below the pointer region.
void window_planes(ForwardPlan& f, const golden::Params& p) {
    f.rows = true;
    f.aggy = p.agg_ry;
    f.wl = f.preg;
    f.wh = f.wl + p.D;
    f.preg = f.wh + p.D;
    f.pmax = static_cast<int>(golden::pixel_cost_max(p));  // <= 32,766: check_range
    f.h8 = int64_t{2 * p.agg_rx + 1} * f.pmax <= 255;
    f.d8 = 2 * int64_t{f.pmax} <= 255;
}

}  // namespace

void place_regions(ForwardPlan& f, const golden::Params& p, const isa::MachineConfig& cfg) {
    const int mem = plan_mem(cfg);
    line_buffers(f, p);
    beside_buffers(f, p);
    if (p.agg_rx > 0) window_copies(f, p, mem);
    if (p.agg_rx > 0 || p.agg_ry > 0) window_planes(f, p);
    if (f.preg > mem) {
        std::ostringstream os;
        os << "does not fit: needs at least " << f.preg + 1
           << " bytes of local memory per PE for the line buffers"
           << (f.bt ? ", their bt bounds" : "") << " and costs (have " << mem << ", mem_bytes)";
        throw FirmwareError(os.str());
    }
}

}  // namespace imap::firmware::detail
