// The energy model: the table's fields, the events of a run, their energy
// (docs/energy.md).
#include "imap/isa/energy.hpp"

#include <algorithm>
#include <cmath>
#include <sstream>

#include "imap/isa/config.hpp"
#include "imap/isa/machine.hpp"
#include "imap/isa/opcodes.hpp"

namespace imap::isa {

namespace {

std::string num(double v) {
    std::ostringstream s;
    s << v;
    return s.str();
}

std::string range_of(const EnergyTable::Field& f) {
    return num(f.min) + ".." + num(f.max);
}

bool in_range(const EnergyTable::Field& f, double v) {
    return std::isfinite(v) && v <= f.max && (f.min_exclusive ? v > f.min : v >= f.min);
}

// "allowed 0..1e+06 Hz, exclusive of 0"
std::string allowed(const EnergyTable::Field& f) {
    return "allowed " + range_of(f) + (*f.unit ? " " : "") + f.unit +
           (f.min_exclusive ? ", exclusive of " + num(f.min) : "");
}

}  // namespace

const std::vector<EnergyTable::Field>& EnergyTable::fields() {
    using T = EnergyTable;
    static const std::vector<Field> f = {
        {"e_alu_pj", &T::e_alu_pj, 0, 1e6, "pJ",
         "ALU-class PE instruction (add, logic, compare, move, select) per active PE"},
        {"e_minmax_pj", &T::e_minmax_pj, 0, 1e6, "pJ",
         "min / max (compare and select) per active PE"},
        {"e_shift_pj", &T::e_shift_pj, 0, 1e6, "pJ", "shifter instruction per active PE"},
        {"e_rf_pj", &T::e_rf_pj, 0, 1e6, "pJ",
         "register-file reads and write of an ALU / min-max / shift instruction per active PE"},
        {"e_masked_pj", &T::e_masked_pj, 0, 1e6, "pJ",
         "a PE instruction (ALU, min-max, shift, memory) on a PE under mask 0: decode only"},
        {"e_load_pj", &T::e_load_pj, 0, 1e6, "pJ",
         "local-memory byte read (ld / ldx) per active PE, for a 1 KB memory"},
        {"e_store_pj", &T::e_store_pj, 0, 1e6, "pJ",
         "local-memory byte write (st / stx) per active PE, for a 1 KB memory"},
        {"mem_size_exp", &T::mem_size_exp, 0, 2, "",
         "local-memory access energy scales as (mem_bytes / 1024)^mem_size_exp"},
        {"e_ring_hop_pj", &T::e_ring_hop_pj, 0, 1e6, "pJ",
         "one hop of rxl / rxr on one PE (every PE's ring register moves)"},
        {"e_mask_pj", &T::e_mask_pj, 0, 1e6, "pJ", "mask / status instruction, per PE"},
        {"e_cp_pj", &T::e_cp_pj, 0, 1e6, "pJ",
         "CP instruction: 32-bit ALU and register file (branches, param block, ...)"},
        {"e_issue_pj", &T::e_issue_pj, 0, 1e6, "pJ",
         "every instruction: fetch of its 64-bit word, decode and broadcast"},
        {"e_ext_byte_pj", &T::e_ext_byte_pj, 0, 1e7, "pJ",
         "external-memory byte of xld / xst (board DRAM; not scaled by energy_scale)"},
        {"e_ext_xfer_pj", &T::e_ext_xfer_pj, 0, 1e8, "pJ",
         "external-memory transfer setup, per xld / xst (not scaled by energy_scale)"},
        {"e_video_byte_pj", &T::e_video_byte_pj, 0, 1e6, "pJ",
         "video byte of vin / vout (P per line), line buffer access"},
        {"s_pe_clock_pj", &T::s_pe_clock_pj, 0, 1e6, "pJ/cycle", "clock tree of one PE per cycle"},
        {"s_cp_clock_pj", &T::s_cp_clock_pj, 0, 1e6, "pJ/cycle", "clock tree of the CP per cycle"},
        {"s_pe_leak_uw", &T::s_pe_leak_uw, 0, 1e6, "uW",
         "leakage of one PE (not scaled by energy_scale)"},
        {"s_cp_leak_uw", &T::s_cp_leak_uw, 0, 1e6, "uW",
         "leakage of the CP (not scaled by energy_scale)"},
        {"energy_scale", &T::energy_scale, 0.001, 10000, "x",
         "technology factor on every on-chip pJ figure (1 = the 45 nm table; docs/energy.md 4)"},
        {"frame_rate_hz", &T::frame_rate_hz, 0, 1e6, "Hz",
         "the camera's frame rate: average power at the camera rate (the frame, then idle at "
         "the static power until the next; docs/energy.md 1)",
         true},
    };
    return f;
}

bool EnergyTable::has(std::string_view name) {
    for (const Field& f : fields())
        if (name == f.name) return true;
    return false;
}

void EnergyTable::set(std::string_view name, double value) {
    for (const Field& f : fields()) {
        if (name != f.name) continue;
        if (!in_range(f, value))
            throw ConfigError("invalid value " + num(value) + " for " + std::string(name) + ": " +
                              allowed(f));
        this->*f.ptr = value;
        return;
    }
    std::string names;
    for (const Field& f : fields()) names += std::string(names.empty() ? "" : ", ") + f.name;
    throw ConfigError("unknown energy parameter '" + std::string(name) + "' (known: " + names +
                      ")");
}

double EnergyTable::get(std::string_view name) const {
    for (const Field& f : fields())
        if (name == f.name) return this->*f.ptr;
    throw ConfigError("unknown energy parameter '" + std::string(name) + "'");
}

void EnergyTable::validate() const {
    for (const Field& f : fields()) {
        const double v = this->*f.ptr;
        if (!in_range(f, v))
            throw ConfigError("invalid value " + num(v) + " for " + f.name + ": " + allowed(f));
    }
}

const std::vector<EnergyTable::Preset>& EnergyTable::presets() {
    // The external memory of the older nodes: a 3.3 V PC100-class SDRAM
    // (typical datasheet currents of a 64 Mbit x16 part, not one product):
    // burst read/write ~150 mA x 3.3 V at 200 MB/s = 2.5 nJ per byte; a row
    // cycle ~110 mA x 3.3 V over tRC ~70 ns = 25 nJ per transfer.
    static const std::vector<Preset> p = {
        {"45nm", "Horowitz, ISSCC 2014 (the defaults)", {}},
        {"350nm",
         "45 nm x (350/45) x (3.3 V / 1.0 V)^2 = 85 on chip, no leakage; PC100-class SDRAM",
         {{"energy_scale", 85},
          {"s_pe_leak_uw", 0},
          {"s_cp_leak_uw", 0},
          {"e_ext_byte_pj", 2500},
          {"e_ext_xfer_pj", 25000}}},
        {"500nm",
         "45 nm x (500/45) x (3.3 V / 1.0 V)^2 = 121 on chip, no leakage; PC100-class SDRAM",
         {{"energy_scale", 121},
          {"s_pe_leak_uw", 0},
          {"s_cp_leak_uw", 0},
          {"e_ext_byte_pj", 2500},
          {"e_ext_xfer_pj", 25000}}},
    };
    return p;
}

std::string EnergyTable::preset_names() {
    std::string s;
    for (const Preset& p : presets()) s += (s.empty() ? "" : "|") + std::string(p.name);
    return s;
}

void EnergyTable::apply_preset(std::string_view name) {
    for (const Preset& p : presets()) {
        if (name != p.name) continue;
        const EnergyTable base;
        for (const Field& f : fields())
            if (f.ptr != &EnergyTable::frame_rate_hz) this->*f.ptr = base.*f.ptr;
        for (const auto& [n, v] : p.values) set(n, v);
        tech = p.name;
        return;
    }
    throw ConfigError("invalid value '" + std::string(name) + "' for tech: allowed " +
                      preset_names());
}

std::vector<ParamInfo> EnergyTable::list() const {
    std::vector<ParamInfo> out;
    out.push_back({"tech", tech, preset_names(), "", "energy",
                   "technology preset the energies start from (docs/energy.md 4); parameters "
                   "set after it override it",
                   true, false});
    for (const Field& f : fields())
        out.push_back({f.name, num(this->*f.ptr),
                       range_of(f) + (f.min_exclusive ? " (exclusive of " + num(f.min) + ")" : ""),
                       f.unit, "energy", f.doc, true, false});
    return out;
}

EnergyEvents energy_events(const Stats& s, uint64_t pes, uint64_t cycles) {
    EnergyEvents e;
    e.pes = pes;
    e.cycles = cycles;
    e.ring_pe_hops = s.ring_hops * pes;
    e.ext_bytes = s.ext_bytes;
    for (const OpInfo& i : all_ops()) {
        const size_t o = static_cast<size_t>(i.op);
        const uint64_t n = s.op_counts[o], lanes = s.op_lanes[o];
        if (n == 0) continue;
        const uint64_t masked = n * pes - lanes;
        switch (i.cost_class) {
            case CostClass::Alu:
                e.alu_lanes += lanes;
                e.masked_lanes += masked;
                break;
            case CostClass::MinMax:
                e.minmax_lanes += lanes;
                e.masked_lanes += masked;
                break;
            case CostClass::Shift:
                e.shift_lanes += lanes;
                e.masked_lanes += masked;
                break;
            case CostClass::Mem:
            case CostClass::Indirect:
                (i.op == Op::ST || i.op == Op::STX ? e.store_lanes : e.load_lanes) += lanes;
                e.masked_lanes += masked;
                break;
            case CostClass::Ring:
                break;  // hops x P above
            case CostClass::Mask:
            case CostClass::Status:
                e.mask_pe_ops += n * pes;
                break;
            case CostClass::Cp:
                e.cp_instructions += n;
                break;
            case CostClass::Video:
                e.video_bytes += n * pes;
                break;
            case CostClass::Xfer:
                e.ext_transfers += n;
                break;
            case CostClass::Phase:
                continue;  // a marker, not an instruction
        }
        e.instructions += n;
    }
    return e;
}

const char* to_string(EnergyClass c) {
    static const char* const names[kEnergyClassCount] = {
        "alu",  "minmax", "shift", "regfile",  "masked",   "load",  "store",     "ring",
        "mask", "cp",     "issue", "ext_byte", "ext_xfer", "video", "static_pe", "static_cp"};
    const auto i = static_cast<size_t>(c);
    return i < kEnergyClassCount ? names[i] : "?";
}

EnergyReport energy_of(const Stats& s, uint64_t cycles, const MachineConfig& cfg) {
    const EnergyTable& t = cfg.energy;
    EnergyReport r;
    r.events = energy_events(s, static_cast<uint64_t>(cfg.pes), cycles);
    const EnergyEvents& e = r.events;
    const double k = t.energy_scale;
    const double mem = std::pow(static_cast<double>(cfg.mem_bytes) / 1024.0, t.mem_size_exp);
    const auto d = [](uint64_t n) { return static_cast<double>(n); };
    auto& c = r.by_class_pj;
    c[size_t(EnergyClass::Alu)] = d(e.alu_lanes) * t.e_alu_pj * k;
    c[size_t(EnergyClass::MinMax)] = d(e.minmax_lanes) * t.e_minmax_pj * k;
    c[size_t(EnergyClass::Shift)] = d(e.shift_lanes) * t.e_shift_pj * k;
    c[size_t(EnergyClass::RegFile)] =
        d(e.alu_lanes + e.minmax_lanes + e.shift_lanes) * t.e_rf_pj * k;
    c[size_t(EnergyClass::Masked)] = d(e.masked_lanes) * t.e_masked_pj * k;
    c[size_t(EnergyClass::Load)] = d(e.load_lanes) * t.e_load_pj * mem * k;
    c[size_t(EnergyClass::Store)] = d(e.store_lanes) * t.e_store_pj * mem * k;
    c[size_t(EnergyClass::Ring)] = d(e.ring_pe_hops) * t.e_ring_hop_pj * k;
    c[size_t(EnergyClass::Mask)] = d(e.mask_pe_ops) * t.e_mask_pj * k;
    c[size_t(EnergyClass::Cp)] = d(e.cp_instructions) * t.e_cp_pj * k;
    c[size_t(EnergyClass::Issue)] = d(e.instructions) * t.e_issue_pj * k;
    c[size_t(EnergyClass::ExtByte)] = d(e.ext_bytes) * t.e_ext_byte_pj;
    c[size_t(EnergyClass::ExtXfer)] = d(e.ext_transfers) * t.e_ext_xfer_pj;
    c[size_t(EnergyClass::Video)] = d(e.video_bytes) * t.e_video_byte_pj * k;
    r.seconds = cfg.seconds(cycles);
    // uW x s = 1e-6 J = 1e6 pJ
    c[size_t(EnergyClass::StaticPe)] =
        d(e.pes) * (d(cycles) * t.s_pe_clock_pj * k + r.seconds * t.s_pe_leak_uw * 1e6);
    c[size_t(EnergyClass::StaticCp)] =
        d(cycles) * t.s_cp_clock_pj * k + r.seconds * t.s_cp_leak_uw * 1e6;
    for (int i = 0; i < kEnergyClassCount; ++i)
        (i >= static_cast<int>(EnergyClass::StaticPe) ? r.static_pj : r.dynamic_pj) += c[size_t(i)];
    r.total_pj = r.dynamic_pj + r.static_pj;
    r.power_mw = r.seconds > 0 ? r.total_pj * 1e-9 / r.seconds : 0.0;
    // pJ / s = 1e-9 mW
    r.frame_rate_hz = t.frame_rate_hz;
    r.period_s = 1.0 / t.frame_rate_hz;
    r.static_mw = r.seconds > 0 ? r.static_pj * 1e-9 / r.seconds : 0.0;
    r.keeps_up = r.seconds <= r.period_s;
    r.power_camera_mw =
        r.keeps_up ? (r.total_pj * 1e-9 + r.static_mw * (r.period_s - r.seconds)) * r.frame_rate_hz
                   : r.power_mw;
    return r;
}

std::vector<EnergyReport> energy_by_phase(const Stats& s, const std::vector<uint64_t>& phase_cycles,
                                          const MachineConfig& cfg) {
    const size_t n = std::max(s.by_phase.size(), phase_cycles.size());
    std::vector<EnergyReport> out;
    out.reserve(n);
    const Stats none;
    for (size_t i = 0; i < n; ++i)
        out.push_back(energy_of(i < s.by_phase.size() ? s.by_phase[i] : none,
                                i < phase_cycles.size() ? phase_cycles[i] : 0, cfg));
    return out;
}

}  // namespace imap::isa

namespace imap::isa {

std::vector<EnergySensitivity> energy_tornado(const Stats& s, uint64_t cycles,
                                              const MachineConfig& cfg, double factor) {
    std::vector<EnergySensitivity> out;
    for (const EnergyTable::Field& f : EnergyTable::fields()) {
        if (f.ptr == &EnergyTable::frame_rate_hz) continue;
        EnergySensitivity e;
        e.name = f.name;
        MachineConfig c = cfg;
        const double v = cfg.energy.*f.ptr;
        // clamped to the field's range (energy_scale stays above its minimum)
        c.energy.*f.ptr = std::max(f.min, v / factor);
        e.low_pj = energy_of(s, cycles, c).total_pj;
        c.energy.*f.ptr = std::min(f.max, v * factor);
        e.high_pj = energy_of(s, cycles, c).total_pj;
        out.push_back(e);
    }
    std::stable_sort(out.begin(), out.end(),
                     [](const EnergySensitivity& a, const EnergySensitivity& b) {
                         return a.high_pj - a.low_pj > b.high_pj - b.low_pj;
                     });
    return out;
}

}  // namespace imap::isa
