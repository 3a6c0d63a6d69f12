// The planner's entry (plan_frame) and its refusals. The checks that refuse
// what the firmware cannot run exactly (SPEC A.9 options, the 16-bit cost
// range), from the parameters; then the frame plan (FramePlan) of a ROI on a
// machine: lines per batch and the batches (overlapping at inner edges by
// the halo, one line at a time on arrays of 2 to 5 PEs with the vote), the
// video, census-code and output rows in the local memory, and where single
// mode's spilled pointer columns go (the external memory or the spare PE
// above each line, whichever the cost estimate prefers). The forward plan
// comes from plan_forward.cpp, the re-layout geometry from plan_relayout.cpp.
#include <algorithm>
#include <sstream>

#include "imap/golden/cost.hpp"
#include "plan_internal.hpp"

namespace imap::firmware {

namespace detail {

// The largest match cost (SPEC A.9): the window's terms times the largest pixel term.
int64_t wm_max(const golden::Params& p) {
    return golden::window_terms(p) * golden::pixel_cost_max(p);
}

// The cost spread the 16-bit costs hold exactly (docs/firmware.md, section 2).
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

}  // namespace detail

namespace {

using detail::ceil_div;

// The most lines a batch holds, whatever the PE count: the re-layout
// addresses line y's video and output rows with a one-byte per-PE index
// (relayout.inc: ldx / stx [r14 + row], y in 0..255). Measured with the cap
// lifted (64x300 ROI on 1024 PEs, single mode): without the vote line 256 is
// the first wrong one, with it line 255 (its vote reads line 256). Lines per
// batch = min(P / span, this).
constexpr int kMaxBatchLines = 255;

// The lines a batch holds beyond the ones it outputs, on each side at an
// inner batch edge (the halo): an output line y needs the paths of y -+ 1
// for the vote, their match costs the window's lines y -+ 1 -+ agg_ry, and
// those lines' census codes the lines r further out. A halo line's own
// values, clamped at the batch's edge, are never output.
int batch_halo(const golden::Params& p) {
    return (p.vote ? 1 : 0) + p.agg_ry + (p.kc > 0 ? p.census : 0);
}

// Batches too short for their halo: what the halo is made of and what
// would hold it (more PEs, or a ROI in one batch).
FirmwareError too_few_for_the_halo(const FramePlan& fp, const golden::Params& p, int span) {
    const int halo = batch_halo(p);
    std::ostringstream os;
    os << "firmware: too few PEs for the lines the batches share: " << fp.P << " PEs hold "
       << fp.lpb << " line(s) per batch, and a batch holds " << halo
       << " line(s) either side of the ones it outputs (";
    const char* sep = "";
    if (p.vote) {
        os << "the vote 1";
        sep = ", ";
    }
    if (p.agg_ry > 0) {
        os << sep << "--agg-ry " << p.agg_ry;
        sep = ", ";
    }
    if (p.kc > 0) os << sep << "the census radius " << p.census;
    os << "), so a batch needs " << 2 * halo + 1 << " lines (use >= " << span * (2 * halo + 1)
       << " PEs";
    if (p.vote && p.agg_ry == 0 && p.kc == 0) os << ", --vote off";
    os << ", or a ROI of at most " << fp.lpb << " lines)";
    return FirmwareError(os.str());
}

// The batches of the ROI's H lines (fp.lpb lines per batch at most, the
// halo's lines either side of an inner edge), the most lines in one, the
// video segments; the census's last segment at least r pixels wide.
void plan_batches(FramePlan& fp, const golden::Params& p, bool tiny, int span) {
    const int H = fp.roi.h;
    if (tiny) {
        for (int y = 0; y < H; ++y) fp.batches.push_back({y, 1, 0, 1});
    } else if (H <= fp.lpb) {
        fp.batches.push_back({0, H, 0, H});
    } else {
        const int halo = fp.halo = batch_halo(p);
        const int stride = fp.lpb - 2 * halo;
        if (stride < 1) throw too_few_for_the_halo(fp, p, span);
        for (int o = 0; o < H; o += stride) {
            const int oe = std::min(H, o + stride);
            const int first = std::max(0, o - halo);
            const int last = std::min(H, oe + halo);
            fp.batches.push_back({first, last - first, o - first, oe - o});
        }
    }
    for (const Batch& b : fp.batches) fp.hbmax = std::max(fp.hbmax, b.lines);
    fp.nseg = (fp.roi.w + fp.P - 1) / fp.P;
    // the census's codes at a segment's edges read the pixels x -+ r of the
    // segments either side; a last segment narrower than r would need those
    // clamped into the ROI within the one before it
    const int last = fp.roi.w - (fp.nseg - 1) * fp.P;
    if (p.kc > 0 && fp.nseg > 1 && last < p.census) {
        std::ostringstream os;
        os << "firmware: --kc " << p.kc << " (census) over " << fp.nseg << " video segments of "
           << fp.P << " pixels needs the last one at least " << p.census
           << " pixels wide (the census radius): the ROI is " << fp.roi.w
           << " wide, the last segment " << last << "; use a ROI width of " << (fp.nseg - 1) * fp.P
           << " or at least " << (fp.nseg - 1) * fp.P + p.census << " (--roi), or other --pes";
        throw FirmwareError(os.str());
    }
}

// "does not fit" for `need` bytes of local memory per PE for `what`: a lower
// bound, each check seeing only its rows as placed for this memory (more
// memory moves the window's copies at its top and may undo split video
// rows, so the frame can need more), hence "at least".
FirmwareError rows_do_not_fit(int need, const char* what, int mem) {
    std::ostringstream os;
    os << "does not fit: needs at least " << need << " bytes of local memory per PE for " << what
       << " (have " << mem << ", mem_bytes)";
    return FirmwareError(os.str());
}

// Video rows and the output rows: free memory outside the constant block,
// the line buffers and (for the output) the map; sets the frame's memory needs.
void place_rows(FramePlan& fp, const isa::MachineConfig& cfg) {
    const ForwardPlan& f = fp.f;
    const int mem = static_cast<int>(cfg.mem_bytes);
    int end = f.mem_needed;
    // the cost planes and the pointer region are free during the input (with
    // the window: the copies' region too, up to the re-layout's buffers)
    fp.inl = f.agg > 0 ? f.kblk + f.kbs : f.costl;
    if (fp.rl.windows) {
        // windowed rows: wsize rows per image (plan_windows checked the room)
        fp.inr = fp.inl + fp.rl.wsize;
        end = std::max(end, fp.inl + 2 * fp.rl.wsize);
    } else if (fp.rl.copies) {
        // kind copies: row 2y + kind per image (plan_skew checked the room)
        fp.inr = fp.inl + 2 * fp.hbmax;
        end = std::max(end, fp.inl + 4 * fp.hbmax);
    } else if (fp.rl.skew && detail::row_stride(fp, mem) > 1) {
        // one skewed copy: rows rys bytes apart, the images interleaved
        // (row_stride's rows start at the cost planes: inl here)
        fp.rys = detail::row_stride(fp, mem);
        fp.inr = fp.inl + 1;
        end = std::max(end, fp.inl + fp.rys * (fp.hbmax - 1) + 2);
    } else if (fp.inl + 2 * fp.hbmax <= mem) {
        fp.inr = fp.inl + fp.hbmax;
        end = std::max(end, fp.inl + 2 * fp.hbmax);
    } else if (fp.inl + fp.hbmax <= mem && !(f.census > 0 && fp.nseg > 1)) {
        // (census over video segments: both images' rows at once; the
        // one-image-at-a-time input is not run with the segments' edges)
        fp.split_in = true;
        fp.inr = fp.inl;
        end = std::max(end, fp.inl + fp.hbmax);
    } else {
        throw rows_do_not_fit(fp.inl + fp.hbmax, "the video rows", mem);
    }
    // several video segments: 3 bytes beside the census's code rows take
    // the pixels x -+ r of the lines above, at and below from the segment
    // beside (census.inc, CENSUS_EDGE: the left and right edges reuse them)
    const int scr = f.census > 0 && fp.nseg > 1 ? 3 : 0;
    if (f.census > 0) {
        // census code rows (video layout): beside the pixel rows, clear of the
        // code buffers the code re-layout writes (they end at preg)
        const int rows = fp.split_in ? 1 : 2;
        fp.cinl = f.agg > 0 ? fp.inl + rows * fp.hbmax : std::max(f.preg, fp.inl + rows * fp.hbmax);
        fp.cinr = fp.split_in ? fp.cinl : fp.cinl + fp.hbmax;
        fp.cscr = fp.cinl + rows * fp.hbmax;
        if (fp.cinl + rows * fp.hbmax + scr > mem)
            throw rows_do_not_fit(fp.cinl + rows * fp.hbmax + scr, "the census code rows", mem);
        end = std::max(end, fp.cinl + rows * fp.hbmax + scr);
    }
    if (f.agg > 0) {
        const int rows_end = f.census > 0 ? fp.cinr + fp.hbmax + scr : fp.inr + fp.hbmax;
        if (rows_end > f.agg_src) {
            std::ostringstream os;
            os << "does not fit: --agg-rx " << f.agg << " needs at least "
               << rows_end - f.agg_src + mem
               << " bytes of local memory per PE for the video rows beside the line buffers (have "
               << mem << ", mem_bytes)";
            throw FirmwareError(os.str());
        }
        end = std::max(end, mem);
    }
    // output rows: after the constant block, avoiding the map
    // (windowed rows: osize slots, plan_out_windows checked the room)
    if (fp.rl.skew && !fp.rl.owindows)
        fp.ryso = detail::out_row_stride(fp.P, fp.span(), fp.spare, f.kbs, f.map, f.N, mem);
    const int orows = fp.rl.owindows ? fp.rl.osize
                      : fp.ryso > 1  ? fp.ryso * (fp.hbmax - 1) + 1
                                     : fp.hbmax;
    fp.out = f.kbs;
    if (fp.out < f.map + f.N && fp.out + orows > f.map) fp.out = f.map + f.N;
    if (fp.out + orows > mem) throw rows_do_not_fit(fp.out + orows, "the output rows", mem);
    end = std::max(end, fp.out + orows);
    fp.mem_needed = end;
    fp.ext_needed = f.ext_needed;
}

FramePlan plan_frame_impl(const golden::Params& p, const golden::Roi& roi,
                          const isa::MachineConfig& cfg, bool spare,
                          RowLayout rows = RowLayout::Fastest,
                          PassLayout passes = PassLayout::Fastest) {
    detail::check_options(p, true);
    if (!cfg.indirect)
        throw FirmwareError(
            "the DP firmware needs per-PE (indirect) addressing for its re-layout and "
            "backtrack: set indirect=on");
    FramePlan fp;
    fp.roi = roi;
    fp.P = static_cast<int>(cfg.pes);
    fp.mem = detail::plan_mem(cfg);
    fp.spare = spare;
    fp.rows_allowed = static_cast<int>(rows);
    const bool bidir = p.mode == golden::Mode::Bidir || p.mode == golden::Mode::Joint;
    const int span = bidir || spare ? 2 : 1;
    fp.lpb = std::min(fp.P / span, kMaxBatchLines);
    // Too few lines per batch for the vote across batches: one line at a
    // time, every pointer table kept in the external memory.
    const bool tiny = p.vote && roi.h > fp.lpb && fp.lpb < 3 && fp.lpb >= 1;
    // the census and the vertical window need batches of their halo (3 lines at least)
    if ((p.kc > 0 || p.agg_ry > 0) && tiny) throw too_few_for_the_halo(fp, p, span);
    fp.f = detail::plan_forward_impl(p, roi.w, cfg, tiny, true,
                                     passes == PassLayout::Fastest);  // range and DP memory checks
    if (tiny) fp.lpb = 1;
    if (fp.lpb < 1) {
        std::ostringstream os;
        os << "too few PEs: bidir mode needs 2 PEs per line, have " << fp.P;
        throw FirmwareError(os.str());
    }
    plan_batches(fp, p, tiny, span);
    detail::plan_relayout(fp, fp.mem, cfg.costs);
    place_rows(fp, cfg);
    relayout_bound(fp, cfg.costs);
    return fp;
}

// Spilled pointer columns and idle PEs (single mode, one batch, one video
// segment, at least two PEs per line): the spare layout keeps them on chip,
// in the PE above each line's PE (docs/firmware.md, section 3). Plans it
// into *sp, or returns why it does not apply.
const char* plan_spare(const golden::Params& p, const golden::Roi& roi,
                       const isa::MachineConfig& cfg, const FramePlan& fp, FramePlan* sp) {
    const ForwardPlan& f = fp.f;
    if (f.bidir || f.tiny || f.kc > 0 || f.agg > 0 || f.aggy > 0 || f.bt)
        return "it needs single mode without census, aggregation or bt dissimilarity";
    if (f.ext_needed == 0) return "no pointer column spills";
    if (fp.batches.size() != 1 || fp.nseg != 1 || 2 * roi.h > fp.P)
        return "it needs one batch, one video segment and two PEs per ROI line";
    try {
        *sp = plan_frame_impl(p, roi, cfg, true);
    } catch (const FirmwareError&) {
        return "the spare layout's plan does not fit the machine";
    }
    if (!sp->rl.skew || sp->batches.size() != 1)
        return "the spare layout's lines do not take skewed rows in one batch";
    // The spare's memory from the forward pass to the last reload: its
    // constant block and the map (cleared by every PE) stay; the rest is free.
    const int mem = detail::plan_mem(cfg);
    const int lo = sp->f.kblk + sp->f.kbs, ext = static_cast<int>(sp->f.ext_needed);
    if (sp->f.map < lo || lo + ext + sp->f.N > mem)
        return "the spilled columns do not fit the spare PE's free memory";
    sp->spare_base = lo;  // spill byte e at lo + e, beyond the map's start at lo + e + N
    sp->ext_needed = 0;
    return nullptr;
}

// Whether the spare layout `sp` is cheaper than the external path of `fp`:
// the external transfers move the bytes of the PEs holding a line (len *
// lines / ext_bytes_per_cycle per column and direction), the spare's 3
// cycles per byte each way, plus one instruction per skewed round and the
// vote's two hops instead of one (4 ring instructions per backtrack step;
// the steps estimated as 3 * (KMAX + D), 2.6x the headline's). With few
// lines the external path wins.
bool spare_cheaper(const golden::Params& p, const isa::MachineConfig& cfg, const FramePlan& fp,
                   const FramePlan& sp) {
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
    return spare_cost < ext_cost;
}

}  // namespace

FramePlan plan_frame(const golden::Params& p, const golden::Roi& roi, const isa::MachineConfig& cfg,
                     SpillLayout layout, RowLayout rows, PassLayout passes) {
    FramePlan fp = plan_frame_impl(p, roi, cfg, false, rows, passes);
    if (layout == SpillLayout::External) return fp;
    FramePlan sp;
    if (const char* why = plan_spare(p, roi, cfg, fp, &sp)) {
        if (layout == SpillLayout::Spare)
            throw FirmwareError(std::string("the spare-PE spill layout does not apply: ") + why);
        return fp;
    }
    if (layout == SpillLayout::Spare) return sp;
    return spare_cheaper(p, cfg, fp, sp) ? sp : fp;
}

}  // namespace imap::firmware
