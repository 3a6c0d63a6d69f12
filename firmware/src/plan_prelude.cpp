// The generated prelude of the DP firmware and its assembly, from a frame
// plan (or a forward plan for the test programs): .equ constants for dp.s and
// the PLAN_* macros, one call per column of the forward pass and the
// backtrack (FCOL, BCOL, spills and reloads), per line-buffer byte of the
// window's copies and the bt bounds (AGX, BTX), and per video segment of the
// re-layout; then the .include of the firmware source. Also the param block
// and the register groups the waves show as one value.
#include <algorithm>
#include <initializer_list>
#include <sstream>

#include "imap/isa/assembler.hpp"
#include "plan_internal.hpp"

namespace imap::firmware {

namespace {

using detail::column_bytes;
using detail::ColumnBytes;
using detail::in_lanes;
using detail::index_steps_a_byte;
using detail::seg_width;

struct Equ {
    const char* name;
    int64_t value;
};

void equ(std::ostringstream& os, const char* name, int64_t v) {
    os << ".equ " << name << " " << v << "\n";
}

void equs(std::ostringstream& os, std::initializer_list<Equ> list) {
    for (const Equ& e : list) equ(os, e.name, e.value);
}

// The line buffers' address of pixel X of R / L on a PE of kind h (linear
// in X; relayout.inc: RSK_STORE takes them as LRB/LRS, LLB/LLS per kind).
int buffer_addr_r(const ForwardPlan& f, int h, int X) {
    if (!f.bidir) return f.rb - 1 - X;
    if (f.joint) return h == 0 ? f.rb - 1 - X : f.rb - f.N + X;
    return h == 0 ? f.rb - f.s + X : f.rb + f.s - X;
}
int buffer_addr_l(const ForwardPlan& f, int h, int X) {
    if (!f.bidir) return f.rb + 2 + X;
    if (f.joint) return h == 0 ? f.rb + 2 + X + f.lsh[0] : f.rb + f.N + f.D - X + f.lsh[1];
    return h == 0 ? f.rb + f.s + f.D - X + f.lsh[0] : f.rb + 1 - f.s + X + f.lsh[1];
}

// The output frame: 0 cyclopean, 1 left, 2 right.
int frame_code(const golden::Params& p) {
    return p.frame == golden::Frame::Cyclopean ? 0 : p.frame == golden::Frame::Left ? 1 : 2;
}

// The left wavefront's last output position + 1 (the merge band ends there).
int band_end(const golden::Params& p, const ForwardPlan& f) {
    if (!f.bidir) return 0;
    const int fr = frame_code(p);
    const int e = f.joint ? f.s : f.s - 1;  // the left PE's last event site
    const int last = fr == 0 ? e + (f.D - 1) / 2 : fr == 1 ? e + f.D - 1 : e;
    return std::min(f.N, last + 1);
}

void dp_constants(std::ostringstream& os, const golden::Params& p, const ForwardPlan& f) {
    equs(os,
         {
             {"MODE", f.bidir ? 1 : 0},
             {"JOINT", f.joint ? 1 : 0},
             {"JM", f.bidir ? std::min(f.D - 1, f.N - 1 - f.s) : 0},  // top level of site s
             {"N", f.N},
             {"D", f.D},
             {"S", f.s},
             {"DS", f.ds},
             {"KM", p.km},
             {"KB", p.kb},
             {"GB", p.gb},
             {"ADMAX", std::min(255, p.ad_max)},
             {"WO", p.Wo},
             {"WD", p.Wd},
             {"FRAME", frame_code(p)},
             {"VOTE", p.vote ? 1 : 0},
             {"KMAX", f.kmax},
             {"KLEFT", f.bidir ? f.K[0] : 0},
             {"KRIGHT", f.bidir ? f.K[1] : f.K[0]},
             {"KBLK", f.kblk},
             {"KBS", f.kbs},
             {"RB", f.rb},
             {"KR", f.kr},
             {"KL", f.kl},
             {"COSTL", f.costl},
             {"COSTH", f.costh},
             {"XO", f.xo},
             {"XM", f.xm},
             {"XD", f.xd},
             {"KPP", f.kpp},
             {"MAP", f.map},
             {"BSTEP", f.bstep_tab >= 0 ? 1 : 0},
             {"BTAB", std::max(0, f.bstep_tab)},
             {"BSK0", f.bstep_k0[0]},
             {"BSK1", f.bidir ? f.bstep_k0[1] : f.bstep_k0[0]},
             {"TINY", f.tiny ? 1 : 0},
             {"TTABLE", f.ext_table},
             {"TBUF0", f.tiny_buf[0]},
             {"TBUF1", f.tiny_buf[1]},
             {"TBUF2", f.tiny_buf[2]},
             {"BANDE", band_end(p, f)},
             {"KC", f.kc},
             {"CENSUS", f.census},
             {"CO", f.co},
             {"AGG", f.agg},
             {"RBR", f.rbr},
             {"RBL", f.rbl},
             {"LSH0", f.lsh[0]},
             {"LSH1", f.lsh[1]},
             {"FSPLIT", std::any_of(f.passes.begin(), f.passes.end(),
                                    [](const ForwardPass& ps) { return ps.split > 0; })
                            ? 1
                            : 0},
             {"CNO", f.agg > 0 ? f.cxo : f.co},
             {"BT", f.bt ? 1 : 0},
             {"BLO", f.blo},
             {"BHI", f.bhi},
             {"AGGR", f.rows ? 1 : 0},
             {"AGGY", f.aggy},
             {"WL", f.wl},
             {"WH", f.wh},
             {"PMAX", f.pmax},
             {"H8", f.h8 ? 1 : 0},
             {"D8", f.d8 ? 1 : 0},
             {"EXCHN", f.bidir ? std::max(0, std::min(f.N - 1 - f.s, f.D - (f.joint ? 1 : 2))) : 0},
             {"LRB0", buffer_addr_r(f, 0, 0)},
             {"LRS0", buffer_addr_r(f, 0, 1) - buffer_addr_r(f, 0, 0)},
             {"LLB0", buffer_addr_l(f, 0, 0)},
             {"LLS0", buffer_addr_l(f, 0, 1) - buffer_addr_l(f, 0, 0)},
             {"LRB1", buffer_addr_r(f, 1, 0)},
             {"LRS1", buffer_addr_r(f, 1, 1) - buffer_addr_r(f, 1, 0)},
             {"LLB1", buffer_addr_l(f, 1, 0)},
             {"LLS1", buffer_addr_l(f, 1, 1) - buffer_addr_l(f, 1, 0)},
         });
}

// The frame's own constants: the machine, the ROI, the batches (dp.s
// BATCH_LINES / BATCH_OUT: every batch but the last outputs BSTRIDE lines
// and holds BOVERLAP more either side, the halo), the rows and the
// re-layout.
void frame_constants(std::ostringstream& os, const FramePlan& fp) {
    const bool multi = !fp.f.tiny && fp.batches.size() > 1;
    const int P = fp.P;
    // Skewed rounds (RSK_SEND): a sender whose lane holds no line's row this
    // round may read any row that lies in the local memory. SKNC 0: it reads
    // row 0 (clamped); 1: row q mod P (kind copies: 16 bits); 2: the row
    // index's low byte (kind copies: the rows q < 2 lines <= 256 keep their
    // index); 3: P such that the sender steps a byte alone
    // (index_steps_a_byte).
    const int rows_top = std::max({fp.inl, fp.inr, fp.cinl, fp.cinr});
    const bool byte_steps = index_steps_a_byte(P, fp.rl.copies, fp.span());
    int sknc = 0;
    if (rows_top + 255 < fp.mem && (!fp.rl.copies || 2 * fp.hbmax <= 256))
        sknc = byte_steps ? 3 : 2;
    else if (fp.rl.copies && rows_top + P - 1 < fp.mem)
        sknc = 1;
    // Rows rys bytes apart (row_stride): their senders step the scaled
    // index alone, so the rows must lie where any index reads (SKNC 3).
    if (fp.rys > 1 && sknc != 3) throw FirmwareError("internal: strided video rows without SKNC 3");
    int rysl = 0, rysol = 0;
    while ((1 << rysl) < fp.rys) ++rysl;
    while ((1 << rysol) < fp.ryso) ++rysol;
    // Packed rounds (relayout.inc, RPK_*): one copy of the skewed rows in
    // bidir, its senders stepping a byte, no census; the R lanes index the
    // rows INR - INL above their own, so every line's R row lies within 256
    // bytes of INL.
    const bool packed = fp.f.bidir && fp.rl.skew && !fp.rl.copies && !fp.rl.windows && sknc == 3 &&
                        fp.f.census == 0 && fp.inr > fp.inl &&
                        fp.inr - fp.inl + fp.rys * (fp.hbmax - 1) <= 255;
    equs(os,
         {
             {"P", fp.P},
             {"HROI", fp.roi.h},
             {"X0", fp.roi.x0},
             {"Y0", fp.roi.y0},
             {"NSEG", fp.nseg},
             {"LPB", fp.lpb},
             {"BSTRIDE", multi ? fp.batches[0].out_count : fp.roi.h},
             {"BOVERLAP", multi ? fp.halo : 0},
             {"HBMAX", fp.hbmax},
             {"INL", fp.inl},
             {"INR", fp.inr},
             {"OUT", fp.out},
             {"SPLIT_IN", fp.split_in ? 1 : 0},
             {"RYS", fp.rys},
             {"RYSL", rysl},
             {"RYSO", fp.ryso},
             {"RYSOL", rysol},
             {"CINL", fp.cinl},
             {"CINR", fp.cinr},
             {"CSCR", fp.cscr},
             {"RMOD", fp.rl.modular ? 1 : 0},
             {"BP", fp.rl.base},
             {"UR", fp.rl.ur},
             {"UL", fp.rl.ul},
             {"SKEW", fp.rl.skew ? 1 : 0},
             {"SKW", fp.rl.wrap ? 1 : 0},
             {"YWI", fp.rl.ywi},
             {"YWO", fp.rl.ywo},
             {"SKC", fp.rl.copies ? 1 : 0},
             {"SKB", fp.rl.skb},
             {"SKNC", sknc},
             {"SKPK", packed ? 1 : 0},
             {"YBB", fp.rl.ybb},
             {"YWB1", fp.rl.ywb1},
             {"YWB2", fp.rl.ywb2},
             {"SKX1", fp.rl.base - (fp.rl.copies ? fp.rl.skb : 0) - fp.rl.skew_in - fp.rl.dmin + 1},
             {"SKI", fp.rl.skew_in},
             {"SKO", fp.rl.skew_out},
             {"SKX", fp.rl.base - fp.rl.skew_in - fp.rl.dmin},
             {"DMIN", fp.rl.dmin},
             {"DMAX", fp.rl.dmax},
             {"SPARE", fp.spare ? 1 : 0},
             {"SKWIN", fp.rl.windows ? 1 : 0},
             {"SKWL0", fp.rl.wlo[0]},
             {"SKWH0", fp.rl.whi[0]},
             {"SKWL1", fp.rl.wlo[1]},
             {"SKWH1", fp.rl.whi[1]},
             {"SKRC", fp.rl.wrc},
             {"SKWB", fp.rl.wsize <= 256 ? 1 : 0},
             {"SKWO", fp.rl.owindows ? 1 : 0},
             {"SKOWL", fp.rl.owlo},
             {"SKOWH", fp.rl.owhi},
             {"SKORC", fp.rl.orc},
             {"SKOWB", fp.rl.osize <= 256 || fp.rl.owrap ? 1 : 0},
         });
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
    return buffer_addr_r(f, holder(f, X), X);
}
int addr_l(const ForwardPlan& f, int X) {
    return buffer_addr_l(f, holder(f, X), X);
}

// One `op` line per line-buffer byte the node reads (R' then L', from level
// `first` to the buffer's top + agg): its destination address, then for each
// kind (the same one twice in single mode) the fields fields(img, kind, X)
// writes for the byte's site X, clamped into the ROI.
template <class Fields>
void buffer_lines(std::ostringstream& os, const ForwardPlan& f, const char* op, int first,
                  Fields&& fields) {
    for (int img = 0; img < 2; ++img) {
        const int top = img == 0 ? f.kr : f.kl;
        for (int m = first; m <= top + f.agg; ++m) {
            os << "        " << op << " " << (img == 0 ? f.rbr - m : f.rbl + m);
            for (int kind = 0; kind < 2; ++kind) {
                const int kk = f.kinds == 2 ? kind : 0;
                const int site = img == 0 ? site_r(f, kk, m) : site_l(f, kk, m);
                fields(img, kk, std::max(0, std::min(f.N - 1, site)));
            }
            os << "\n";
        }
    }
}

// The address of pixel X of image img as the re-layout stored it, and
// whether it is kind `kind`'s own byte (else the partner's, one ring hop away).
void source_field(std::ostringstream& os, const ForwardPlan& f, int img, int kind, int X) {
    os << ", " << (img == 0 ? addr_r(f, X) : addr_l(f, X)) << ", "
       << (holder(f, X) == kind ? 1 : 0);
}

// The extended, clamped line buffers of the aggregation window
// (AGG_EXTEND in census.inc): one AGX line per destination byte, with the
// source of each kind.
void agg_macros(std::ostringstream& os, const ForwardPlan& f) {
    os << ".macro PLAN_AGG\n";
    if (f.agg > 0)
        buffer_lines(os, f, "AGX", 1 - f.agg,
                     [&](int img, int kind, int X) { source_field(os, f, img, kind, X); });
    os << ".endm\n";
}

// The Birchfield-Tomasi bounds (BT_BOUNDS in census.inc): one BTX line per
// byte the node reads (the line buffers, or the window's copies), with the
// sources of the three pixels X-1, X, X+1 of its site X (clamped into the
// ROI, as docs/golden.md requires) on each kind.
void bt_macros(std::ostringstream& os, const ForwardPlan& f) {
    os << ".macro PLAN_BT\n";
    if (f.bt)
        buffer_lines(os, f, "BTX", f.agg > 0 ? 1 - f.agg : 0, [&](int img, int kind, int X) {
            for (int u = -1; u <= 1; ++u)
                source_field(os, f, img, kind, std::max(0, std::min(f.N - 1, X + u)));
        });
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

// A spill (after its pass) or reload (before its column's backtrack): to or
// from the external memory (FSPILL / FRELOAD), or with spare_base >= 0 the
// spare PE's memory (RSPILL / RRELOAD).
void transfer(std::ostringstream& os, const ForwardPlan& f, int spare_base, bool spill,
              const Transfer& t) {
    if (spare_base >= 0)
        spare_transfer(os, f, spare_base, spill ? "RSPILL" : "RRELOAD", t);
    else
        os << "        " << (spill ? "FSPILL" : "FRELOAD") << " " << t.local << ", " << t.ext
           << ", " << t.len << "\n";
}

// PLAN_FORWARD: one FCOL per pass, each followed by the spills due after it.
void forward_macro(std::ostringstream& os, const ForwardPlan& f, int spare_base) {
    os << ".macro PLAN_FORWARD\n";
    size_t si = 0;
    for (size_t i = 0; i < f.passes.size(); ++i) {
        const ForwardPass& ps = f.passes[i];
        os << "        FCOL " << ps.k << ", " << ps.kind << ", " << ps.jlo << ", " << ps.n << ", "
           << (ps.donly ? 1 : 0) << ", " << ps.pad << ", " << ps.addr << ", " << ps.rfull << ", "
           << ps.rinc << ", " << ps.split << ", " << ps.late << ", " << (ps.ldonly ? 1 : 0) << "\n";
        while (si < f.spills.size() && f.spills[si].after == static_cast<int>(i))
            transfer(os, f, spare_base, true, f.spills[si++]);
    }
    os << "        FEND\n.endm\n";
}

// PLAN_BACK: per column from the last, its reloads (TRELOAD of the whole
// column on arrays of 2 to 5 PEs), then BCOL with the column's address, each
// kind's first level and whether the kind has the column.
void back_macro(std::ostringstream& os, const ForwardPlan& f, int spare_base) {
    os << ".macro PLAN_BACK\n";
    for (int k = f.kmax; k >= 1; --k) {
        if (f.tiny) {
            const ColumnBytes col = column_bytes(f, k);
            if (col.ext >= 0) os << "        TRELOAD " << col.ext << ", " << col.size << "\n";
        }
        for (const Transfer& t : f.reloads)
            if (t.after == k) transfer(os, f, spare_base, false, t);
        int addr = -1, maxb = 0, base[2] = {0, 0}, act[2] = {0, 0};
        for (int p = 0; p < f.kinds; ++p) {
            const PointerColumn& c = f.ptr[p][k];
            if (k > f.K[p] || c.bytes == 0) continue;
            addr = c.addr;
            base[p] = c.base;
            act[p] = 1;
            maxb = std::max(maxb, c.bytes);
        }
        // a kind's base may lie below slot 0 (a split pass's late kind): the
        // walk's slot j - base is 8-bit arithmetic
        os << "        BCOL " << k << ", " << addr << ", " << (base[0] & 255) << ", "
           << (base[1] & 255) << ", " << maxb - 1 << ", " << act[0] << ", " << act[1] << "\n";
    }
    os << ".endm\n";
    // PLAN_BTAB: the step-synchronous backtrack's table, one BTE per column
    // (each kind's slot address; column 0 holds 0; a column only one kind
    // steps in holds that kind's address for both, one store per byte)
    os << ".macro PLAN_BTAB\n";
    if (f.bstep_tab >= 0)
        for (int k = 0; k <= f.kmax; ++k) {
            int a0 = f.bstep_a[0][k], a1 = f.bidir ? f.bstep_a[1][k] : a0;
            if (k > f.bstep_k0[0]) a0 = a1;
            if (f.bidir && k > f.bstep_k0[1]) a1 = a0;
            os << "        BTE " << k << ", " << a0 << ", " << a1 << "\n";
        }
    os << ".endm\n";
}

void dp_macros(std::ostringstream& os, const ForwardPlan& f, int spare_base = -1) {
    agg_macros(os, f);
    bt_macros(os, f);
    forward_macro(os, f, spare_base);
    os << ".macro PLAN_RELOAD\n.endm\n";
    back_macro(os, f, spare_base);
}

// Per-segment re-layout calls: PLAN_IN with the segment, its width and the
// receiver lanes of both kinds; PLAN_OUT with the output displacements.
void relayout_macros(std::ostringstream& os, const FramePlan& fp) {
    os << ".macro PLAN_IN\n";
    // windowed rows: one pass over the whole line (pixels X = lanes)
    for (int g = 0; g < (fp.rl.windows ? 1 : fp.nseg); ++g) {
        const int W = fp.rl.windows ? fp.f.N : seg_width(fp, g);
        int a0, n0, a1 = 0, n1 = 0;
        in_lanes(fp.f, fp.P, g, W, 0, &a0, &n0);
        if (fp.f.bidir) in_lanes(fp.f, fp.P, g, W, 1, &a1, &n1);
        os << (fp.f.census > 0 ? "        RELAYOUT_IN_CENSUS " : "        RELAYOUT_IN ") << g
           << ", " << W << ", " << a0 << ", " << n0 << ", " << a1 << ", " << n1 << "\n";
    }
    os << ".endm\n";
    os << ".macro PLAN_OUT\n";
    for (int g = 0; g < (fp.rl.owindows ? 1 : fp.nseg); ++g) {
        int smin, smax;
        detail::out_displacements(fp, g, &smin, &smax);
        os << "        RELAYOUT_OUT " << g << ", " << (fp.rl.owindows ? fp.f.N : seg_width(fp, g))
           << ", " << smin << ", " << smax << "\n";
    }
    os << ".endm\n";
}

}  // namespace

std::string frame_source(const golden::Params& p, const FramePlan& fp) {
    std::ostringstream os;
    os << "; Generated by the firmware planner (firmware/src/plan.cpp) for one parameter set:\n"
          "; the constants and the per-column plan of dp.s (docs/firmware.md).\n";
    dp_constants(os, p, fp.f);
    frame_constants(os, fp);
    dp_macros(os, fp.f, fp.spare ? fp.spare_base : -1);
    relayout_macros(os, fp);
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
    equs(os, {{"P", P}, {"HB", lines}, {"HROI", lines}});
    dp_macros(os, f);
    os << ".include \"" << file << "\"\n";
    isa::AsmOptions o;
    o.files = &firmware_sources();
    return isa::assemble_string(os.str(), firmware_dir() + "/test_plan.s", o);
}

isa::Program assemble_split_test(const golden::Params& p, const ForwardPlan& f,
                                 const SplitForward& sf, int lines, int P) {
    ForwardPlan g = f;  // the node's constants at the split's addresses
    g.costl = sf.costl;
    g.costh = sf.costh;
    std::ostringstream os;
    dp_constants(os, p, g);
    equs(
        os,
        {{"P", P}, {"HB", lines}, {"HROI", lines}, {"SENTW", sf.sent}, {"LX", sf.indexed ? 1 : 0}});
    dp_macros(os, f);
    const PairSchedule& s = sf.s;
    auto cut = [&](int q, int c) { return detail::split_cut(f, q, s.m[q], c); };
    auto valid = [&](int q, int c, int j) {
        return c >= 0 && c <= f.K[q] && j >= f.lo[q][c] && j <= f.hi[q][c];
    };
    const int D = f.D;
    // each kind's lower part's top at column k (any slot where it has none)
    auto top_slot = [&](int q, int k) {
        if (k > f.K[q]) return 0;
        const int c = cut(q, k);
        return c > f.lo[q][k] ? c - 1 + s.sigma[q] + sf.shift : 0;
    };
    // the start column's levels j0..j1 on the PEs of kind q, level j at slot j + off
    auto init_part = [&](int q, int j0, int j1, int off) {
        if (j1 < j0) return;
        os << "        SINIT " << q << ", " << j0 + off << ", " << j0 << ", " << j1 << "\n";
        if (j1 == D - 1) os << "        SPAD " << q << ", " << D - 1 + off << "\n";
    };
    os << ".macro PLAN_SPLIT\n";
    // the start column: the levels below m_q(0) at home before the first step
    for (int q = 0; q < 2; ++q) init_part(q, f.lo[q][0], cut(q, 0) - 1, s.sigma[q] + sf.shift);
    os << "        SXFER " << top_slot(0, 0) << ", " << top_slot(1, 0) << ", 0\n";
    // the start column's upper parts, once the first step's lower parts are done
    bool upper0 = false;
    auto init_upper = [&] {
        for (int q = 0; q < 2; ++q) {
            const int o = 1 - q;
            init_part(q, cut(o, 0), f.hi[o][0], s.tau[q] + sf.shift);
        }
        upper0 = true;
    };
    for (const SplitStep& st : sf.steps) {
        if (st.k > 1 && !upper0) init_upper();
        const int c2 = sf.indexed ? sf.cbase + st.k + st.x0 : sf.rbl + st.k + st.x0 - sf.v0;
        os << "        SSTEP " << st.x0 << ", " << c2 << ", " << st.addr << "\n";
        struct Ev {
            int t, q;
            const SplitPart* sp;
        };
        std::vector<Ev> ev;
        for (int q = 0; q < 2; ++q)
            for (const SplitPart& sp : st.part[q])
                if (!sp.none()) ev.push_back({sp.lo + sp.off - st.x0, q, &sp});
        std::stable_sort(ev.begin(), ev.end(), [](const Ev& a, const Ev& b) { return a.t < b.t; });
        int at = 0;
        for (const Ev& e : ev) {
            if (e.t > at) os << "        SRUN " << at << ", " << e.t << "\n";
            at = e.t;
            const SplitPart& sp = *e.sp;
            const int c = sp.col, j = sp.lo, kind = sp.kind;
            int how = 0;
            bool pads = false;
            if (!valid(kind, c - 1, j)) {
                how = 1;  // D only
            } else if (sp.upper) {
                const bool msent = j == cut(kind, c - 1) - 1;
                const bool osent = j > f.lo[kind][c];
                how = msent ? (osent ? 3 : 2) : (osent ? 4 : 0);
            }
            if (sp.upper && j == D - 1 && cut(kind, c - 1) == D) pads = true;
            const int ra = (kind == e.q ? sf.rbr : sf.rbr2) - c;
            os << "        SFIRST " << e.q << ", " << e.t << ", " << ra << ", " << how << ", "
               << (pads ? 1 : 0) << ", " << sp.lx << ", " << st.k % 2 << "\n";
        }
        os << "        SRUN " << at << ", " << st.n << "\n";
        os << "        SEND " << st.n << "\n";
        for (int q = 0; q < 2; ++q)
            for (const SplitPart& sp : st.part[q])
                if (!sp.none() && sp.hi == D - 1)
                    os << "        SPAD " << q << ", " << D - 1 + sp.off << "\n";
        os << "        SXFER " << top_slot(0, st.k) << ", " << top_slot(1, st.k) << ", " << st.k
           << "\n";
        if (st.k == 1) init_upper();
    }
    os << ".endm\n";
    os << ".include \"dp_split_test.s\"\n";
    isa::AsmOptions o;
    o.files = &firmware_sources();
    return isa::assemble_string(os.str(), firmware_dir() + "/split_plan.s", o);
}

std::vector<std::pair<int, uint32_t>> param_block(const FramePlan& fp) {
    std::vector<std::pair<int, uint32_t>> v;
    v.emplace_back(0, static_cast<uint32_t>(fp.batches.size()));
    return v;
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

}  // namespace imap::firmware
