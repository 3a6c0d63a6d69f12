#include "imap/firmware/plan.hpp"

#include <algorithm>
#include <sstream>

#include "imap/isa/assembler.hpp"

namespace imap::firmware {

std::string firmware_dir() { return IMAP_FIRMWARE_DIR; }

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
    f.map = a;
    a += N;
    f.kbase = a;
    a += 17;  // K_SIZE in dp_back.inc
    f.mem_needed = a;
    f.ext_needed = int64_t{f.kmax} * f.dq;
    if (f.mem_needed > int64_t{cfg.mem_bytes} || f.ext_needed > int64_t{cfg.ext_bytes}) {
        std::ostringstream os;
        os << "does not fit: needs " << f.mem_needed << " bytes of local memory per PE (have "
           << cfg.mem_bytes << ") and " << f.ext_needed
           << " bytes of external memory per PE for the pointers (have " << cfg.ext_bytes
           << ")";
        throw FirmwareError(os.str());
    }
    return f;
}

isa::Program assemble_forward(const golden::Params& p, const ForwardPlan& f) {
    return assemble(p, f, "dp_forward_test.s", {});
}

isa::Program assemble(const golden::Params& p, const ForwardPlan& f, const std::string& file,
                      const std::map<std::string, int64_t>& extra) {
    isa::AsmOptions o;
    o.defines = {{"MODE", f.bidir ? 1 : 0},
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
    for (const auto& [k, v] : extra) o.defines[k] = v;
    return isa::assemble_file(firmware_dir() + "/" + file, o);
}

}  // namespace imap::firmware
