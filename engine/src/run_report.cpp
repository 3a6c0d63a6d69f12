// The report of a model run (model_run.hpp): its energy (once per run), the
// comparison with the golden and the JSON run report, from a ModelRun and
// the parameters it ran with.
#include <algorithm>
#include <filesystem>

#include "imap/engine/model_run.hpp"
#include "imap/engine/params_json.hpp"
#include "imap/engine/result.hpp"

namespace imap::engine {

namespace g = imap::golden;
namespace fw = imap::firmware;

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

RunEnergy run_energy(const ModelRun& run, const isa::MachineConfig& cfg) {
    const fw::FrameResult& r = run.result;
    RunEnergy e;
    e.frame = isa::energy_of(r.stats, r.cycles, cfg);
    e.phases = phase_energies(run, cfg);
    e.tornado = isa::energy_tornado(r.stats, r.cycles, cfg);
    return e;
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

nlohmann::json energy_json(const RunEnergy& re, const std::string& source) {
    const isa::EnergyReport& e = re.frame;
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
    for (const auto& [name, pe] : re.phases) ph[name] = pe.total_pj * 1e-6;
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

nlohmann::json tornado_json(const std::vector<isa::EnergySensitivity>& t) {
    nlohmann::json a = nlohmann::json::array();
    for (const isa::EnergySensitivity& e : t)
        a.push_back(
            {{"name", e.name}, {"half_uj", e.low_pj * 1e-6}, {"double_uj", e.high_pj * 1e-6}});
    return a;
}

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
                          const g::Roi& roi, const isa::MachineConfig& cfg, double golden_ms,
                          const nlohmann::json& area, const nlohmann::json& design_fmax) {
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
    std::vector<std::pair<std::string, uint64_t>> bounds;
    for (const fw::PhaseBound& b : run.bounds.phases)
        bounds.emplace_back(b.phase, static_cast<uint64_t>(b.cycles));
    j["bounds"] = bounds_json(bounds);
    j["bound_cycles"] = run.bounds.total();
    j["efficiency"] = efficiency(static_cast<uint64_t>(run.bounds.total()), r.cycles);
    j["bound_basis"] = {{"node_cycles", run.bounds.node_cycles},
                        {"valid_states", run.bounds.states}};
    j["relayout"] = {{"in_cycles", r.relayout_in},
                     {"in_lower_bound", r.relayout_bound_in},
                     {"in_ring_bound", r.relayout_ring_in},
                     {"in_memory_bound", r.relayout_mem_in},
                     {"out_cycles", r.relayout_out},
                     {"out_lower_bound", r.relayout_bound_out},
                     {"out_ring_bound", r.relayout_ring_out},
                     {"out_memory_bound", r.relayout_mem_out}};
    j["pe_utilisation"] =
        static_cast<double>(r.stats.active_lane_cycles) /
        (static_cast<double>(cfg.pes) * static_cast<double>(std::max<uint64_t>(1, r.cycles)));
    j["energy"] = energy_json(run.energy, run.energy_source);
    j["energy"]["tech"] = cfg.energy.tech;
    j["energy"]["tornado"] = tornado_json(run.energy.tornado);
    if (!area.is_null()) j["area"] = area;
    if (!design_fmax.is_null()) j["design_fmax"] = design_fmax;
    for (const auto& [k, v] : run.model_info.items()) j[k] = v;
    j["params"] = params_json(run, p, roi, cfg);
    return j;
}

// The emitted firmware source: the planner's constants and per-column plan
// macros, ending with the .include of dp.s, after a header that says how to
// assemble it and how to exec the result.
std::string firmware_source_text(const ModelRun& run, const std::string& source,
                                 const isa::MachineConfig& cfg, const std::string& emit_program,
                                 const std::string& inc_path) {
    std::string t;
    t += "; Constants and plan of the DP firmware for one imapsim run (docs/firmware.md,\n";
    t += "; \"Assembling the firmware by hand\"): " + source + "\n";
    t += ";\n; Re-assemble (this file includes dp.s at its end):\n";
    t += ";     imapsim asm " + std::filesystem::absolute(inc_path).lexically_normal().string() +
         " -o FRAME.bin\n";
    t += "; gives the program that ran.\n";
    std::string params;
    for (const auto& [i, val] : fw::param_block(run.plan))
        params += " --param " + std::to_string(i) + "=" + std::to_string(val);
    std::string machine;
    const isa::MachineConfig def;
    const auto now = cfg.list(), base = def.list();
    for (size_t i = 0; i < now.size() && i < base.size(); ++i)
        if (now[i].value != base[i].value) machine += " --set " + now[i].name + "=" + now[i].value;
    t += "; Run it (the images of the run, whose ROI the constants X0, Y0 and the\n";
    t += "; program's size name; the map comes out of video port 0):\n";
    t += ";     imapsim exec " + (emit_program.empty() ? std::string("FRAME.bin") : emit_program) +
         " --left LEFT --right RIGHT" + params + " --out-size " + std::to_string(run.plan.roi.w) +
         "x" + std::to_string(run.plan.roi.h) + machine + " --out-left MAP.png\n";
    t += "; Param block (param[0]: the number of batches):" + params + "\n";
    t += fw::inline_firmware_includes(run.source);
    return t;
}

}  // namespace imap::engine
