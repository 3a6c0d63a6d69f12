// Running the DP firmware on a model (models.hpp): plan, assemble, run on
// core, tlm, rtl or lockstep (those this build has), trace, and take the
// energy; an rtl / lockstep run takes its energy events from the
// instruction-set model of the same program.
#include <cstdio>
#include <string>
#include <vector>

#include "imap/engine/error.hpp"
#include "imap/engine/models.hpp"
#include "imap/engine/output_files.hpp"
#include "imap/isa/energy.hpp"
#include "imap/isa/machine.hpp"
#include "wave_rtl.hpp"
#ifdef IMAP_ENGINE_HAVE_TLM
#include "imap/tlm/system.hpp"
#endif
#ifdef IMAP_ENGINE_HAVE_RTL
#include "imap/rtl/area.hpp"
#include "imap/rtl/cache.hpp"
#include "imap/rtl/lockstep.hpp"
#include "imap/rtl/pnr.hpp"
#include "imap/rtl/system.hpp"
#endif
#ifdef IMAP_ENGINE_HAVE_WAVES
#include "imap/waves/isa_trace.hpp"
#endif

namespace imap::engine {

namespace g = imap::golden;
namespace fw = imap::firmware;

std::string model_names() {
    std::string s;
#ifdef IMAP_ENGINE_HAVE_TLM
    s += "tlm (SystemC TLM-2.0), ";
#endif
#ifdef IMAP_ENGINE_HAVE_RTL
    s += "rtl (the verilated register-transfer design), lockstep (tlm and rtl side by side, "
         "compared at every retired instruction), ";
#endif
    return s + "core (the bare instruction-set executor)";
}

std::vector<std::string> rtl_area_lines(double clock_mhz) {
    std::vector<std::string> out;
#ifdef IMAP_ENGINE_HAVE_RTL
    const imap::rtl::SynthFigures& s = imap::rtl::synthesis();
    char b[256];
    if (s.available)
        std::snprintf(b, sizeof b,
                      "  RTL area (yosys, generic cells): %llu cells per PE, %llu per CP; %llu + "
                      "%llu memory bits",
                      static_cast<unsigned long long>(s.pe.cells),
                      static_cast<unsigned long long>(s.cp.cells),
                      static_cast<unsigned long long>(s.pe.memory_bits),
                      static_cast<unsigned long long>(s.cp.memory_bits));
    else
        std::snprintf(b, sizeof b,
                      "  RTL area                not synthesized (no yosys in this build)");
    out.push_back(b);
    const std::string fmax = imap::rtl::fmax_text(imap::rtl::place_and_route(), clock_mhz);
    if (!fmax.empty()) out.push_back("  RTL " + fmax);
#else
    (void)clock_mhz;
#endif
    return out;
}

void print_rtl_area(double clock_mhz) {
    for (const std::string& l : rtl_area_lines(clock_mhz)) std::printf("%s\n", l.c_str());
}

void check_model_name(const std::string& m) {
    if (m == "core") return;
#ifdef IMAP_ENGINE_HAVE_TLM
    if (m == "tlm") return;
#endif
#ifdef IMAP_ENGINE_HAVE_RTL
    if (m == "rtl" || m == "lockstep") return;
#endif
    throw Error("invalid value '" + m + "' for --model: expected " + model_names());
}

#ifdef IMAP_ENGINE_HAVE_RTL
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

namespace {

// run_model without the energy.
ModelRun run_on_model(const std::string& model, const g::Params& p, const g::Roi& roi,
                      const g::ImageView& left, const g::ImageView& right,
                      const isa::MachineConfig& cfg, const WaveOptions* waves,
                      const RtlOptions& rf) {
    (void)rf;  // used by the rtl and lockstep models only
    ModelRun run;
    run.model = model;
    if (waves && !waves->vcd.empty() && model != "tlm" && model != "core" && model != "rtl")
        throw Error(
            "--vcd traces --model tlm or core (per instruction) or rtl (the design's signals); "
            "trace the models of a lockstep run one at a time (--model " +
            model + " cannot write one)");
    try {
        run.plan = fw::plan_frame(p, roi, cfg);
    } catch (const fw::FirmwareError& e) {
        throw Error(e.what());
    }
    const isa::Program prog = fw::assemble_frame(p, run.plan);
    run.bounds = fw::frame_bounds(p, run.plan, cfg);
    run.program_words = prog.code.size();
    run.program = prog;
    run.source = fw::frame_source(p, run.plan);
    // --model rtl writes the design's own waves (Verilator tracing); the
    // other models trace the instruction-set machine per instruction.
    const bool rtl_waves_on = model == "rtl" && waves && !waves->vcd.empty();
    WaveSession session(waves && !rtl_waves_on ? *waves : WaveOptions{}, cfg, prog);
    isa::Observer* observer = session.observer();
    auto finish_waves = [&](uint64_t end_cycle) { session.finish(end_cycle); };
#ifdef IMAP_ENGINE_HAVE_WAVES
    imap::waves::TraceSelection rtl_sel;
    if (rtl_waves_on) {
        check_output_file("--vcd", waves->vcd, false);
        try {
            rtl_sel = imap::waves::parse_trace_selection(waves->pes, waves->window, waves->signals,
                                                         waves->limit_mb, cfg);
        } catch (const imap::waves::WaveError& e) {
            throw Error(e.what());
        }
    }
#endif
    try {
#ifdef IMAP_ENGINE_HAVE_RTL
        if (model == "rtl" || model == "lockstep") {
            namespace rtl = imap::rtl;
            rtl::LockstepConfig lc;
            if (!rf.cache_dir.empty()) rtl::set_cache_dir(rf.cache_dir);
            try {
                if (!rf.inject_fault.empty())
                    lc.rtl.inject = rtl::parse_fault_injection(rf.inject_fault);
                lc.rtl.mutant = rf.mutant;
                lc.divergence_waves = rf.lockstep_waves;
                lc.validate(cfg);
#ifdef IMAP_ENGINE_HAVE_WAVES
                if (model == "rtl" && waves && !waves->vcd.empty()) {
                    lc.rtl.waves = rtl_waves(waves->vcd, rtl_sel);
                    lc.rtl.waves.validate(cfg);
                }
#endif
                rtl::check_runnable(cfg, rtl::waves_format(lc.rtl.waves.path),
                                    !lc.rtl.mutant.empty(), prog.code.size(), prog.phases.size());
            } catch (const isa::ConfigError& e) {
                throw Error(std::string("--model ") + model + ": " + e.what());
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
#ifdef IMAP_ENGINE_HAVE_WAVES
                    print_rtl_waves(lc.rtl.waves, nullptr, "", rtl_sel.limit_name);
#endif
                    throw;
                }
#ifdef IMAP_ENGINE_HAVE_WAVES
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
                print_rtl_area(cfg.clock_mhz);
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
#ifdef IMAP_ENGINE_HAVE_TLM
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
        throw Error(std::string("machine fault: ") + e.what(), kExitFault);
    }
    finish_waves(run.result.cycles);
    return run;
}

}  // namespace

ModelRun run_model(const std::string& model, const g::Params& p, const g::Roi& roi,
                   const g::ImageView& left, const g::ImageView& right,
                   const isa::MachineConfig& cfg, const WaveOptions* waves, const RtlOptions* rtl) {
    ModelRun run = run_on_model(model, p, roi, left, right, cfg, waves, rtl ? *rtl : RtlOptions{});
    if (run.divergence.empty()) run.energy = run_energy(run, cfg);
    return run;
}

nlohmann::json area_json(const isa::MachineConfig& cfg) {
#ifdef IMAP_ENGINE_HAVE_RTL
    // Silicon of this machine configuration: the design's PE and CP as
    // synthesized by yosys, scaled to cfg (docs/rtl.md, "Synthesis"); a
    // property of the configuration, so every model reports it (the sweep's
    // area column).
    if (imap::rtl::synthesis().available) {
        const imap::rtl::ArrayArea a = imap::rtl::array_area(cfg);
        return {{"cells", a.cells},
                {"memory_bits", a.memory_bits},
                {"pe_cells", a.pe_cells},
                {"cp_cells", a.cp_cells},
                {"ext_bits", a.ext_bits}};
    }
#endif
    (void)cfg;
    return nullptr;
}

nlohmann::json fmax_json(const isa::MachineConfig& cfg) {
#ifdef IMAP_ENGINE_HAVE_RTL
    // the design's timing from place and route (docs/rtl.md), like the area
    // a property of the design: every model reports it (the sweep's mark)
    const imap::rtl::PnrFigures& f = imap::rtl::place_and_route();
    if (f.available)
        return {{"mhz", f.fmax_mhz},
                {"technology", f.technology},
                {"configuration", f.configuration},
                {"clock_mhz", cfg.clock_mhz},
                {"clock_above", imap::rtl::above_fmax(f, cfg.clock_mhz)},
                {"text", imap::rtl::fmax_text(f, cfg.clock_mhz)}};
#endif
    (void)cfg;
    return nullptr;
}

}  // namespace imap::engine
