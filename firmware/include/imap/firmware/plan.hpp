// Host side of the DP firmware: the range checks that make the 16-bit
// wrap-around costs exact, the per-column schedule of the forward pass, the
// per-PE memory plan (pointer columns on chip, in the dead part of the line
// buffers, or spilled to the external memory), the batches, the
// re-layout geometry and its lower bound, and the assembly of the firmware
// with a generated prelude of constants and per-column macro calls
// (docs/firmware.md).
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "imap/golden/params.hpp"
#include "imap/golden/stereo.hpp"
#include "imap/isa/config.hpp"
#include "imap/isa/program.hpp"

namespace imap::firmware {

// A parameter set the firmware cannot run (range or memory); the message
// says what is needed and what is available.
class FirmwareError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Accepted cost range (docs/firmware.md, section 2): every compared pair of
// candidates differs by at most max(Wm_max, Wo + Wd), which must stay below
// half the 16-bit range.
inline constexpr int64_t kMaxSpread = 32766;

// One pass of the forward pass over column k: slots jlo .. jlo + n - 1 of
// every PE of `kind` (-1: all kinds at once); kind p's level j is slot
// j + ForwardPlan::lsh[p].
struct ForwardPass {
    int k = 0;
    int kind = -1;
    int jlo = 0, n = 0;
    bool donly = false;  // the first slot has only its D source
    int pad = 0;         // bit p: kind p reaches level D-1 here (its pad after the pass)
    // A split pass (kind -1): kind `late` starts `split` slots after jlo
    // (its first slot set up there, D only if ldonly); the other kind starts
    // at jlo. split 0: both start at jlo.
    int split = 0, late = -1;
    bool ldonly = false;
    int addr = 0;   // local address of the pass's pointer bytes (or of the staging area)
    int bytes = 0;  // ceil(n / 4)
    // The window's match costs (AGG_BODY, dp_forward.inc): the first `rfull`
    // slots and those after rfull + rinc are summed whole; the `rinc` slots
    // between them, which every kind of the pass computed in the previous
    // column, update that column's sum (the site entering the window minus
    // the one leaving it).
    int rfull = 0, rinc = 0;
};

// Where the pointer bytes of column k of a kind are during the backtrack.
struct PointerColumn {
    int addr = -1;  // local address
    int base = 0;   // level of the first slot (pointer of level j: slot j - base)
    int bytes = 0;  // bytes holding this kind's pointers
    int ext = -1;   // external address if the column was spilled, else -1
};

// A block transfer: spill after pass `after` (xst) or reload after the
// forward pass (xld).
struct Transfer {
    int local = 0, ext = 0, len = 0, after = -1;
};

// Forward-pass plan of one scanline length N (shared by all lines).
struct ForwardPlan {
    int N = 0, D = 0;
    bool bidir = false;  // two PEs per line (bidir or joint)
    bool joint = false;  // SPEC A.9 joint: kind 0 = sites 0..s forward, kind 1 = s..N-1 mirrored
    int s = 0;           // seed column (bidir)
    int ds = -1;         // seed disparity, -1 = free
    int kinds = 1;       // 1 (single) or 2 (bidir: 0 = left wavefront, 1 = right)
    int K[2] = {0, 0};   // last column of each kind
    int kmax = 0;        // max(K)
    std::vector<int> lo[2], hi[2];      // level range of each kind at columns 0..K
    std::vector<ForwardPass> passes;    // in execution order
    std::vector<PointerColumn> ptr[2];  // per kind, columns 0..kmax (0 unused)
    std::vector<Transfer> spills, reloads;
    int64_t valid_states = 0;  // valid states of one line (both kinds)
    int64_t slots = 0;         // slots the passes compute (per PE)
    // Constants of the node (docs/firmware.md, section 2).
    int xo = 0, xm = 0, xd = 0;  // forcing offsets
    int kpp = 0;                 // kb*gb - Wd - Wo (16-bit two's complement)
    // Memory (local addresses per PE).
    int kblk = 0;                // per-PE constant block
    int kbs = 10;                // its size (the census adds its popcount table)
    int rb = 0, kr = 0, kl = 0;  // R'[i] at rb - i (i <= kr), L'[i] at rb + 1 + i + lsh (<= kl)
    int costl = 0, costh = 0;    // cost planes (slots 0..D + the larger lsh, pad included)
    // Kind p's level j at slot j + lsh[p] of the cost planes, its L'[i] at
    // rb + 1 + i + lsh[p]: slots apart let the kinds' passes share columns
    // whose first levels differ (split passes; docs/firmware.md, section 2).
    int lsh[2] = {0, 0};
    int preg = 0;  // start of the pointer region
    // SPEC A.9 census (docs/firmware.md, section 10): radius (0 = off), and
    // the census codes of R' and L' at the line buffers' addresses + co.
    int census = 0, kc = 0, co = 0;
    // SPEC A.9 horizontal aggregation (agg-rx > 0): the node reads extended,
    // clamped copies of the line buffers, Rx[m] at rbr - m, Lx[m] at rbl + m
    // (m from 1 - agg to kr + agg / kl + agg), codes at + cxo.
    int agg = 0, rbr = 0, rbl = 0, cxo = 0;
    // SPEC A.9 dissim bt: the Birchfield-Tomasi bounds lo/hi of every byte the
    // node reads (line buffers, or the window's copies) at its address + blo / + bhi.
    bool bt = false;
    int blo = 0, bhi = 0;
    // SPEC A.9 window (agg-rx or agg-ry > 0, docs/firmware.md, section 10):
    // before each column pass, every PE computes its line's row sums H(k, j)
    // over the window's sites (or their change from column k - 1), adds those
    // of the lines y-aggy..y+aggy (the same-kind PEs span hops away, clamped
    // into the ROI) and stores the match cost at wl + j / wh + j. h8: every
    // row sum fits one byte; d8: every change, biased by pmax, does.
    int aggy = 0, wl = 0, wh = 0, pmax = 0;
    bool rows = false, h8 = false, d8 = false;
    int agg_src = 0;  // the re-layout's buffers (rb, co) then sit at the top: agg_src..mem
    int map = 0;      // output line (N bytes) during the backtrack and after
    // Step-synchronous backtrack (docs/firmware.md, section 4): each PE walks
    // its own path, reading column k's pointers at the slot address
    // bstep_a[kind][k] = 4 * address - base (16 bit) from a table at
    // bstep_tab (low bytes, columns 0..kmax) and bstep_tab + kmax + 1 (high
    // bytes); -1: the column-synchronous backtrack (spilled or reloaded
    // columns, arrays of 2 to 5 PEs, kmax > 255, or no room for the table).
    int bstep_tab = -1;
    std::vector<int> bstep_a[2];
    int bstep_k0[2] = {0, 0};  // the first column each kind steps in
    int mem_needed = 0;
    int64_t ext_needed = 0;
    // 2 to 5 PEs with the vote across batches: one line per batch, pointer
    // tables in three rotating external slots of ext_table bytes, the
    // backtrack's own and neighbour columns reloaded into tiny_buf.
    bool tiny = false;
    int ext_table = 0;
    int tiny_buf[3] = {0, 0, 0};

