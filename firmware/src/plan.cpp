#include "imap/firmware/plan.hpp"

#include <algorithm>
#include <sstream>

#include "imap/isa/assembler.hpp"

namespace imap::firmware {

std::string firmware_dir() {
    return IMAP_FIRMWARE_DIR;
}

ForwardPlan plan_forward(const golden::Params& p, int N, const isa::MachineConfig& cfg) {
    golden::validate_for_width(p, N);
    // Wm is formed in 16 bits; every reachable cost stays below the golden's
    // bound B, and unreachable ones in [INF, INF + B): both need B <= 2^23.
    const int64_t wm_max = int64_t{p.km} * 255 + int64_t{p.kb} * p.gb;
    if (wm_max >= 65536) {
        std::ostringstream os;
        os << "firmware: match cost km*255 + kb*gb = " << wm_max
           << " does not fit the 16-bit match term (needs < 65536; lower --km or --kb)";
        throw FirmwareError(os.str());
    }
    const int64_t w = std::max({wm_max, int64_t{p.Wo}, int64_t{p.Wd}});
    const int64_t bound = (2 * int64_t{N} + p.D + 4) * w;
    if (bound > kInf) {
        std::ostringstream os;
        os << "firmware: cost bound (2N + D + 4) * max(Wm, Wo, Wd) = " << bound
           << " exceeds the 24-bit cost range (needs <= " << kInf
           << "; lower the weights or the ROI width)";
        throw FirmwareError(os.str());
    }

    ForwardPlan f;
    f.N = N;
    f.D = p.D;
    f.bidir = p.mode == golden::Mode::Bidir;
    if (f.bidir) {
        f.s = golden::resolve_seed_col(p, N);
        f.ds = p.seed_disp.free ? -1 : p.seed_disp.value;
        f.kmax = std::max(N - 1 - f.s, f.s);
    } else {
        f.kmax = N;
    }
    f.dq = (p.D + 3) / 4;
    int a = 0;
    f.imgr = a;
    a += f.kmax + 1;
    f.imgl = a;
    a += f.kmax + p.D + 1;
    f.c0 = a;
    a += p.D + 1;
    f.c1 = a;
    a += p.D + 1;
    f.c2 = a;
    a += p.D + 1;
    f.pbuf = a;
    a += f.dq;
    f.vbuf = a;
    a += f.dq;
    f.map = f.imgr;  // the output line reuses the line buffers after the forward pass
    f.kbase = a;
    a += 21;  // K_SIZE in dp_back.inc + 4 bytes of relayout.inc
    f.mem_needed = a;
    f.ext_needed = int64_t{f.kmax} * f.dq;
    if (f.mem_needed > int64_t{cfg.mem_bytes} || f.ext_needed > int64_t{cfg.ext_bytes}) {
        std::ostringstream os;
        os << "does not fit: needs " << f.mem_needed << " bytes of local memory per PE (have "
           << cfg.mem_bytes << ", mem_bytes) and " << f.ext_needed
           << " bytes of external memory per PE for the pointers (have " << cfg.ext_bytes
           << ", ext_bytes)";
        throw FirmwareError(os.str());
    }
    return f;
}

FramePlan plan_frame(const golden::Params& p, const golden::Roi& roi,
                     const isa::MachineConfig& cfg) {
    if (golden::uses_options(p))  // SPEC A.9: golden only until the firmware implements them
        throw FirmwareError("the DP firmware implements SPEC A.1-A.7 only, not the A.9 options " +
                            golden::options_string(p) + " (use --preset paper)");
    if (!cfg.indirect)
        throw FirmwareError(
            "the DP firmware needs per-PE (indirect) addressing for its re-layout and "
            "backtrack: set indirect=on");
    FramePlan fp;
    fp.roi = roi;
    fp.P = static_cast<int>(cfg.pes);
    fp.f = plan_forward(p, roi.w, cfg);  // range and DP memory checks
    const bool bidir = p.mode == golden::Mode::Bidir;
    fp.lpb = bidir ? fp.P / 2 : fp.P;
    if (fp.lpb < 1) {
        std::ostringstream os;
        os << "too few PEs: bidir mode needs 2 PEs per line, have " << fp.P;
        throw FirmwareError(os.str());
    }
    const int H = roi.h;
    if (H <= fp.lpb) {
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
    if (static_cast<int>(fp.batches.size()) > kMaxBatches) {
        std::ostringstream os;
        os << "ROI of " << H << " lines needs " << fp.batches.size() << " batches on " << fp.P
           << " PEs; the firmware's batch table holds " << kMaxBatches
           << " (use more PEs or a shorter ROI)";
        throw FirmwareError(os.str());
    }
    for (const Batch& b : fp.batches) fp.hbmax = std::max(fp.hbmax, b.lines);
    fp.nseg = (roi.w + fp.P - 1) / fp.P;

    // Video rows share memory with buffers that are idle while they live:
    // IN rows (input re-layout) and OUT rows (output re-layout, while the map
    // in the line-buffer area is read) both go to the cost planes and pointer
    // buffers when they fit there.
    int end = fp.f.mem_needed;
    const ForwardPlan& f = fp.f;
    const int spare = f.kbase - f.c0;
    const int64_t mem = cfg.mem_bytes;
    if (2 * fp.hbmax <= spare) {
        fp.inl = f.c0;
    } else if (end + 2 * fp.hbmax <= mem) {
        fp.inl = end;
        end += 2 * fp.hbmax;
    } else {
        fp.split_in = true;  // one image per re-layout pass: one set of rows
        if (fp.hbmax <= spare) {
            fp.inl = f.c0;
        } else {
            fp.inl = end;
            end += fp.hbmax;
        }
    }
    fp.inr = fp.inl + fp.hbmax;
    if (fp.hbmax <= spare) {
        fp.out = f.c0;
    } else {
        fp.out = end;
        end += fp.hbmax;
    }
    fp.mem_needed = end;
    fp.ext_needed = f.ext_needed;
    if (fp.mem_needed > int64_t{cfg.mem_bytes}) {
        std::ostringstream os;
        os << "does not fit: needs " << fp.mem_needed << " bytes of local memory per PE, have "
           << cfg.mem_bytes << " (mem_bytes)";
        throw FirmwareError(os.str());
    }
    return fp;
}

namespace {

// The constants of the forward pass (every program that includes
// dp_forward.inc) and of the algorithm (FRAME, VOTE).
std::map<std::string, int64_t> forward_defines(const golden::Params& p, const ForwardPlan& f) {
    return {{"MODE", f.bidir ? 1 : 0},
            {"N", f.N},
            {"D", f.D},
            {"S", f.s},
            {"DS", f.ds},
            {"KMAX", f.kmax},
            {"DQ", f.dq},
            {"KM", p.km},
            {"KB", p.kb},
            {"GB", p.gb},
            {"WO", p.Wo},
            {"WD", p.Wd},
            {"IMGR", f.imgr},
            {"IMGL", f.imgl},
            {"COST0", f.c0},
            {"COST1", f.c1},
            {"COST2", f.c2},
            {"PBUF", f.pbuf},
            {"VBUF", f.vbuf},
            {"MAP", f.map},
            {"K_BASE", f.kbase},
            {"FRAME", p.frame == golden::Frame::Cyclopean ? 0
                      : p.frame == golden::Frame::Left    ? 1
                                                          : 2},
            {"VOTE", p.vote ? 1 : 0}};
}

}  // namespace

std::string frame_source() {
    return firmware_dir() + "/dp.s";
}

std::map<std::string, int64_t> frame_defines(const golden::Params& p, const FramePlan& fp) {
    std::map<std::string, int64_t> d = forward_defines(p, fp.f);
    const std::map<std::string, int64_t> frame = {
        {"P", fp.P},       {"HROI", fp.roi.h}, {"X0", fp.roi.x0},
        {"Y0", fp.roi.y0}, {"NSEG", fp.nseg},  {"INL", fp.inl},
        {"INR", fp.inr},   {"OUT", fp.out},    {"SPLIT_IN", fp.split_in ? 1 : 0}};
    for (const auto& [k, v] : frame) d[k] = v;
    return d;
}

isa::Program assemble_frame(const golden::Params& p, const FramePlan& fp) {
    isa::AsmOptions o;
    o.defines = frame_defines(p, fp);
    return isa::assemble_file(frame_source(), o);
}

const std::vector<WaveGroup>& wave_groups() {
    // dp_forward.inc (DP_NODE): the 24-bit costs of the node being
    // computed, three byte registers each: r1-r3 M, then the best of M and
    // D; r4-r6 Q = E(k-1, j+1) once loaded (temporaries before); r7-r9 the
    // running E(k, j) of the O chain (docs/firmware.md, section 2).
    static const std::vector<WaveGroup> g = {
        {"fwd_best", "forward", {1, 2, 3}},
        {"fwd_q", "forward", {4, 5, 6}},
        {"fwd_run", "forward", {7, 8, 9}},
    };
    return g;
}

std::vector<std::pair<int, uint32_t>> param_block(const FramePlan& fp) {
    std::vector<std::pair<int, uint32_t>> v;
    v.emplace_back(0, static_cast<uint32_t>(fp.batches.size()));
    for (size_t b = 0; b < fp.batches.size(); ++b) {
        const Batch& t = fp.batches[b];
        const int base = 1 + 4 * static_cast<int>(b);
        v.emplace_back(base + 0, uint32_t(t.first));
        v.emplace_back(base + 1, uint32_t(t.lines));
        v.emplace_back(base + 2, uint32_t(t.out_first));
        v.emplace_back(base + 3, uint32_t(t.out_count));
    }
    return v;
}

isa::Program assemble_forward(const golden::Params& p, const ForwardPlan& f) {
    return assemble(p, f, "dp_forward_test.s", {});
}

isa::Program assemble(const golden::Params& p, const ForwardPlan& f, const std::string& file,
                      const std::map<std::string, int64_t>& extra) {
    isa::AsmOptions o;
    o.defines = forward_defines(p, f);
    for (const auto& [k, v] : extra) o.defines[k] = v;
    return isa::assemble_file(firmware_dir() + "/" + file, o);
}

}  // namespace imap::firmware
