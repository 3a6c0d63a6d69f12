// The machine, RTL and wave flags of the subcommands that run the machine
// (their CLI11 definitions) and the text summary of a model run; the runs
// themselves are the engine's (imap/engine/models.hpp).
#include "model_runner.hpp"

#include <algorithm>
#include <cstdio>

#include "imap/engine/result.hpp"
#ifdef IMAPSIM_HAVE_RTL
#include "imap/rtl/cache.hpp"
#endif

namespace imapsim {

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
    add_rtl_cache_flag(app, f.cache_dir);
}

void add_rtl_cache_flag(CLI::App* app, std::string& dir) {
    app->add_option("--rtl-cache", dir,
                    "folder of the RTL configurations built on demand (any --pes, --mem-bytes, "
                    "--ext-bytes not built in; docs/rtl.md), 'off' to refuse them [default: "
                    "$IMAP_RTL_CACHE, else ~/.cache/imapsim/rtl]")
        ->group("RTL / lockstep (docs/rtl.md)");
}

void apply_rtl_cache_flag(const std::string& dir) {
#ifdef IMAPSIM_HAVE_RTL
    if (!dir.empty()) imap::rtl::set_cache_dir(dir);
#else
    (void)dir;
#endif
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

static void print_energy(const isa::EnergyReport& e, const isa::MachineConfig& cfg,
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
static void print_tornado(const std::vector<isa::EnergySensitivity>& t, size_t top) {
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
        100.0 * imap::engine::efficiency(static_cast<uint64_t>(frame_bound), r.cycles),
        static_cast<long long>(run.bounds.states), static_cast<long long>(run.bounds.node_cycles));
    const double util = r.stats.pe_cycles == 0
                            ? 0.0
                            : static_cast<double>(r.stats.active_lane_cycles) /
                                  (static_cast<double>(cfg.pes) * static_cast<double>(r.cycles));
    std::printf(
        "  re-layout: in %llu cycles (lower bound %lld = ring %lld + loads/stores %lld), out %llu "
        "(bound %lld = %lld + %lld)\n",
        static_cast<unsigned long long>(r.relayout_in), static_cast<long long>(r.relayout_bound_in),
        static_cast<long long>(r.relayout_ring_in), static_cast<long long>(r.relayout_mem_in),
        static_cast<unsigned long long>(r.relayout_out),
        static_cast<long long>(r.relayout_bound_out), static_cast<long long>(r.relayout_ring_out),
        static_cast<long long>(r.relayout_mem_out));
    std::printf("  PE utilisation: %.1f%% (active PE-cycles / (PEs x cycles))\n", 100.0 * util);
    print_energy(run.energy.frame, cfg, run.energy_source, run.energy.phases);
    print_tornado(run.energy.tornado, 6);
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

}  // namespace imapsim
