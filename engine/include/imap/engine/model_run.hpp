// One run of the DP firmware on a model and what is reported about it: the
// run itself (plan, program, frame result, the machine's bounds, the
// model's own fields), its comparison with the golden, its energy (computed
// once per run) and the JSON run report (`imapsim run --report`). Plain C++:
// the models that run it are in models.hpp (imap_engine_models).
#pragma once

#include <cstdint>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "imap/firmware/bounds.hpp"
#include "imap/firmware/plan.hpp"
#include "imap/firmware/run.hpp"
#include "imap/golden/params.hpp"
#include "imap/isa/config.hpp"
#include "imap/isa/energy.hpp"
#include "imap/isa/program.hpp"

namespace imap::engine {

// The energy of a frame (docs/energy.md): the frame's, each phase's that
// ran (in program order; empty when the model did not split its counts by
// phase) and the tornado (each energy parameter halved and doubled).
struct RunEnergy {
    isa::EnergyReport frame;
    std::vector<std::pair<std::string, isa::EnergyReport>> phases;
    std::vector<isa::EnergySensitivity> tornado;
};

struct ModelRun {
    std::string model;
    firmware::FramePlan plan;
    size_t program_words = 0;
    isa::Program program;  // the program that ran
    std::string source;    // its generated source (constants, plan macros, .include of dp.s)
    firmware::FrameResult result;
    // The machine's bound of each phase (docs/firmware.md, section 11).
    firmware::FrameBounds bounds;
    // What the model itself reports, merged into the run report: "rtl"
    // (configuration, clocks), "lockstep" (instructions retired and
    // compared, both models' cycles, the first divergence).
    nlohmann::json model_info = nlohmann::json::object();
    // Where the energy model's event counts come from: "isa" (the
    // instruction-set executor that ran: core, tlm), or for rtl / lockstep
    // the instruction-set model's counts of the same program (docs/energy.md 5).
    std::string energy_source = "isa";
    // The run's energy (run_energy), filled when the run finished.
    RunEnergy energy;
    // A lockstep divergence: its one-line message (empty when none). The
    // run stopped there, so `result` holds no map and no energy.
    std::string divergence;
};

// The energy of a finished run on `cfg`.
RunEnergy run_energy(const ModelRun& run, const isa::MachineConfig& cfg);

struct Comparison {
    bool equal = true;
    size_t differing = 0;
    int first_x = -1, first_y = -1;
    int model_value = 0, golden_value = 0;
};
Comparison compare_maps(const golden::DisparityMap& got, const golden::DisparityMap& want);

// The "energy" object of a run report (without "tech" and "tornado").
nlohmann::json energy_json(const RunEnergy& e, const std::string& events_source);
// The tornado as [{name, half_uj, double_uj}].
nlohmann::json tornado_json(const std::vector<isa::EnergySensitivity>& t);

// The report of a lockstep run that diverged: the model's fields (the
// lockstep's, with the divergence) and the parameters; no map, no cycles.
nlohmann::json divergence_report(const ModelRun& run, const golden::Params& p,
                                 const golden::Roi& roi, const isa::MachineConfig& cfg);

// The report of a finished run (docs/cli.md: `imapsim run --report`);
// `area` is the configuration's synthesized area ("area" key), `design_fmax`
// the design's Fmax against the clock ("design_fmax" key), null for none.
nlohmann::json run_report(const ModelRun& run, const Comparison& cmp, const golden::Params& p,
                          const golden::Roi& roi, const isa::MachineConfig& cfg, double golden_ms,
                          const nlohmann::json& area = nullptr,
                          const nlohmann::json& design_fmax = nullptr);

// The emitted firmware source of a run (`imapsim run --emit-defines`): the
// planner's constants and per-column plan macros ending with the .include of
// dp.s, after a header saying how to assemble it (inc_path: where it is
// written) and how to exec the result (emit_program: the program's file, if
// any); `source` names the run's input.
std::string firmware_source_text(const ModelRun& run, const std::string& source,
                                 const isa::MachineConfig& cfg, const std::string& emit_program,
                                 const std::string& inc_path);

}  // namespace imap::engine
