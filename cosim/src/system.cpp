#include "imap/rtl/system.hpp"
#include "imap/isa/assembler.hpp"
#include "imap/tlm/sanitizer.hpp"

#include <cstring>
#include <stdexcept>

#include "bench.hpp"
#include "checker.hpp"
#include "rtl_cache_impl.hpp"
#include "support.hpp"
#include "waves_view.hpp"

#include <filesystem>
#include <fstream>

namespace imap::rtl {

namespace detail {

void claim_process(const char* who) {
    static const char* first = nullptr;
    if (first)
        throw std::logic_error(std::string(who) +
                               ": SystemC elaborates once per process (already used by " + first +
                               ")");
    first = who;
}

const ConfigInfo& pick_config(const isa::MachineConfig& cfg, const RtlConfig& rcfg) {
    const int trace = waves_format(rcfg.waves.path);
    const bool mut = !rcfg.mutant.empty();
    // without waves: the untraced variant, else a traced one (its tracing
    // stays off: IMAP_RTL_FST_ALL builds every configuration traced)
    const ConfigInfo *exact = nullptr, *traced = nullptr;
    for (const ConfigInfo& c : configs())
        if (c.pes == cfg.pes && c.mem_bytes == cfg.mem_bytes && c.ext_bytes == cfg.ext_bytes &&
            (c.mutants != 0) == mut) {
            if (c.trace == trace)
                exact = &c;
            else if (trace == 0)
                traced = &c;
        }
    if (exact) return *exact;
    if (traced) return *traced;
    throw isa::ConfigError(trace == 2   ? "RTL: FST waves need the FST variant of the configuration"
                           : trace == 1 ? "RTL: VCD waves need the VCD variant of the configuration"
                                        : "RTL: configuration not built");
}

const ConfigInfo* traced_config(const isa::MachineConfig& cfg, int format, bool mutants) {
    for (const ConfigInfo& c : configs())
        if (c.pes == cfg.pes && c.mem_bytes == cfg.mem_bytes && c.ext_bytes == cfg.ext_bytes &&
            c.trace == format && (c.mutants != 0) == mutants)
            return &c;
    return nullptr;
}

void fill_job(Job& j, const isa::MachineConfig& cfg, const isa::Program& prog,
              const std::vector<std::pair<int, uint32_t>>& params, const Image& left,
              const Image& right, int out_w, int out_h) {
    j.cfg = cfg;
    j.prog = &prog;
    j.params = params;
    j.input[0] = left;
    j.input[1] = right;
    for (Image& o : j.output) {
        o.width = out_w;
        o.height = out_h;
        o.pixels.assign(static_cast<size_t>(out_w) * static_cast<size_t>(std::max(out_h, 0)), 0);
    }
}

RtlRunResult collect(const Job& j, const Bench& b, const isa::MachineConfig& cfg,
                     const isa::Program& prog) {
    const Backdoor& bd = const_cast<Bench&>(b).backdoor();
    RtlRunResult r;
    r.halted = j.halted;
    r.cycles = j.cycles;
    r.modeled_ms = cfg.milliseconds(j.cycles);
    r.wall_s = j.wall_s;
    r.clocks = j.clocks;
    r.waves_written = j.waves_written;
    r.waves_empty = j.waves_empty;
    r.waves_limited = j.waves_limited;
    const ConfigInfo& c = b.config();
    r.configuration = std::string(c.name) + (c.mutants      ? " (mutation check)"
                                             : c.trace == 1 ? " (VCD)"
                                             : c.trace == 2 ? " (FST)"
                                                            : "");
    // the design's performance counters as isa::Stats (sequencer kinds in
    // the order of isa::CostClass: see imap_pkg::kind_t)
    static const isa::CostClass kind_class[12] = {
        isa::CostClass::Cp,    isa::CostClass::Alu,  isa::CostClass::MinMax,
        isa::CostClass::Shift, isa::CostClass::Mem,  isa::CostClass::Indirect,
        isa::CostClass::Ring,  isa::CostClass::Mask, isa::CostClass::Status,
        isa::CostClass::Video, isa::CostClass::Xfer, isa::CostClass::Phase};
    r.stats.instructions = j.instructions;
    for (int k = 0; k < 12; ++k)
        r.stats.class_cycles[static_cast<size_t>(kind_class[k])] += bd.kind_cyc[k];
    for (int o = 0; o < 256; ++o) r.stats.op_counts[static_cast<size_t>(o)] = bd.op_cnt[o];
    r.stats.pe_cycles = *bd.pe_cyc;
    r.stats.active_lane_cycles = *bd.active_cyc;
    r.phase_cycles.assign(std::max<size_t>(prog.phases.size(), 1), 0);
    for (size_t i = 0; i < r.phase_cycles.size() && i < static_cast<size_t>(bd.phases); ++i)
        r.phase_cycles[i] = bd.phase_cyc[i];
    const RtlStateData s = read_state(bd, cfg.pe_regs);
    auto st = std::make_shared<RtlState>();
    st->pes = s.pes;
    st->pe_regs = s.pe_regs;
    st->lanes = s.lanes;
    st->mem = s.mem;
    st->ext.assign(s.ext.begin(),
                   s.ext.begin() + static_cast<std::ptrdiff_t>(static_cast<size_t>(cfg.ext_bytes) *
                                                               static_cast<size_t>(cfg.pes)));
    st->creg = s.creg;
    st->param = s.param;
    st->mask_depth = s.msp;
    st->call_depth = s.csp;
    st->phase = s.phase;
    r.state = st;
    return r;
}

// Fault injection: XOR into the design's state through the backdoor right
// after instruction `n` retires (needs the trace port).
class Injector final : public Listener {
  public:
    Injector(Bench& b, const FaultInjection& f) : b_(b), f_(f) {}
    Verdict on_retire(const RetireRecord& r, const Shadow&, const Backdoor&,
                      const Touched&) override {
        if (r.index == f_.instruction) inject(b_.backdoor(), f_);
        return Verdict::Go;
    }
    Verdict on_fault(const FaultRecord&, const Shadow&) override { return Verdict::Go; }