    int rp_addr(int i) const { return rb - i; }
    int lp_addr(int i, int kind) const { return rb + 1 + i + lsh[kind]; }
    // Level range of line buffer L' used by kind `kind` of the DP (for tests).
    // Pointer of state (k, j) of a kind as the golden encodes it (M 0, D 1,
    // O 2), read through `mem` (local memory) or `ext` (external memory) of
    // one PE at the end of the forward pass.
    uint8_t pointer(int kind, int k, int j, const std::function<uint8_t(uint32_t)>& mem,
                    const std::function<uint8_t(uint32_t)>& ext) const;
};

// The part of `p` the firmware runs (docs/firmware.md, section 10): the
// same parameters with the SPEC A.9 options it does not implement turned
// off; --ad-max, --mode joint, --dissim bt, the census and the window stay.
// For the trade-off table's measured part; a parameter set with other
// options is refused by plan_frame.
golden::Params firmware_part(const golden::Params& p);

// Checks the cost range and plans the forward pass and its memory for
// scanlines of length N (lines on consecutive PEs, the test layout); throws
// FirmwareError when the set does not fit `cfg`.
ForwardPlan plan_forward(const golden::Params& p, int N, const isa::MachineConfig& cfg);

// The planner's model of the forward pass with each kind's columns split
// over the PE pair (docs/firmware.md, section 7; not run by the firmware
// yet). Column k of kind p splits at the level boundary m_p(k) = m[p] -
// (k - 1), one level lower each column: its levels below the boundary (the
// lower part) run on the kind's own PE at step k, the others (the upper
// part) on the partner PE at step k + 1. Every state's sources are then on
// the same PE one step or one node earlier, except one 16-bit value a kind
// and step (the lower part's top, E(k, m_p(k) - 1)) that moves one hop.
// Addresses are broadcast, so each part keeps a fixed level-to-address
// offset (the cost planes stay in place) and a step's pass runs over the
// hull of both PEs' addresses. On the PE of kind q, its own lower part's
// level j sits at j + sigma[q], the partner kind's upper part's at j +
// tau[q]: above the lower part and touching it at the boundary (both fall
// one level a step), or with upper_first[q] below it, apart for the whole
// pass (the upper part's top node reads the level above it) and, unless
// indexed_l, apart in the L' bytes too: a node at address x of step k reads
// L' at k + x (broadcast), so each PE's L' buffer holds its own kind's and
// the partner kind's bytes side by side; with indexed_l the node reads L'
// through a per-PE offset register (`ldx`, one cycle more a node) and the
// L' bytes do not constrain the layout. Node times of one PE; single mode
// (one kind) has no pair: split = balanced = passes.
struct PairSchedule {
    int64_t passes = 0;    // today's passes (the plan's slots)
    int64_t even = 0;      // half of both kinds' valid reachable states (rounded up)
    int64_t balanced = 0;  // least sum over the steps of the larger PE's node count
    int64_t split = 0;     // least sum over the steps of the pass's address hull
    int m[2] = {0, 0};     // the split's boundaries at column 1
    bool upper_first[2] = {false, false};
    int sigma[2] = {0, 0}, tau[2] = {0, 0};
    int steps = 0;  // columns 1 .. kmax + 1
    bool indexed_l = false;
};
PairSchedule pair_schedule(const ForwardPlan& f, bool indexed_l = false);

// The split schedule laid out for the forward harness (dp_split_test.s,
// dp_split.inc; bidir with a free seed disparity and the default node, the
// L' bytes read by broadcast address). Slots of the cost planes: a part's
// level j at slot j + off.
struct SplitPart {
    int kind = -1, col = 0, lo = 0, hi = -1, off = 0;
    bool upper = false;  // the partner kind's upper part (else the PE's own lower part)
    int lx = 0;          // indexed: its L' offset (the node reads L' at lx + c2 + slot)
    bool none() const { return hi < lo; }
};
struct SplitStep {
    int k = 0;             // column k's lower parts, column k - 1's upper parts
    int x0 = 0, n = 0;     // the pass's first slot and its nodes
    int addr = 0;          // its pointer bytes, 2 per 8 nodes (first node in the top bits)
    SplitPart part[2][2];  // per PE kind q: [0] its lower part, [1] the partner kind's upper part
};
struct SplitForward {
    PairSchedule s;
    int shift = 0;  // slots = the schedule's addresses (sigma, tau) + shift
    // R'[i] of the PE's own kind at rbr - i, of its partner kind at rbr2 - i
    int rbr = 0, rbr2 = 0;
    bool indexed = false;  // the node reads L' through its part's offset (ldx)
    // broadcast: a node of step k at slot x reads L' at rbl + k + x - v0;
    // indexed: at lx + cbase + k + x, kind 0's L'[i] at rl + i, kind 1's at
    // ru + i (on every PE)
    int rbl = 0, v0 = 0, rl = 0, ru = 0, cbase = 0;
    int lbytes = 0;  // L' bytes per PE
    int sent = 0;    // 6 bytes: the partner kind's last two lower-part tops, the offset
    int costl = 0, costh = 0, slots = 0;
    int preg = 0, mem_needed = 0;
    std::vector<SplitStep> steps;
};
// Throws FirmwareError for a plan the harness does not run (single or joint
// mode, a fixed seed disparity, the SPEC A.9 options).
SplitForward plan_split_forward(const golden::Params& p, const ForwardPlan& f,
                                bool indexed = false);
isa::Program assemble_split_test(const golden::Params& p, const ForwardPlan& f,
                                 const SplitForward& sf, int lines, int P);

// Folder of the firmware sources as the assembler names them ("firmware/asm"):
// the sources are compiled into the library (firmware_sources()), so
// diagnostics and fault messages name firmware/asm/FILE:LINE wherever the
// binary runs.
std::string firmware_dir();
// The firmware sources by path (firmware_dir() + "/" + file name), for
// isa::AsmOptions::files.
const std::map<std::string, std::string>& firmware_sources();
// `text` (assembled as if it were in firmware_dir()) with every .include of
// a firmware source replaced by that source's text, recursively: a program
// that assembles anywhere, without the firmware's files.
std::string inline_firmware_includes(const std::string& text);

// One batch of ROI lines processed together (lines first .. first+lines-1,
// of which out_count starting at batch line out_first are written out).
struct Batch {
    int first = 0, lines = 0, out_first = 0, out_count = 0;
};

// Re-layout geometry (docs/firmware.md, section 5).
struct Relayout {
    bool modular = false;  // the lines fill the ring: routes take the shorter way round
    int base = 0;          // unrolled position of the first line's first PE
    int ur = 0, ul = 0;    // rounds of the rightward / leftward sweeps (input)
    int our = 0, oul = 0;  // rounds of the rightward / leftward sweeps (output)
    // Skewed rows (the lines do not fill the ring, one segment): line y's
    // video row comes in from column X0 - skew_in - span*y and goes out to
    // column -(skew_out + span*y), so every line's items share one
    // displacement per pixel: input rounds d = dmin .. dmax, output sigma =
    // smin .. smax (step span).
    bool skew = false;
    // Wrapped skewed rows: a row that passes the ring's end continues at
    // lane 0 (lanes taken mod P); input lines from ywi on take their wrapped
    // part from a second `vin`, output lines from ywo a second `vout`.
    bool wrap = false;
    int ywi = 0, ywo = 0;
    // Kind copies (bidir, skewed rows): each line's rows come in twice, row
    // 2y + kind for the PE of that kind, kind 1's copy from lane offset
    // skb + span*y (skb = first lane of kind 0 + 1 - first lane of kind 1),
    // so that every round serves both kinds: max(n0, n1) rounds instead of
    // about n0 + n1.
    bool copies = false;
    int skb = 0;
    // kind 1's copy: its lines below ybb start past the ring's end; the
    // first line whose row passes lane P - 1 among those (ywb1) and the
    // others (ywb2); relayout.inc VROWS
    int ybb = 0, ywb1 = 0, ywb2 = 0;
    int skew_in = 0, skew_out = 0;
    int dmin = 0, dmax = 0, smin = 0, smax = 0;
    // The planner's estimate of the skewed rows' input (video rows and
    // rounds, cycles as counted in relayout.inc), against which the
    // windowed rows are weighed in one-segment frames.
    int64_t skew_estimate = -1;
    // Windowed rows (bidir; the input only, the output keeps the direct
    // routes): copy k of line y comes in window by window, window t from
    // column X0 + t P - (k ? skb : 0) - skew_in - span*y, so pixel X of the
    // copy sits on lane (X + (k ? skb : 0) + skew_in + span*y) mod P and
    // every line's items share one displacement mod P per pixel (rounds
    // dmin .. dmax); window t of row q = span*y + k is stored at row index q
    // - P t + wrc (wsize rows per image), so round d's sender reads row lane
    // + d - base + wrc, whichever window its receiver's pixel lies in.
    bool windows = false;
    int wlo[2] = {0, 0}, whi[2] = {0, 0};  // the windows t of copy k
    int wrc = 0, wsize = 0;
    // Windowed output rows (several video segments): pixel x of line y goes
    // to lane (x + skew_out + span*y) mod P, rounds sigma = smin .. smax
    // (step 2 in bidir mode) over the whole line, d mod P hops; round i's
    // receiver stores at slot floor((lane + smin - base) / span) + orc + i,
    // which is row y - (P / span) t + orc of window t (osize rows); window t
    // of line y goes out from column t P - skew_out - span*y.
    bool owindows = false;
    int owlo = 0, owhi = 0, orc = 0, osize = 0;
    bool owrap = false;  // the slots' low byte (osize = 256 + rounds)
    // The re-layout's lower bound (relayout_bound), summed over batches:
    // bound = ring + mem; ring = the ring instructions' cycles (the larger
    // of the hop and cut bounds), hop = the byte-hop part of it, mem = the
    // loads at the senders and stores at the receivers.
    int64_t bound_in = 0, bound_out = 0;
    int64_t ring_bound_in = 0, ring_bound_out = 0;
    int64_t hop_bound_in = 0, hop_bound_out = 0;
    int64_t mem_bound_in = 0, mem_bound_out = 0;
};

// Everything the full firmware (dp.s) needs for one frame.
struct FramePlan {
    ForwardPlan f;
    golden::Roi roi;
    int P = 0;
    int lpb = 0;    // lines per batch
    int hbmax = 0;  // most lines in one batch
    int halo = 0;   // lines a batch holds either side of its output (several batches)
    int nseg = 0;   // segments of P pixels per ROI line
    int mem = 0;    // local memory per PE the plan fits in (bytes)
    int inl = 0, inr = 0, out = 0;  // video rows (local addresses)
    bool split_in = false;          // input re-layout one image at a time (memory)
    int rys = 1;                    // bytes between video rows (one skewed copy: row_stride)
    int ryso = 1;                   // bytes between output rows (skewed output: out_row_stride)
    int cinl = 0, cinr = 0;         // census code rows in the video layout (census on)
    int cscr = 0;                   // 3 bytes: the census's pixels of the segment beside
    Relayout rl;
    std::vector<Batch> batches;
    int mem_needed = 0;      // local bytes per PE
    int64_t ext_needed = 0;  // external bytes per PE
    // Single mode with spare PEs (docs/firmware.md, section 3): line y on PE
    // BP + 2y, the spilled pointer columns kept in the PE above it (the
    // spare) from local address spare_base on, not in the external memory.
    bool spare = false;
    int spare_base = 0;
    int span() const { return f.bidir || spare ? 2 : 1; }
    // which placements of the video rows the planner may take (RowLayout)
    int rows_allowed = 3;  // 0 direct only, 1 + skewed rows, 2 + wrapped, 3 + kind copies
};

// How the planner places the video rows (docs/firmware.md, section 5):
// Fastest weighs the direct routes, the skewed rows (around the ring) and
// the kind copies by its estimate of their cycles on the run's cost table;
// Direct never skews; Skewed and Wrapped take the skewed rows wherever they
// apply (unwrapped / around the ring), without kind copies (for measuring
// one placement against another).
enum class RowLayout { Direct = 0, Skewed = 1, Wrapped = 2, Fastest = 3 };

// Where single mode's spilled pointer columns go (docs/firmware.md,
// section 3): Cheaper picks the spare layout where it is feasible and its
// cost estimate beats the external path's; External never uses spares;
// Spare forces the spare layout (FirmwareError where it is not feasible).
enum class SpillLayout { Cheaper, External, Spare };

// How the forward pass runs the columns whose kinds start at different
// levels (docs/firmware.md, section 2): Fastest shifts the kinds' slots
// apart and runs split passes where its estimate favours them (bidir
// without the census, bt or the window); Masked keeps equal slots, one
// masked pass per kind there (for measuring one against the other).
enum class PassLayout { Fastest, Masked };

// Plans a frame: the forward plan, batches (overlapping at inner edges by
// the halo: the vote's line, the vertical window's and the census's), video rows, memory,
// re-layout. FirmwareError when the set cannot run on `cfg` (what is needed vs available).
FramePlan plan_frame(const golden::Params& p, const golden::Roi& roi, const isa::MachineConfig& cfg,
                     SpillLayout layout = SpillLayout::Cheaper, RowLayout rows = RowLayout::Fastest,
                     PassLayout passes = PassLayout::Fastest);

// Lower bound of the re-layout's cycles of a frame plan (docs/firmware.md,
// section 5), in and out, per batch and segment: the ring instructions (the
// larger of the byte-hop bound, every needed byte must cross its links and
// P bytes move one hop per ring_hop, and the cut bound, one byte per hop
// enters any arc of the ring) plus the memory instructions (a byte leaves a
// PE's memory by a load at its sender and enters the receiver's by a store,
// one byte per PE per instruction; the ring is the only path between PEs).
// Sets plan.rl's bound_*, ring_bound_*, hop_bound_*, mem_bound_*.
void relayout_bound(FramePlan& plan, const isa::CostTable& costs);

// The generated prelude of a frame plan: .equ constants and the PLAN_*
// macros (per-column calls of the forward pass, spills, reloads, backtrack
// columns), then `.include` of dp.s. Assembling this text is the firmware
// the frame runs.
std::string frame_source(const golden::Params& p, const FramePlan& plan);

// Assembles dp.s for a frame plan.
isa::Program assemble_frame(const golden::Params& p, const FramePlan& plan);

// Assembles a test program (dp_forward_test.s, dp_core_test.s) for a
// forward plan with lines on PEs 2y / 2y+1 (bidir) or y (single) and HB lines.
isa::Program assemble_test(const golden::Params& p, const ForwardPlan& plan,
                           const std::string& file, int lines, int P);

// The param block words of a frame plan (index, value): set before the run
// (imapsim exec --param INDEX=VALUE).
std::vector<std::pair<int, uint32_t>> param_block(const FramePlan& plan);

// Registers that the firmware uses together as one multi-byte value (a
// cost), low byte first: the waves' GTKWave view shows each group as one
// decimal vector (docs/waves.md). `phase` names the phase where the group
// holds that value (the registers are reused elsewhere).
struct WaveGroup {
    std::string name;       // e.g. "fwd_run"
    std::string phase;      // e.g. "forward"
    std::vector<int> regs;  // PE registers, low byte first
};
const std::vector<WaveGroup>& wave_groups();

}  // namespace imap::firmware
