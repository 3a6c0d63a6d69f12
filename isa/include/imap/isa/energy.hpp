// Energy of a run (docs/energy.md): an energy per event the machine performs
// (EnergyTable, named and range-checked like CostTable), the events a run
// performed (EnergyEvents, from the executor's Stats) and their product plus
// static power over the run's time (EnergyReport). Every default is an
// assumption [A] from a published per-operation figure (45 nm, Horowitz,
// ISSCC 2014), never fitted to a chip's published total.
#pragma once

#include <array>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace imap::isa {

struct ParamInfo;
struct Stats;
struct MachineConfig;

// Energies per event in pJ, static power in uW, at the 45 nm reference
// (energy_scale scales the dynamic and clock-tree parts to another node).
struct EnergyTable {
    double e_alu_pj = 0.03;         // ALU op (add, logic, compare, move) per active PE
    double e_minmax_pj = 0.06;      // min / max (compare and select) per active PE
    double e_shift_pj = 0.03;       // shifter op per active PE
    double e_rf_pj = 0.08;          // register-file accesses of an ALU / min-max / shift op
    double e_masked_pj = 0.01;      // a PE instruction reaching a PE under mask = 0
    double e_load_pj = 0.44;        // local-memory byte read (ld / ldx), 1 KB memory
    double e_store_pj = 0.44;       // local-memory byte write (st / stx), 1 KB memory
    double mem_size_exp = 0.5;      // load / store energy x (mem_bytes / 1024)^exp
    double e_ring_hop_pj = 0.05;    // one ring hop of one PE's 8-bit ring register
    double e_mask_pj = 0.01;        // mask / status instruction, per PE
    double e_cp_pj = 1.0;           // CP instruction (32-bit ALU, register file)
    double e_issue_pj = 10.0;       // any instruction: fetch of a 64-bit word, decode, broadcast
    double e_ext_byte_pj = 250.0;   // external-memory byte (xld / xst)
    double e_ext_xfer_pj = 2000.0;  // external-memory transfer setup (per xld / xst)
    double e_video_byte_pj = 1.25;  // video byte (vin / vout), line buffer
    double s_pe_clock_pj = 0.2;     // clock tree of one PE per cycle
    double s_cp_clock_pj = 2.0;     // clock tree of the CP per cycle
    double s_pe_leak_uw = 2.0;      // leakage of one PE (uW; not scaled by energy_scale)
    double s_cp_leak_uw = 20.0;     // leakage of the CP (uW; not scaled by energy_scale)
    double energy_scale = 1.0;      // technology factor on every pJ figure (1 = 45 nm)
    double frame_rate_hz = 30.0;    // the camera's frame rate (power at the camera rate)
    std::string tech = "45nm";      // the preset the values started from (docs/energy.md 4)

    struct Field {
        const char* name;
        double EnergyTable::*ptr;
        double min, max;
        const char* unit;
        const char* doc;
        bool min_exclusive = false;  // the range excludes min (allowed: > min)
    };
    static const std::vector<Field>& fields();
    static bool has(std::string_view name);

    // Set / get by name; ConfigError for an unknown name or a value outside
    // the field's range (the message names the range).
    void set(std::string_view name, double value);
    double get(std::string_view name) const;
    void validate() const;
    std::vector<ParamInfo> list() const;

    // Technology presets (docs/energy.md section 4): a preset sets the
    // fields it names from the 45 nm defaults; the others keep their default
    // values. Parameters set after it override it. ConfigError for an
    // unknown name (the message lists the presets).
    struct Preset {
        const char* name;
        const char* source;
        std::vector<std::pair<const char*, double>> values;
    };
    static const std::vector<Preset>& presets();
    static std::string preset_names();  // "45nm|350nm|500nm"
    void apply_preset(std::string_view name);
};