  private:
    Bench& b_;
    FaultInjection f_;
};

Divergence assertion_divergence(const AssertionRecord& a, const isa::Program& prog) {
    Divergence d;
    d.assertion = a.name;
    d.instruction = a.index;
    d.cycle = a.cycle;
    d.pc = a.pc;
    d.pe = a.pe;
    d.reference = "";
    if (a.pc < prog.code.size()) {
        d.word = prog.code[a.pc];
        try {
            d.disassembly = isa::disassemble_word(d.word);
        } catch (const std::exception&) {
            d.disassembly = ".word";
        }
    } else {
        d.disassembly = "no instruction in execute";
    }
    const std::string w = assertion_what(a.name);
    d.what = w.empty() ? "(unknown assertion)" : w;
    return d;
}

void inject(Backdoor& bd, const FaultInjection& f) {
    const size_t p = static_cast<size_t>(f.pe);
    if (f.reg >= 0)
        bd.regs[p][f.reg] ^= f.mask;
    else if (f.reg == FaultInjection::kRegC)
        *bd.carry[p] ^= 1u;
    else if (f.reg == FaultInjection::kRegT)
        *bd.st[p] ^= 2u;
    else
        *bd.st[p] ^= 1u;
}

void finish_waves(const Job& j, const Bench& b, const isa::MachineConfig& cfg,
                  const std::string& top, const std::vector<int>& pes) {
    finish_waves_file(j.waves_path);
    WavesView v;
    v.waves_path = j.waves_path;
    v.gtkw_path = gtkw_path(j.waves_path);
    v.top = top;
    v.pes = pes;
    v.pes_total = cfg.pes;
    if (v.pes.empty())
        for (int p = 0; p < std::min(cfg.pes, 4); ++p) v.pes.push_back(p);
    v.nregs = cfg.pe_regs;
    int aw = 1;
    while ((1u << aw) < cfg.mem_bytes) ++aw;
    v.addr_bits = aw;
    v.mask_depth = kHdlMaskDepth;
    v.start_time = j.waves_open_ps;
    v.span_time = static_cast<uint64_t>(40 * b.period_ps());
    write_gtkw(v);
}

void finish_waves_file(const std::string& path) {
    const std::string part = path + ".part";
    std::error_code ec;
    std::filesystem::rename(part, path, ec);
    if (ec) throw std::runtime_error("cannot write " + path + ": " + ec.message());
    if (path.size() < 4 || path.compare(path.size() - 4, 4, ".fst") != 0) return;
    // FST header block: type (1), length (8), start / end time, endianness,
    // memory, scopes, vars, max handle, blocks (8 each), timescale (1),
    // version (128), then the date (119 bytes): cleared so that two runs give
    // the same file.
    std::fstream f(path, std::ios::in | std::ios::out | std::ios::binary);
    if (!f) throw std::runtime_error("cannot open " + path);
    char type = 0;
    f.read(&type, 1);
    if (!f || type != 0) return;  // not an FST header block first
    f.seekp(1 + 8 * 9 + 1 + 128);
    const std::string zeros(119, '\0');
    f.write(zeros.data(), static_cast<std::streamsize>(zeros.size()));
    if (!f) throw std::runtime_error("cannot write " + path);
}

}  // namespace detail

RtlRunResult run_rtl(const isa::MachineConfig& cfg, const isa::Program& prog,
                     const std::vector<std::pair<int, uint32_t>>& params, const ImageInput& left,
                     const ImageInput& right, int out_w, int out_h, OutputImages* out,
                     const RtlConfig& rcfg) {
    using namespace detail;
    cfg.validate();
    rcfg.validate(cfg);
    check_runnable(cfg, waves_format(rcfg.waves.path), !rcfg.mutant.empty(), prog.code.size(),
                   prog.phases.size());
    const ConfigInfo& ci = pick_config(cfg, rcfg);
    claim_process("run_rtl");
    tlm::detail::ElaborationGuard guard;
    Bench bench("top", ci, std::unique_ptr<Model>(ci.make("dut")), nullptr, cfg.clock_mhz);
    Job job;
    fill_job(job, cfg, prog, params, left, right, out_w, out_h);
    job.mutant = rcfg.mutant.empty() ? 0 : mutant_id(rcfg.mutant);
    std::unique_ptr<Injector> inj;
    if (rcfg.inject.enabled) {
        inj = std::make_unique<Injector>(bench, rcfg.inject);
        job.listener = inj.get();
    }
    if (!rcfg.waves.path.empty()) {
        job.waves_path = rcfg.waves.path;
        job.waves_scopes = rcfg.waves.scopes("dut", cfg.pes);
        if (job.waves_scopes.empty()) job.waves_scopes.push_back("dut.imap_tb");
        job.waves_t0 = rcfg.waves.t0;
        job.waves_t1 = rcfg.waves.t1;
        job.waves_limit_bytes = rcfg.waves.limit_bytes;
    }
    bool given = false;
    bench.next_job = [&]() -> Job* {
        if (given) return nullptr;
        given = true;
        return &job;
    };
    RtlRunResult result;
    bench.job_done = [&](Job& j) { result = collect(j, bench, cfg, prog); };
    sc_core::sc_start();
    imap::tlm::declare_main_stack_to_sanitizer();  // docs/testing.md (ASan and ended SystemC
                                                   // threads)
    if (!job.error.empty()) throw std::runtime_error("RTL testbench: " + job.error);
    if (job.waves_written) finish_waves(job, bench, cfg, "dut", rcfg.waves.pes);
    if (job.assertion.valid) {
        const Divergence d = assertion_divergence(job.assertion, prog);
        throw AssertionFailure(d.message(), d.assertion, d.instruction, d.pc, d.pe, d.cycle);
    }
    if (job.fault.valid) throw to_fault(job.fault, prog, cfg);
    if (out) {
        out->image[0] = job.output[0];
        out->image[1] = job.output[1];
    }
    return result;
}

}  // namespace imap::rtl
