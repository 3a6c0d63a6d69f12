// The planner's internal interface (not part of include/imap/firmware): the
// steps and helpers one of its files decides and another uses. The frame
// plan (plan.cpp: checks, batches, rows, spill layout) starts from the
// forward plan (plan_forward.cpp: columns and passes, its fixed regions from
// plan_memory.cpp, its pointer columns from plan_pointers.cpp) and adds the
// re-layout geometry (plan_relayout.cpp); plan_prelude.cpp writes and
// assembles the generated source.
#pragma once

#include <algorithm>
#include <climits>
#include <cstdint>
#include <utility>
#include <vector>

#include "imap/firmware/plan.hpp"

namespace imap::firmware::detail {

inline constexpr int kNever = INT_MAX;  // an address that never holds pointers

inline int ceil_div(int a, int b) {
    return (a + b - 1) / b;
}

// a / b rounded towards minus infinity (b > 0).
inline int floor_div(int a, int b) {
    return a >= 0 ? a / b : -((-a + b - 1) / b);
}

// The local memory the planner uses per PE: mem_bytes, at most 1 MiB.
inline int plan_mem(const isa::MachineConfig& cfg) {
    return static_cast<int>(std::min<uint32_t>(cfg.mem_bytes, 1u << 20));
}

// The split forward (docs/firmware.md, section 7): kind p's column k with
// the boundary m at column 1 falling one level a column; the first level
// that runs on the partner (hi + 1: none, lo: the whole column).
inline int split_cut(const ForwardPlan& f, int p, int m, int k) {
    return std::clamp(m - (k - 1), f.lo[p][k], f.hi[p][k] + 1);
}

// The skewed senders keep their row index's low byte and step it alone
// (relayout.inc, SKNC 3) where q mod P, read a byte, wraps with it: with
// kind copies or one row a lane (span 1) P a multiple of 256 or a power of
// two below; one copy at span 2 (index q mod P / 2) a multiple of 512 or a
// power of two up to 256. relayout.inc checks the same on its own.
inline bool index_steps_a_byte(int P, bool copies, int span) {
    const int wrap = copies || span == 1 ? 256 : 512;
    return P % wrap == 0 || 256 % P == 0;
}

// The one copy of the skewed rows (relayout.inc, RYS): the senders keep
// their row index scaled by RYS = 256 / R, so that it wraps with its byte
// at R rows and steps without a mask; the rows sit RYS bytes apart, the two
// images' interleaved (INR = INL + 1). R = P / span where that is below 256
// rows, else 128: where span * R divides P, q mod (span * R) names the same
// row as q mod P for the batch's lines (at most R). The rows start at the
// cost planes (no census, no window: `inl` = costl) and take 256 bytes
// there, with the byte above them in memory as the unclamped senders read
// (SKNC 3). Else 1 (one byte apart, the index masked where it wraps below
// 256 rows). From the plan's machine, batches and options (not yet its
// placement: plan_skew weighs the stride before place_rows takes it).
inline int row_stride(const FramePlan& fp, int mem) {
    const ForwardPlan& f = fp.f;
    const int P = fp.P, span = fp.span();
    if (f.census > 0 || f.agg > 0 || f.aggy > 0 || f.costl + 256 >= mem ||
        !index_steps_a_byte(P, false, span))
        return 1;
    const int rows = P / span < 256 ? P / span : 128;
    if (rows < 2 || fp.hbmax > rows || 256 % rows != 0) return 1;
    return 256 / rows;
}

// The skewed output's rows (relayout.inc, RYSO, skewed output with OSKB):
// where the receivers' row index wraps below 256 rows (P / span rows), the
// rows sit 256 / (P / span) bytes apart and the receivers keep the index at
// that scale, so it wraps with its byte and steps without a mask. Needs the
// 256 bytes of the output rows where place_rows puts them (after the
// constant block, or after the map where they would meet it). Else 1.
inline int out_row_stride(int P, int span, bool spare, int kbs, int map, int N, int mem) {
    const int rows = P / span;
    if (spare || !index_steps_a_byte(P, false, span) || P % span != 0 || rows < 2 || rows >= 256 ||
        256 % rows != 0)
        return 1;
    int out = kbs;
    if (out < map + N && out + 256 > map) out = map + N;
    return out + 256 <= mem ? 256 / rows : 1;
}

// ---- plan.cpp ----
// The largest match cost (SPEC A.9): the window's terms times the largest pixel term.
int64_t wm_max(const golden::Params& p);
// Refuses a cost spread beyond the 16-bit costs' range (kMaxSpread).
void check_range(const golden::Params& p);
// Refuses the SPEC A.9 options the firmware does not run (census_ok: the
// full firmware, else the forward-pass test layout).
void check_options(const golden::Params& p, bool census_ok);

// ---- plan_relayout.cpp ----
// Pixels x of [lo, hi] (hi - lo < P, 1 <= len <= P) whose lane x + off
// (mod P; off any integer) lies in the arc [a, a + len) of the ring of P
// lanes, appended to *iv as disjoint intervals of x (the cut bound's
// pixels already inside an arc, relayout_bound).
void arc_pixels(int P, int lo, int hi, int off, int a, int len,
                std::vector<std::pair<int, int>>* iv);

// ---- plan_forward.cpp ----
// The forward plan of scanlines of length N; `tiny`: every pointer table in
// the external memory (arrays of 2 to 5 PEs with the vote); `split`: the
// kinds' slots may shift apart for split passes (PassLayout::Fastest).
ForwardPlan plan_forward_impl(const golden::Params& p, int N, const isa::MachineConfig& cfg,
                              bool tiny, bool census_ok, bool split = true);
// Whether pass `ps` computes slots of kind p.
inline bool runs_on(const ForwardPlan& f, const ForwardPass& ps, int p) {
    return (ps.kind == p || ps.kind == -1) && ps.k <= f.K[p];
}

// ---- plan_memory.cpp ----
// The fixed regions of the per-PE memory: constant block, line buffers, the
// census codes and bt bounds beside them, the window's copies, the cost and
// window planes, up to the pointer region at f.preg. FirmwareError when they
// do not fit mem_bytes.
void place_regions(ForwardPlan& f, const golden::Params& p, const isa::MachineConfig& cfg);

// ---- plan_pointers.cpp ----
// Places the pointer columns, the output line and the spills and reloads in
// the local memory (the fewest spilled columns, or with `tiny` every table in the
// external memory); FirmwareError naming the least local memory that would do,
// or the external memory the spills need.
void place_columns(ForwardPlan& f, const isa::MachineConfig& cfg, bool tiny);
// Column k's pointer bytes (the widest of its passes) and the external
// address they were spilled to (-1: on chip).
struct ColumnBytes {
    int size = 0, ext = -1;
};
ColumnBytes column_bytes(const ForwardPlan& f, int k);

// ---- plan_relayout.cpp ----
int seg_width(const FramePlan& fp, int g);
// Source lanes [a, a + n) of segment g (width W) whose pixels go to kind `kind` (input).
void in_lanes(const ForwardPlan& f, int P, int g, int W, int kind, int* a, int* n);
// The re-layout geometry of a frame with its batches and segments planned (fp.rl).
void plan_relayout(FramePlan& fp, int mem, const isa::CostTable& costs);
// The displacements sigma = sender - receiver of segment g's output items.
void out_displacements(const FramePlan& fp, int g, int* smin, int* smax);

}  // namespace imap::firmware::detail