// What a run did, in the units the energies are given in.
struct EnergyEvents {
    uint64_t alu_lanes = 0;     // active PE lanes of Alu-class instructions
    uint64_t minmax_lanes = 0;  // ... of MinMax-class instructions (compare / select)
    uint64_t shift_lanes = 0;   // ... of Shift-class instructions
    uint64_t load_lanes = 0;    // ... of ld / ldx (one byte each)
    uint64_t store_lanes = 0;   // ... of st / stx (one byte each)
    uint64_t masked_lanes = 0;  // PE lanes under mask = 0 of every PE-work instruction
    uint64_t ring_pe_hops = 0;  // hops x P of rxl / rxr (every PE's ring register moves)
    uint64_t mask_pe_ops = 0;   // (mask + status instructions) x P
    uint64_t cp_instructions = 0;
    uint64_t instructions = 0;   // every executed instruction (phase markers excluded)
    uint64_t ext_bytes = 0;      // bytes over the external path (len x active PEs)
    uint64_t ext_transfers = 0;  // xld + xst
    uint64_t video_bytes = 0;    // (vin + vout) x P
    uint64_t cycles = 0;
    uint64_t pes = 0;
};
// The events of a run from its statistics (P = PEs, cycles = run length).
EnergyEvents energy_events(const Stats& s, uint64_t pes, uint64_t cycles);

// Event classes of the report, in this order.
enum class EnergyClass : uint8_t {
    Alu,
    MinMax,
    Shift,
    RegFile,
    Masked,
    Load,
    Store,
    Ring,
    Mask,
    Cp,
    Issue,
    ExtByte,
    ExtXfer,
    Video,
    StaticPe,
    StaticCp,
};
inline constexpr int kEnergyClassCount = 16;
const char* to_string(EnergyClass c);  // "alu", "minmax", ... "static_pe", "static_cp"

struct EnergyReport {
    EnergyEvents events;
    std::array<double, kEnergyClassCount> by_class_pj{};
    double dynamic_pj = 0, static_pj = 0, total_pj = 0;
    double seconds = 0;   // the run's modeled time
    double power_mw = 0;  // total / seconds
    // At the camera's rate (EnergyTable::frame_rate_hz): a frame every
    // period; the machine runs the frame, then idles at its static power
    // (clock tree and leakage: static / seconds) until the next one, so
    // power_camera_mw = (total + static power x (period - seconds)) / period.
    // When the frame takes longer than the period (!keeps_up) the camera's
    // rate cannot be met: power_camera_mw = power_mw.
    double frame_rate_hz = 0;
    double period_s = 0;   // 1 / frame_rate_hz
    double static_mw = 0;  // static / seconds (0 for a run of no time)
    bool keeps_up = true;  // seconds <= period_s
    double power_camera_mw = 0;
};
// Energy of a run of `cycles` with statistics `s` on configuration `cfg`.
EnergyReport energy_of(const Stats& s, uint64_t cycles, const MachineConfig& cfg);

// The energy parameters' influence (a tornado): the frame's total energy
// with each parameter divided and multiplied by `factor`, the others as
// set; sorted by the spread (high - low), largest first. frame_rate_hz
// (no effect on the frame's energy) is left out.
struct EnergySensitivity {
    std::string name;
    double low_pj = 0, high_pj = 0;  // total with the parameter / factor and x factor
};
std::vector<EnergySensitivity> energy_tornado(const Stats& s, uint64_t cycles,
                                              const MachineConfig& cfg, double factor = 2.0);

// Energy of each phase of a run (index = phase id, as Stats::by_phase and
// Machine::phase_cycles): the phase's counted events over its own cycles, so
// that the phases add up to energy_of(s, sum of phase_cycles, cfg). Size:
// the larger of s.by_phase and phase_cycles (a missing entry counts zero).
std::vector<EnergyReport> energy_by_phase(const Stats& s, const std::vector<uint64_t>& phase_cycles,
                                          const MachineConfig& cfg);

}  // namespace imap::isa
