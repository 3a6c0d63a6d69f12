#include "model_runner.hpp"

#include <algorithm>
#include <cstdio>

#include "imap/isa/energy.hpp"
#include "imap/isa/machine.hpp"
#ifdef IMAPSIM_HAVE_TLM
#include "imap/tlm/system.hpp"
#endif
#ifdef IMAPSIM_HAVE_RTL
#include "imap/rtl/area.hpp"
#include "imap/rtl/lockstep.hpp"
#include "imap/rtl/system.hpp"
#endif
#ifdef IMAPSIM_HAVE_WAVES
#include <filesystem>
#include <memory>

#include "imap/waves/isa_trace.hpp"
#endif

namespace imapsim {

namespace g = imap::golden;
namespace fw = imap::firmware;
namespace isa = imap::isa;

void add_machine_flags(CLI::App* app, MachineFlags& f) {
    const isa::MachineConfig d;
    const char* grp = "Machine (docs/isa.md)";
    app->add_option("--pes", f.pes, "PEs in the array (>= 2) [default: 256]")->group(grp);
    app->add_option("--clock-mhz", f.clock_mhz, "array clock in MHz [default: 40]")->group(grp);
    app->add_option("--mem-bytes", f.mem_bytes, "local memory per PE [default: 1024]")->group(grp);
    app->add_option("--ext-bytes", f.ext_bytes, "external memory per PE, 0 = none [default: 65536]")
        ->group(grp);
    app->add_option("--camera", f.camera,
                    "camera timing (docs/isa.md 2.4): ideal (lines already in the line buffer), "
                    "ntsc (12.27 MHz pixel clock) or pixel-clock:MHZ [default: ideal]")
        ->group(grp);
    app->add_option("--set", f.sets,
                    "any machine, cost, board or energy parameter, NAME=VALUE (e.g. ring_hop=2, "
                    "ext_mb_s=400); repeatable")
        ->group(grp);
}

// --camera: the pixel clock it names, in MHz (0 = ideal).
std::string camera_pixel_mhz(const std::string& v) {
    if (v == "ideal") return "0";
    if (v == "ntsc") return "12.2727";  // NTSC square pixels: 780 x 525 x 29.97 Hz
    const std::string pre = "pixel-clock:";
    if (v.compare(0, pre.size(), pre) == 0 && v.size() > pre.size()) {
        const std::string mhz = v.substr(pre.size());
        char* end = nullptr;
        const double d = std::strtod(mhz.c_str(), &end);
        if (*end == '\0' && d > 0) return mhz;
    }
    throw UserError("invalid value '" + v +
                    "' for --camera: expected ideal, ntsc or pixel-clock:MHZ with MHZ > 0");
}

isa::MachineConfig parse_machine_flags(const MachineFlags& f) {
    isa::MachineConfig cfg;
    auto set = [&](const std::string& flag, const std::string& name, const std::string& value) {
        if (value.empty()) return;
        try {
            cfg.set(name, value);
        } catch (const std::exception& e) {
            throw UserError(flag + ": " + e.what());
        }
    };
    set("--pes", "pes", f.pes);
    set("--clock-mhz", "clock_mhz", f.clock_mhz);
    set("--mem-bytes", "mem_bytes", f.mem_bytes);
    set("--ext-bytes", "ext_bytes", f.ext_bytes);
    if (!f.camera.empty()) set("--camera", "camera_pixel_mhz", camera_pixel_mhz(f.camera));
    for (const std::string& s : f.sets) {
        const size_t eq = s.find('=');
        if (eq == std::string::npos || eq == 0)
            throw UserError("invalid value '" + s + "' for --set: expected NAME=VALUE");
        set("--set", s.substr(0, eq), s.substr(eq + 1));
    }
    try {
        cfg.validate();
    } catch (const std::exception& e) {
        throw UserError(e.what());
    }
    return cfg;
}

std::string model_names() {
    std::string s;
#ifdef IMAPSIM_HAVE_TLM
    s += "tlm (SystemC TLM-2.0), ";
#endif
#ifdef IMAPSIM_HAVE_RTL
    s += "rtl (the verilated register-transfer design), lockstep (tlm and rtl side by side, "
         "compared at every retired instruction), ";
#endif
    return s + "core (the bare instruction-set executor)";
}

void print_rtl_area() {
#ifdef IMAPSIM_HAVE_RTL
    const imap::rtl::SynthFigures& s = imap::rtl::synthesis();
    if (!s.available) {
        std::printf("  RTL area                not synthesized (no yosys in this build)\n");
        return;
    }
    std::printf(
        "  RTL area (yosys, generic cells): %llu cells per PE, %llu per CP; %llu + %llu "
        "memory bits\n",
        static_cast<unsigned long long>(s.pe.cells), static_cast<unsigned long long>(s.cp.cells),
        static_cast<unsigned long long>(s.pe.memory_bits),
        static_cast<unsigned long long>(s.cp.memory_bits));
#endif
}

namespace {
RtlFlags g_rtl_flags;

#if defined(IMAPSIM_HAVE_RTL) && defined(IMAPSIM_HAVE_WAVES)
// --vcd with --model rtl: the design's own signals (Verilator tracing); the
// selection of PEs and the window as for the other models, the signal
// groups mapped onto the design's hierarchy (docs/rtl.md, "Waves").
imap::rtl::RtlWaves rtl_waves(const std::string& path, const imap::waves::TraceSelection& s) {
    imap::rtl::RtlWaves w;
    w.path = path;
    w.t0 = s.t0;
    w.t1 = s.t1 == UINT64_MAX ? UINT64_MAX : s.t1 - 1;
    w.limit_bytes = s.limit_bytes;
    w.pes = s.pes;
    if (s.cp) w.groups.push_back("cp"), w.groups.push_back("board");
    if (s.ring || s.mask) w.groups.push_back("array");
    if (s.regs || s.mem) w.groups.push_back("pe");
    return w;
}

// The waves line of an RTL run, as the ISA tracer's: a "->" line only for a
// file that exists, and the same warnings (stopped at the size limit; an
// empty window).
void print_rtl_waves(const imap::rtl::RtlWaves& w, const imap::rtl::RtlRunResult* rr,
                     const std::string& window, const std::string& limit_name) {
    if (w.path.empty()) return;
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(w.path, ec);
    if (ec) {
        std::fflush(stdout);
        std::fprintf(stderr, "warning: --vcd: no waves were written to %s\n", w.path.c_str());
        return;
    }
    const bool limited = rr && rr->waves_limited;
    std::printf("  waves -> %s (%.2f MB, the design's signals%s) + %s\n", w.path.c_str(),
                static_cast<double>(bytes) / 1048576.0,
                limited ? ", stopped at --trace-limit-mb" : "",
                imap::rtl::gtkw_path(w.path).c_str());
    std::fflush(stdout);
    if (limited)
        std::fprintf(stderr,
                     "warning: --vcd: the trace stopped at %s (valid up to there); narrow "
                     "--trace-window / --trace-pes or raise the limit\n",
                     limit_name.c_str());
    if (rr && rr->waves_empty)
        std::fprintf(stderr,
                     "warning: --trace-window %s starts at cycle %llu, after the end of the run "
                     "(cycle %llu): the trace holds the final state only\n",
                     window.c_str(), static_cast<unsigned long long>(w.t0),
                     static_cast<unsigned long long>(rr->cycles));
}
#endif
}  // namespace

void add_rtl_flags(CLI::App* app, RtlFlags& f) {
    const char* grp = "RTL / lockstep (docs/rtl.md)";
    app->add_option("--inject-fault", f.inject_fault,
                    "--model rtl / lockstep: XOR MASK into register REG (rN, c, t, m) of PE "
                    "after instruction INSTR, RTL side only: INSTR:PE:REG:MASK")
        ->group(grp);
    app->add_option("--rtl-mutant", f.mutant,
                    "--model rtl / lockstep: run the mutation-check model with this planted bug "
                    "(docs/rtl.md)")
        ->group(grp);
    app->add_option("--lockstep-waves", f.lockstep_waves,
                    "--model lockstep: waves (.vcd / .fst) of the RTL before a divergence, '' = "
                    "none [default: rtl_divergence.fst]")
        ->group(grp);
}

void set_rtl_flags(const RtlFlags& f) {
    g_rtl_flags = f;
}

void check_model_name(const std::string& m) {
    if (m == "core") return;
#ifdef IMAPSIM_HAVE_TLM
    if (m == "tlm") return;
#endif
#ifdef IMAPSIM_HAVE_RTL
    if (m == "rtl" || m == "lockstep") return;
#endif
    throw UserError("invalid value '" + m + "' for --model: expected " + model_names());
}

void add_wave_flags(CLI::App* app, WaveFlags& f) {
    const char* grp = "Waves (docs/waves.md)";
    app->add_option("--vcd", f.vcd,
                    "write a VCD of the run here (off by default) and a GTKWave view next to it "
                    "(same name, .gtkw)")
        ->group(grp);
    app->add_option("--trace-pes", f.pes,
                    "PEs to trace: a:b (inclusive) or a list 1,5,9 [default: 0:3]")
        ->group(grp);
    app->add_option("--trace-window", f.window,
                    "cycles to trace t0:t1, or times with ns/us/ms (e.g. 2.5us:3us) [default: all]")
        ->group(grp);
    app->add_option("--trace-signals", f.signals,
                    "signal groups: cp,ring,mask,mem,regs [default: all]")
        ->group(grp);
    app->add_option("--trace-limit-mb", f.limit_mb,
                    "stop tracing (the VCD stays valid) beyond this size in MB [default: 200]")
        ->group(grp);
}

void check_wave_outputs(const WaveFlags& f, const std::string& model) {
    if (f.vcd.empty()) return;
    if (lower_extension(f.vcd) == ".fst" && model != "rtl")
        throw UserError("--vcd '" + f.vcd + "': --model " + model +
                        " writes VCD, not FST: name it .vcd (GTKWave's vcd2fst converts it), "
                        "or trace --model rtl, which writes FST");
    check_output_file("--vcd", f.vcd, false);
#ifdef IMAPSIM_HAVE_WAVES
    const std::string view = imap::waves::detail::gtkw_path_of(f.vcd);
    if (view == f.vcd)
        throw UserError("--vcd '" + f.vcd +
                        "': the GTKWave view would overwrite it (use a .vcd name)");
    check_output_file("--vcd (its GTKWave view)", view, false);
#endif
}

#ifdef IMAPSIM_HAVE_WAVES
struct WaveSession::Impl {
    WaveFlags flags;
    imap::waves::TraceSelection sel;
    std::unique_ptr<imap::waves::IsaTracer> tracer;
};

WaveSession::WaveSession(const WaveFlags& f, const isa::MachineConfig& cfg,
                         const isa::Program& prog)
    : impl_(std::make_unique<Impl>()) {
    if (f.vcd.empty()) return;
    impl_->flags = f;
    try {
        imap::waves::TraceSelection sel =
            imap::waves::parse_trace_selection(f.pes, f.window, f.signals, f.limit_mb, cfg);
        for (const fw::WaveGroup& g : fw::wave_groups()) sel.groups.push_back({g.name, g.regs});
        if (sel.t1 != UINT64_MAX) {
            const double est = imap::waves::IsaTracer::estimate_bytes(sel, sel.t1 - sel.t0);
            if (est > static_cast<double>(sel.limit_bytes))
                std::fprintf(stderr,
                             "warning: --vcd: the selection (%zu PEs x %llu cycles) is "
                             "estimated at %.0f MB, above %s: the trace will stop there\n",
                             sel.pes.size(), static_cast<unsigned long long>(sel.t1 - sel.t0),
                             est / 1048576.0, sel.limit_name.c_str());
        }
        impl_->sel = sel;
        impl_->tracer = std::make_unique<imap::waves::IsaTracer>(f.vcd, cfg, prog, sel);
    } catch (const imap::waves::WaveError& e) {
        throw UserError(e.what());
    }
}

WaveSession::~WaveSession() = default;

bool WaveSession::active() const {
    return impl_->tracer != nullptr;
}

isa::Observer* WaveSession::observer() {
    return impl_->tracer.get();
}

void WaveSession::finish(uint64_t end_cycle) {
    namespace w = imap::waves;
    const w::TraceSelection& sel = impl_->sel;
    uint64_t traced = 0;
    std::string what;
    if (impl_->tracer) {
        w::IsaTracer& t = *impl_->tracer;
        try {
            t.finish(end_cycle);
        } catch (const w::WaveError& e) {
            throw UserError(std::string("--vcd: ") + e.what());
        }
        traced = t.traced_instructions();
        const bool view = t.gtkw_error().empty();
        std::printf("  waves -> %s (%.2f MB, %llu instructions traced%s)%s%s\n",
                    t.vcd_path().c_str(), static_cast<double>(t.bytes()) / 1048576.0,
                    static_cast<unsigned long long>(traced),
                    t.limit_reached() ? ", stopped at --trace-limit-mb" : "", view ? " + " : "",
                    view ? t.gtkw_path().c_str() : "");
        std::fflush(stdout);  // the warning after the line it is about
        if (!view)
            std::fprintf(stderr,
                         "warning: --vcd: the GTKWave view was not written (%s); the VCD %s is "
                         "complete and kept\n",
                         t.gtkw_error().c_str(), t.vcd_path().c_str());
        what = "instruction";
    } else {
        return;
    }
    std::fflush(stdout);
    if (traced == 0) {
        const std::string window = impl_->flags.window.empty() ? "all" : impl_->flags.window;
        if (sel.t0 >= end_cycle)
            std::fprintf(stderr,
                         "warning: --trace-window %s starts at cycle %llu, after the end of the "
                         "run (cycle %llu): the trace is empty\n",
                         window.c_str(), static_cast<unsigned long long>(sel.t0),
                         static_cast<unsigned long long>(end_cycle));
        else
            std::fprintf(stderr,
                         "warning: --trace-window %s: no %s of the run (cycles 0..%llu) starts "
                         "in it: the trace is empty\n",
                         window.c_str(), what.c_str(), static_cast<unsigned long long>(end_cycle));
    }
}
#else
struct WaveSession::Impl {};
WaveSession::WaveSession(const WaveFlags& f, const isa::MachineConfig&, const isa::Program&)
    : impl_(std::make_unique<Impl>()) {
    if (!f.vcd.empty()) throw UserError("--vcd: this imapsim has no waves library");
}
WaveSession::~WaveSession() = default;
bool WaveSession::active() const {
    return false;
}
isa::Observer* WaveSession::observer() {
    return nullptr;
}
void WaveSession::finish(uint64_t) {}
#endif

#ifdef IMAPSIM_HAVE_RTL
namespace {
// The RTL design counts executions per opcode and active PE-cycles, not the
// energy model's events (active PEs per opcode, ring hops, external bytes):
// an rtl or lockstep run takes them from the instruction-set model of the
// same program (`ref`: the lockstep's TLM side, or a core run), after
// checking that its executions per opcode and its cycles are the RTL's.
std::string adopt_isa_events(isa::Stats& rtl, uint64_t rtl_cycles, const isa::Stats& ref,
                             uint64_t ref_cycles, const std::string& who) {
    rtl.op_lanes = ref.op_lanes;
    rtl.ring_hops = ref.ring_hops;
    rtl.ext_bytes = ref.ext_bytes;
    rtl.by_phase = ref.by_phase;  // the design does not split its counters by phase
    if (rtl.op_counts == ref.op_counts && rtl_cycles == ref_cycles) return who;
    std::fflush(stdout);
    std::fprintf(stderr,
                 "warning: energy: the RTL's executions per opcode or cycles differ from the "
                 "%s's; the energy uses the %s's event counts\n",
                 who.c_str(), who.c_str());
    return who + " (differs from the RTL's counts)";
}
}  // namespace
#endif

ModelRun run_model(const std::string& model, const g::Params& p, const g::Roi& roi,
                   const g::ImageView& left, const g::ImageView& right,
                   const isa::MachineConfig& cfg, const WaveFlags* waves) {
    ModelRun run;
    run.model = model;
    if (waves && !waves->vcd.empty() && model != "tlm" && model != "core" && model != "rtl")
        throw UserError(
            "--vcd traces --model tlm or core (per instruction) or rtl (the design's signals); "
            "trace the models of a lockstep run one at a time (--model " +
            model + " cannot write one)");
    try {
        run.plan = fw::plan_frame(p, roi, cfg);
    } catch (const fw::FirmwareError& e) {
        throw UserError(e.what());
    }
    const isa::Program prog = fw::assemble_frame(p, run.plan);
    run.bounds = fw::frame_bounds(p, run.plan, cfg);
    run.program_words = prog.code.size();
    run.program = prog;
    run.source = fw::frame_source(p, run.plan);
    // --model rtl writes the design's own waves (Verilator tracing); the
    // other models trace the instruction-set machine per instruction.
    const bool rtl_waves_on = model == "rtl" && waves && !waves->vcd.empty();
    WaveSession session(waves && !rtl_waves_on ? *waves : WaveFlags{}, cfg, prog);
    isa::Observer* observer = session.observer();
    auto finish_waves = [&](uint64_t end_cycle) { session.finish(end_cycle); };
#ifdef IMAPSIM_HAVE_WAVES
    imap::waves::TraceSelection rtl_sel;
    if (rtl_waves_on) {
        check_output_file("--vcd", waves->vcd, false);
        try {
            rtl_sel = imap::waves::parse_trace_selection(waves->pes, waves->window, waves->signals,
                                                         waves->limit_mb, cfg);
        } catch (const imap::waves::WaveError& e) {
            throw UserError(e.what());
        }
    }
#endif
    try {
#ifdef IMAPSIM_HAVE_RTL
        if (model == "rtl" || model == "lockstep") {
            namespace rtl = imap::rtl;
            rtl::LockstepConfig lc;
            const RtlFlags& rf = g_rtl_flags;
            try {
                if (!rf.inject_fault.empty())
                    lc.rtl.inject = rtl::parse_fault_injection(rf.inject_fault);
                lc.rtl.mutant = rf.mutant;
                lc.divergence_waves = rf.lockstep_waves;
                lc.validate(cfg);
#ifdef IMAPSIM_HAVE_WAVES
                if (model == "rtl" && waves && !waves->vcd.empty()) {
                    lc.rtl.waves = rtl_waves(waves->vcd, rtl_sel);
                    lc.rtl.waves.validate(cfg);
                }
#endif
                rtl::check_runnable(cfg, rtl::waves_format(lc.rtl.waves.path),
                                    !lc.rtl.mutant.empty(), prog.code.size(), prog.phases.size());
            } catch (const isa::ConfigError& e) {
                throw UserError(std::string("--model ") + model + ": " + e.what());
            }
            imap::tlm::OutputImages out;
            fw::FrameResult& r = run.result;
            if (model == "rtl") {
                rtl::RtlRunResult rr;
                try {
                    rr =
                        rtl::run_rtl(cfg, prog, fw::param_block(run.plan), fw::to_video_image(left),
                                     fw::to_video_image(right), roi.w, roi.h, &out, lc.rtl);
                } catch (const isa::Fault&) {
#ifdef IMAPSIM_HAVE_WAVES
                    print_rtl_waves(lc.rtl.waves, nullptr, "", rtl_sel.limit_name);
#endif
                    throw;
                }
#ifdef IMAPSIM_HAVE_WAVES
                print_rtl_waves(lc.rtl.waves, &rr,
                                waves && !waves->window.empty() ? waves->window : "all",
                                rtl_sel.limit_name);
#endif
                r = fw::frame_result(run.plan, prog, rr, std::move(out.image[0].pixels));
                {
                    const fw::FrameResult ref =
                        fw::run_frame_core(run.plan, prog, left, right, cfg);
                    run.energy_source =
                        adopt_isa_events(r.stats, r.cycles, ref.stats, ref.cycles,
                                         "instruction-set model (core run of the same program)");
                }
                run.model_info["rtl"] = {{"configuration", rr.configuration},
                                         {"clocks", rr.clocks},
                                         {"cycles", rr.cycles},
                                         {"waves_written", rr.waves_written}};
                std::printf("  RTL design: configuration %s, %llu clocks\n",
                            rr.configuration.c_str(), static_cast<unsigned long long>(rr.clocks));
                print_rtl_area();
            } else {
                const rtl::LockstepResult lr = rtl::run_lockstep(
                    cfg, prog, fw::param_block(run.plan), fw::to_video_image(left),
                    fw::to_video_image(right), roi.w, roi.h, &out, lc);
                nlohmann::json ls = {{"instructions", lr.instructions},
                                     {"compared", lr.compared},
                                     {"cycles_tlm", lr.tlm.cycles},
                                     {"cycles_rtl", lr.rtl.cycles},
                                     {"rtl_configuration", lr.rtl.configuration},
                                     {"rtl_clocks", lr.rtl.clocks},
                                     {"wall_s", lr.wall_s},
                                     {"diverged", lr.diverged}};
                if (lr.diverged) {
                    const rtl::Divergence& d = lr.divergence;
                    ls["divergence"] = {{"instruction", d.instruction},
                                        {"cycle", d.cycle},
                                        {"pc", d.pc},
                                        {"word", d.word},
                                        {"disassembly", d.disassembly},
                                        {"what", d.what},
                                        {"pe", d.pe},
                                        {"address", d.address},
                                        {"tlm_value", d.tlm_value},
                                        {"rtl_value", d.rtl_value},
                                        {"detail", d.detail},
                                        {"reference", d.reference},
                                        {"waves", d.waves},
                                        {"message", d.message()}};
                    run.model_info["lockstep"] = ls;
                    run.divergence = d.message();
                    return run;
                }
                run.model_info["lockstep"] = ls;
                std::printf(
                    "  lockstep: TLM and RTL agree at all %llu retired instructions (%llu "
                    "compared), cycles TLM %llu = RTL %llu\n",
                    static_cast<unsigned long long>(lr.instructions),
                    static_cast<unsigned long long>(lr.compared),
                    static_cast<unsigned long long>(lr.tlm.cycles),
                    static_cast<unsigned long long>(lr.rtl.cycles));
                r = fw::frame_result(run.plan, prog, lr.rtl, std::move(out.image[0].pixels));
                r.wall_s = lr.wall_s;
                run.energy_source = adopt_isa_events(r.stats, r.cycles, lr.tlm.stats, lr.tlm.cycles,
                                                     "lockstep's TLM side");
            }
            finish_waves(r.cycles);
            return run;
        }
#endif
#ifdef IMAPSIM_HAVE_TLM
        if (model == "tlm") {
            imap::tlm::OutputImages out;
            imap::tlm::TlmConfig tcfg;
            tcfg.observer = observer;
            const imap::tlm::TlmRunResult tr =
                imap::tlm::run_tlm(cfg, prog, fw::param_block(run.plan), fw::to_video_image(left),
                                   fw::to_video_image(right), roi.w, roi.h, &out, tcfg);
            run.result = fw::frame_result(run.plan, prog, tr, std::move(out.image[0].pixels));
            finish_waves(run.result.cycles);
            return run;
        }
#endif
        run.result = fw::run_frame_core(run.plan, prog, left, right, cfg, observer);
    } catch (const isa::Fault& e) {
        finish_waves(e.cycle());  // the waves up to the fault are the useful part
        throw UserError(std::string("machine fault: ") + e.what(), kExitFault);
    }
    finish_waves(run.result.cycles);
    return run;
}

Comparison compare_maps(const g::DisparityMap& got, const g::DisparityMap& want) {
    Comparison c;
    if (got.width != want.width || got.height != want.height) {
        c.equal = false;
        c.differing = want.data.size();
        return c;
    }
    for (int y = 0; y < want.height; ++y)
        for (int x = 0; x < want.width; ++x)
            if (got.at(x, y) != want.at(x, y)) {
                if (c.differing++ == 0) {
                    c.first_x = x;
                    c.first_y = y;
                    c.model_value = got.at(x, y);
                    c.golden_value = want.at(x, y);
                }
            }
    c.equal = c.differing == 0;
    return c;
}

namespace {

// The energy of each phase that ran (cycles or counted events), in program
// order: the phase's counted events (Stats::by_phase) over its own cycles.
// Empty when the model did not split its counts by phase.
std::vector<std::pair<std::string, isa::EnergyReport>> phase_energies(
    const ModelRun& run, const isa::MachineConfig& cfg) {
    const fw::FrameResult& r = run.result;
    std::vector<std::pair<std::string, isa::EnergyReport>> out;
    if (r.stats.by_phase.empty()) return out;
    const size_t n = std::max(r.stats.by_phase.size(), run.program.phases.size());
    std::vector<uint64_t> cycles(n, 0);
    for (size_t i = 0; i < n; ++i)
        for (const auto& [name, cyc] : r.phases)
            if (name == run.program.phase_name(static_cast<uint32_t>(i))) cycles[i] = cyc;
    const std::vector<isa::EnergyReport> e = isa::energy_by_phase(r.stats, cycles, cfg);
    for (size_t i = 0; i < e.size(); ++i)
        if (e[i].total_pj > 0)
            out.emplace_back(run.program.phase_name(static_cast<uint32_t>(i)), e[i]);
    return out;
}

}  // namespace

nlohmann::json energy_json(const isa::EnergyReport& e, const std::string& source,
                           const std::vector<std::pair<std::string, isa::EnergyReport>>& phases) {
    nlohmann::json by = nlohmann::json::object();
    for (int i = 0; i < isa::kEnergyClassCount; ++i)
        by[isa::to_string(static_cast<isa::EnergyClass>(i))] = e.by_class_pj[size_t(i)] * 1e-6;
    const isa::EnergyEvents& v = e.events;
    const nlohmann::json ev = {{"alu_lanes", v.alu_lanes},
                               {"minmax_lanes", v.minmax_lanes},
                               {"shift_lanes", v.shift_lanes},
                               {"load_lanes", v.load_lanes},
                               {"store_lanes", v.store_lanes},
                               {"masked_lanes", v.masked_lanes},
                               {"ring_pe_hops", v.ring_pe_hops},
                               {"mask_pe_ops", v.mask_pe_ops},
                               {"cp_instructions", v.cp_instructions},
                               {"instructions", v.instructions},
                               {"ext_bytes", v.ext_bytes},
                               {"ext_transfers", v.ext_transfers},
                               {"video_bytes", v.video_bytes},
                               {"cycles", v.cycles},
                               {"pes", v.pes}};
    nlohmann::json ph = nlohmann::json::object();
    for (const auto& [name, pe] : phases) ph[name] = pe.total_pj * 1e-6;
    return {{"total_uj", e.total_pj * 1e-6},
            {"dynamic_uj", e.dynamic_pj * 1e-6},
            {"static_uj", e.static_pj * 1e-6},
            {"power_mw", e.power_mw},
            {"frame_rate_hz", e.frame_rate_hz},
            {"power_camera_mw", e.power_camera_mw},
            {"camera_keeps_up", e.keeps_up},
            {"by_class", by},
            {"events", ev},
            {"events_source", source},
            {"phases", ph}};
}

void print_energy(const isa::EnergyReport& e, const isa::MachineConfig& cfg,
                  const std::string& source,
                  const std::vector<std::pair<std::string, isa::EnergyReport>>& phases) {
    std::printf(
        "  energy: %.3f uJ per frame (dynamic %.3f, static %.3f), %.3f mW average over the "
        "frame's %.3f ms; [A] tech %s, energy_scale %g (docs/energy.md)%s%s\n",
        e.total_pj * 1e-6, e.dynamic_pj * 1e-6, e.static_pj * 1e-6, e.power_mw, e.seconds * 1e3,
        cfg.energy.tech.c_str(), cfg.energy.energy_scale,
        source == "isa" ? "" : "; events: ", source == "isa" ? "" : source.c_str());
    if (e.keeps_up)
        std::printf(
            "  power at the camera rate: %.3f mW at %g fps (every %.3f ms: the frame's %.3f ms, "
            "then idle at the static %.3f mW; frame_rate_hz)\n",
            e.power_camera_mw, e.frame_rate_hz, e.period_s * 1e3, e.seconds * 1e3, e.static_mw);
    else
        std::printf(
            "  power at the camera rate: the frame takes %.3f ms > the camera period %.3f ms "
            "(%g fps): cannot keep up; %.3f mW, the frame-time power (frame_rate_hz)\n",
            e.seconds * 1e3, e.period_s * 1e3, e.frame_rate_hz, e.power_camera_mw);
    std::vector<std::pair<double, int>> order;
    for (int i = 0; i < isa::kEnergyClassCount; ++i)
        if (e.by_class_pj[size_t(i)] > 0) order.emplace_back(e.by_class_pj[size_t(i)], i);
    std::sort(order.begin(), order.end(), [](const auto& a, const auto& b) {
        return a.first != b.first ? a.first > b.first : a.second < b.second;
    });
    std::string line;
    for (const auto& [pj, i] : order) {
        char buf[64];
        std::snprintf(buf, sizeof buf, "%s%s %.1f%%", line.empty() ? "" : ", ",
                      isa::to_string(static_cast<isa::EnergyClass>(i)),
                      e.total_pj > 0 ? 100.0 * pj / e.total_pj : 0.0);
        line += buf;
    }
    std::printf("  energy by class: %s\n", line.empty() ? "-" : line.c_str());
    if (phases.empty()) return;
    std::printf("  energy by phase (each phase's counted events over its cycles):\n");
    for (const auto& [name, pe] : phases)
        std::printf("    %-14s %10.3f uJ  %5.1f%%  (dynamic %.3f, static %.3f)\n", name.c_str(),
                    pe.total_pj * 1e-6, e.total_pj > 0 ? 100.0 * pe.total_pj / e.total_pj : 0.0,
                    pe.dynamic_pj * 1e-6, pe.static_pj * 1e-6);
}

// The energy parameters with the most influence: the frame's energy with
// each one halved and doubled (isa::energy_tornado), as % of the frame's.
void print_tornado(const std::vector<isa::EnergySensitivity>& t, size_t top) {
    if (t.empty()) return;
    // the total as set: halving then doubling a parameter brackets it
    std::string line;
    for (size_t i = 0; i < t.size() && i < top; ++i) {
        if (t[i].high_pj - t[i].low_pj <= 0) break;
        char b[96];
        std::snprintf(b, sizeof b, "%s%s %.3f..%.3f uJ", line.empty() ? "" : ", ",
                      t[i].name.c_str(), t[i].low_pj * 1e-6, t[i].high_pj * 1e-6);
        line += b;
    }
    std::printf("  energy parameters with the most influence (each x0.5 .. x2): %s\n",
                line.empty() ? "-" : line.c_str());
}

nlohmann::json tornado_json(const std::vector<isa::EnergySensitivity>& t) {
    nlohmann::json a = nlohmann::json::array();
    for (const isa::EnergySensitivity& e : t)
        a.push_back(
            {{"name", e.name}, {"half_uj", e.low_pj * 1e-6}, {"double_uj", e.high_pj * 1e-6}});
    return a;
}

void print_run_summary(const ModelRun& run, const Comparison& cmp, const isa::MachineConfig& cfg,
                       double golden_ms) {
    const fw::FrameResult& r = run.result;
    std::printf(
        "  firmware: %zu instructions, %d B local + %lld B external per PE, %zu batch%s, "
        "%d segment%s\n",
        run.program_words, run.plan.mem_needed, static_cast<long long>(run.plan.ext_needed),
        run.plan.batches.size(), run.plan.batches.size() == 1 ? "" : "es", run.plan.nseg,
        run.plan.nseg == 1 ? "" : "s");
    if (cmp.equal)
        std::printf("  bit-exact vs golden: yes (%zu pixels)\n", r.map.data.size());
    else
        std::printf(
            "  bit-exact vs golden: NO, %zu pixels differ; first at (%d,%d): model %d, "
            "golden %d\n",
            cmp.differing, cmp.first_x, cmp.first_y, cmp.model_value, cmp.golden_value);
    std::printf("  cycles: %llu, modeled time %.3f ms at %g MHz\n",
                static_cast<unsigned long long>(r.cycles), r.modeled_ms, cfg.clock_mhz);
    std::printf("  phases:                                                machine bound\n");
    for (const auto& [name, cyc] : r.phases) {
        std::printf("    %-14s %10llu cycles  %5.1f%%  %8.3f ms", name.c_str(),
                    static_cast<unsigned long long>(cyc),
                    100.0 * static_cast<double>(cyc) / static_cast<double>(r.cycles),
                    cfg.seconds(cyc) * 1e3);
        const int64_t bound = run.bounds.of(name);
        if (bound > 0)
            std::printf("  %10lld  %6.2fx\n", static_cast<long long>(bound),
                        static_cast<double>(cyc) / static_cast<double>(bound));
        else
            std::printf("           -\n");
    }
    const int64_t frame_bound = run.bounds.total();
    std::printf(
        "  machine bound: %lld cycles (%.3f ms), the frame at %.1f%% of it (bound / achieved); "
        "forward %lld states x %lld cycles per node (docs/firmware.md 11)\n",
        static_cast<long long>(frame_bound), cfg.milliseconds(static_cast<uint64_t>(frame_bound)),
        100.0 * static_cast<double>(frame_bound) /
            static_cast<double>(std::max<uint64_t>(1, r.cycles)),
        static_cast<long long>(run.bounds.states), static_cast<long long>(run.bounds.node_cycles));
    const double util = r.stats.pe_cycles == 0
                            ? 0.0
                            : static_cast<double>(r.stats.active_lane_cycles) /
                                  (static_cast<double>(cfg.pes) * static_cast<double>(r.cycles));
    std::printf("  re-layout: in %llu cycles (ring lower bound %lld), out %llu (bound %lld)\n",
                static_cast<unsigned long long>(r.relayout_in),
                static_cast<long long>(r.relayout_bound_in),
                static_cast<unsigned long long>(r.relayout_out),
                static_cast<long long>(r.relayout_bound_out));
    std::printf("  PE utilisation: %.1f%% (active PE-cycles / (PEs x cycles))\n", 100.0 * util);
    print_energy(isa::energy_of(r.stats, r.cycles, cfg), cfg, run.energy_source,
                 phase_energies(run, cfg));
    print_tornado(isa::energy_tornado(r.stats, r.cycles, cfg), 6);
    const std::string faster = faster_assumptions_text(cfg);
    if (!faster.empty())
        std::printf("  [A+] assumed, faster than the published facts (docs/isa.md 2.2): %s\n",
                    faster.c_str());
    std::printf(
        "  wall: %.3f s (%s), %.2f Mcycles/s simulated, modeled/wall = %.2f; golden %.2f "
        "ms\n",
        r.wall_s, run.model.c_str(),
        r.wall_s > 0 ? static_cast<double>(r.cycles) / r.wall_s / 1e6 : 0.0,
        r.wall_s > 0 ? r.modeled_ms / 1e3 / r.wall_s : 0.0, golden_ms);
}

namespace {

// The parameters of a run, as every report carries them.
nlohmann::json params_json(const ModelRun& run, const g::Params& p, const g::Roi& roi,
                           const isa::MachineConfig& cfg) {
    nlohmann::json prm;
    prm["algorithm"] = algo_params_json(p);
    prm["algorithm"]["roi"] = {roi.x0, roi.y0, roi.w, roi.h};
    prm["machine"] = machine_params_json(cfg);
    prm["machine_info"] = machine_param_info_json(cfg);
    prm["firmware"] = {{"words", run.program_words},
                       {"local_bytes_per_pe", run.plan.mem_needed},
                       {"external_bytes_per_pe", run.plan.ext_needed},
                       {"batches", run.plan.batches.size()},
                       {"segments", run.plan.nseg},
                       {"split_input_relayout", run.plan.split_in},
                       {"seed_col_resolved", run.plan.f.s}};
    nlohmann::json pb = nlohmann::json::object();
    for (const auto& [i, val] : fw::param_block(run.plan)) pb[std::to_string(i)] = val;
    prm["firmware"]["param_block"] = pb;
    return prm;
}

}  // namespace

nlohmann::json divergence_report(const ModelRun& run, const g::Params& p, const g::Roi& roi,
                                 const isa::MachineConfig& cfg) {
    nlohmann::json j;
    j["model"] = run.model;
    j["bit_exact"] = nullptr;  // the run stopped at the divergence: no map
    j["error"] = run.divergence;
    for (const auto& [k, v] : run.model_info.items()) j[k] = v;
    j["params"] = params_json(run, p, roi, cfg);
    return j;
}

nlohmann::json run_report(const ModelRun& run, const Comparison& cmp, const g::Params& p,
                          const g::Roi& roi, const isa::MachineConfig& cfg, double golden_ms) {
    const fw::FrameResult& r = run.result;
    nlohmann::json j;
    j["model"] = run.model;
    j["bit_exact"] = cmp.equal;
    j["differing_pixels"] = cmp.differing;
    if (!cmp.equal)
        j["first_difference"] = {{"x", cmp.first_x},
                                 {"y", cmp.first_y},
                                 {"model", cmp.model_value},
                                 {"golden", cmp.golden_value}};
    j["cycles"] = r.cycles;
    j["modeled_ms"] = r.modeled_ms;
    j["wall_s"] = r.wall_s;
    j["golden_ms"] = golden_ms;
    j["sim_cycles_per_s"] = r.wall_s > 0 ? static_cast<double>(r.cycles) / r.wall_s : 0.0;
    nlohmann::json ph = nlohmann::json::object();
    for (const auto& [name, cyc] : r.phases) ph[name] = cyc;
    j["phases"] = ph;
    nlohmann::json bd = nlohmann::json::object();
    for (const fw::PhaseBound& b : run.bounds.phases) bd[b.phase] = b.cycles;
    j["bounds"] = bd;
    j["bound_cycles"] = run.bounds.total();
    j["efficiency"] = static_cast<double>(run.bounds.total()) /
                      static_cast<double>(std::max<uint64_t>(1, r.cycles));
    j["bound_basis"] = {{"node_cycles", run.bounds.node_cycles},
                        {"valid_states", run.bounds.states}};
    j["relayout"] = {{"in_cycles", r.relayout_in},
                     {"in_lower_bound", r.relayout_bound_in},
                     {"out_cycles", r.relayout_out},
                     {"out_lower_bound", r.relayout_bound_out}};
    j["pe_utilisation"] =
        static_cast<double>(r.stats.active_lane_cycles) /
        (static_cast<double>(cfg.pes) * static_cast<double>(std::max<uint64_t>(1, r.cycles)));
    j["energy"] = energy_json(isa::energy_of(r.stats, r.cycles, cfg), run.energy_source,
                              phase_energies(run, cfg));
    j["energy"]["tech"] = cfg.energy.tech;
    j["energy"]["tornado"] = tornado_json(isa::energy_tornado(r.stats, r.cycles, cfg));
#ifdef IMAPSIM_HAVE_RTL
    // Silicon of this machine configuration: the design's PE and CP as
    // synthesized by yosys, scaled to cfg (docs/rtl.md, "Synthesis"); a
    // property of the configuration, so every model reports it (the sweep's
    // area column).
    if (imap::rtl::synthesis().available) {
        const imap::rtl::ArrayArea a = imap::rtl::array_area(cfg);
        j["area"] = {{"cells", a.cells},
                     {"memory_bits", a.memory_bits},
                     {"pe_cells", a.pe_cells},
                     {"cp_cells", a.cp_cells},
                     {"ext_bits", a.ext_bits}};
    }
#endif
    for (const auto& [k, v] : run.model_info.items()) j[k] = v;
    j["params"] = params_json(run, p, roi, cfg);
    return j;
}

}  // namespace imapsim
