#include "model_runner.hpp"

#include <cstdio>

#include "imap/isa/machine.hpp"
#ifdef IMAPSIM_HAVE_TLM
#include "imap/tlm/system.hpp"
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
    app->add_option("--set", f.sets,
                    "any machine or cost parameter, NAME=VALUE (e.g. ring_hop=2); repeatable")
        ->group(grp);
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
#ifdef IMAPSIM_HAVE_TLM
    return "tlm (SystemC TLM-2.0), core (the bare instruction-set executor)";
#else
    return "core (the bare instruction-set executor)";
#endif
}

void check_model_name(const std::string& m) {
    if (m == "core") return;
#ifdef IMAPSIM_HAVE_TLM
    if (m == "tlm") return;
#endif
    throw UserError("invalid value '" + m + "' for --model: expected " + model_names());
}

ModelRun run_model(const std::string& model, const g::Params& p, const g::Roi& roi,
                   const g::ImageView& left, const g::ImageView& right,
                   const isa::MachineConfig& cfg) {
    ModelRun run;
    run.model = model;
    try {
        run.plan = fw::plan_frame(p, roi, cfg);
    } catch (const fw::FirmwareError& e) {
        throw UserError(e.what());
    }
    const isa::Program prog = fw::assemble_frame(p, run.plan);
    run.program_words = prog.code.size();
    try {
#ifdef IMAPSIM_HAVE_TLM
        if (model == "tlm") {
            imap::tlm::OutputImages out;
            const imap::tlm::TlmRunResult tr =
                imap::tlm::run_tlm(cfg, prog, fw::param_block(run.plan), fw::to_video_image(left),
                                   fw::to_video_image(right), roi.w, roi.h, &out);
            fw::FrameResult& r = run.result;
            r.cycles = tr.cycles;
            r.modeled_ms = tr.modeled_ms;
            r.wall_s = tr.wall_s;
            r.phases = fw::phase_table(prog, tr.phase_cycles);
            r.stats = tr.stats;
            r.map.width = roi.w;
            r.map.height = roi.h;
            r.map.data = out.image[0].pixels;
            return run;
        }
#endif
        run.result = fw::run_frame_core(run.plan, prog, left, right, cfg);
    } catch (const isa::Fault& e) {
        throw UserError(std::string("machine fault: ") + e.what(), kExitFault);
    }
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
    std::printf("  phases:\n");
    for (const auto& [name, cyc] : r.phases)
        std::printf("    %-14s %10llu cycles  %5.1f%%  %8.3f ms\n", name.c_str(),
                    static_cast<unsigned long long>(cyc),
                    100.0 * static_cast<double>(cyc) / static_cast<double>(r.cycles),
                    cfg.seconds(cyc) * 1e3);
    const double util = r.stats.pe_cycles == 0
                            ? 0.0
                            : static_cast<double>(r.stats.active_lane_cycles) /
                                  (static_cast<double>(cfg.pes) * static_cast<double>(r.cycles));
    std::printf("  PE utilisation: %.1f%% (active PE-cycles / (PEs x cycles))\n", 100.0 * util);
    std::printf(
        "  wall: %.3f s (%s), %.2f Mcycles/s simulated, modeled/wall = %.2f; golden %.2f "
        "ms\n",
        r.wall_s, run.model.c_str(),
        r.wall_s > 0 ? static_cast<double>(r.cycles) / r.wall_s / 1e6 : 0.0,
        r.wall_s > 0 ? r.modeled_ms / 1e3 / r.wall_s : 0.0, golden_ms);
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
    j["pe_utilisation"] =
        static_cast<double>(r.stats.active_lane_cycles) /
        (static_cast<double>(cfg.pes) * static_cast<double>(std::max<uint64_t>(1, r.cycles)));
    nlohmann::json prm;
    prm["algorithm"] = {{"D", p.D},
                        {"km", p.km},
                        {"kb", p.kb},
                        {"gb", p.gb},
                        {"Wo", p.Wo},
                        {"Wd", p.Wd},
                        {"mode", g::to_string(p.mode)},
                        {"seed_col", g::seed_col_string(p.seed_col)},
                        {"seed_disp", g::seed_disp_string(p.seed_disp)},
                        {"vote", p.vote},
                        {"frame", g::to_string(p.frame)},
                        {"roi", {roi.x0, roi.y0, roi.w, roi.h}}};
    nlohmann::json mach = nlohmann::json::object();
    for (const isa::ParamInfo& pi : cfg.list()) mach[pi.name] = pi.value;
    prm["machine"] = mach;
    prm["firmware"] = {{"words", run.program_words},
                       {"local_bytes_per_pe", run.plan.mem_needed},
                       {"external_bytes_per_pe", run.plan.ext_needed},
                       {"batches", run.plan.batches.size()},
                       {"segments", run.plan.nseg},
                       {"split_input_relayout", run.plan.split_in},
                       {"seed_col_resolved", run.plan.f.s}};
    j["params"] = prm;
    return j;
}

}  // namespace imapsim
