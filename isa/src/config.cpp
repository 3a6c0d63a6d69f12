// Machine parameters: ranges, validation, listing and setting by name.
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

#include "imap/isa/config.hpp"

namespace imap::isa {

namespace {

constexpr uint64_t kHostLimit = 1ull << 30;  // bytes of modeled memory the host allocates

std::string range_str(long double lo, long double hi) {
    std::ostringstream s;
    s << static_cast<long long>(lo) << ".." << static_cast<long long>(hi);
    return s.str();
}

[[noreturn]] void bad(std::string_view name, const std::string& value, const std::string& range) {
    throw ConfigError("invalid value " + value + " for " + std::string(name) + ": allowed " +
                      range);
}

int64_t parse_int(std::string_view name, std::string_view text) {
    const std::string t(text);
    errno = 0;
    char* end = nullptr;
    const long long v = std::strtoll(t.c_str(), &end, 0);
    if (t.empty() || errno != 0 || end == t.c_str() || *end != '\0')
        throw ConfigError("invalid value '" + t + "' for " + std::string(name) +
                          ": expected an integer");
    return v;
}

struct MachineField {
    const char* name;
    const char* range;
    const char* unit;
    const char* doc;
    bool assumption;
    bool faster;  // the default makes the machine faster than the published facts
};

const MachineField kMachineFields[] = {
    {"pes", "2..65536", "PEs", "processing elements in the linear array (board: 256)", false,
     false},
    {"clock_mhz", "0..100000 (exclusive of 0)", "MHz", "array clock (board: 40 MHz)", false, false},
    {"mem_bytes", "1..1048576", "bytes", "local memory per PE (board: 1 KB)", false, false},
    {"ext_bytes", "0..16777216", "bytes",
     "external memory per PE reached by xld/xst block transfers; 0 = none", true, false},
    {"pe_regs", "1..64", "registers", "general 8-bit registers per PE", true, true},
    {"mask_depth", "1..255", "levels", "mask stack depth (mif nesting)", true, false},
    {"call_depth", "0..255", "levels", "CP return stack depth (call/ret)", true, false},
    {"indirect", "on|off", "", "per-PE (indirect) memory addressing ldx/stx present", true, true},
    {"watchdog_cycles", "1..4611686018427387904", "cycles",
     "a run exceeding this many cycles is a runaway-program fault", false, false},
};

}  // namespace

const std::vector<CostTable::Field>& CostTable::fields() {
    static const std::vector<Field> f = {
        {"alu", &CostTable::alu, 1, 1000000, "cycles",
         "PE ALU, comparator, moves, selects; base of the shift and min/max classes", false},
        {"mem", &CostTable::mem, 1, 1000000, "cycles", "ld / st, broadcast address", false},
        {"indirect_extra", &CostTable::indirect_extra, 0, 1000000, "cycles",
         "extra cycles of ldx / stx (per-PE address) over mem", false},
        {"ring_hop", &CostTable::ring_hop, 1, 1000000, "cycles", "cycles per hop of rxl / rxr",
         false},
        {"mask", &CostTable::mask, 1, 1000000, "cycles", "mif / melse / mend / mall", false},
        {"status", &CostTable::status, 1, 1000000, "cycles",
         "rany / rall: status reduction over the mask bus (latency)", true},
        {"cp", &CostTable::cp, 1, 1000000, "cycles",
         "CP instructions: scalar ALU, param block, branches, nop, halt", false},
        {"branch_taken", &CostTable::branch_taken, 0, 1000000, "cycles",
         "extra cycles when a jump / branch / call / ret / loop is taken", false},
        {"video_line", &CostTable::video_line, 1, 1000000, "cycles",
         "vin / vout of one line (P pixels) from / to the line buffer", true},
        {"xfer_setup", &CostTable::xfer_setup, 0, 1000000, "cycles", "xld / xst fixed setup",
         false},
        {"ext_bytes_per_cycle", &CostTable::ext_bytes_per_cycle, 1, 1000000, "bytes/cycle",
         "xld / xst: bytes per cycle of the external-memory path shared by the whole array "
         "(IMAPCAR: 8)",
         false},
        {"ext_beat", &CostTable::ext_beat, 1, 1000000, "cycles",
         "xld / xst: cycles per ext_bytes_per_cycle bytes (1 = every cycle; more = a path "
         "slower than a byte per cycle)",
         false},
        {"shift_bits", &CostTable::shift_bits, 1, 7, "bits/cycle",
         "shifter: bits shifted per cycle (7 = barrel shifter, 1 = one bit per cycle)", true},
        {"minmax_extra", &CostTable::minmax_extra, 0, 1000000, "cycles",
         "extra cycles of min / max over alu (0 = compare and select in one cycle)", true},
    };
    return f;
}

void CostTable::set(std::string_view name, int64_t value) {
    for (const Field& f : fields()) {
        if (name != f.name) continue;
        if (value < static_cast<int64_t>(f.min) || value > static_cast<int64_t>(f.max))
            bad(name, std::to_string(value), range_str(f.min, f.max) + " " + f.unit);
        this->*f.ptr = static_cast<uint32_t>(value);
        return;
    }
    std::string names;
    for (const Field& f : fields()) names += std::string(names.empty() ? "" : ", ") + f.name;
    throw ConfigError("unknown cost parameter '" + std::string(name) + "' (known: " + names + ")");
}

uint32_t CostTable::get(std::string_view name) const {
    for (const Field& f : fields())
        if (name == f.name) return this->*f.ptr;
    throw ConfigError("unknown cost parameter '" + std::string(name) + "'");
}

void CostTable::validate() const {
    for (const Field& f : fields()) {
        const uint32_t v = this->*f.ptr;
        if (v < f.min || v > f.max)
            bad(f.name, std::to_string(v), range_str(f.min, f.max) + " " + f.unit);
    }
}

std::vector<ParamInfo> CostTable::list() const {
    std::vector<ParamInfo> out;
    for (const Field& f : fields())
        out.push_back({f.name, std::to_string(this->*f.ptr), range_str(f.min, f.max), f.unit,
                       "cost", f.doc, true, f.faster});
    return out;
}

void MachineConfig::validate() const {
    if (pes < 2 || pes > 65536) bad("pes", std::to_string(pes), "2..65536");
    if (!(clock_mhz > 0.0) || clock_mhz > 100000.0 || !std::isfinite(clock_mhz)) {
        std::ostringstream v;
        v << clock_mhz;
        bad("clock_mhz", v.str(), "a number > 0 and <= 100000");
    }
    if (mem_bytes < 1 || mem_bytes > (1u << 20))
        bad("mem_bytes", std::to_string(mem_bytes), "1..1048576");
    if (ext_bytes > (1u << 24)) bad("ext_bytes", std::to_string(ext_bytes), "0..16777216");
    const uint64_t P = static_cast<uint64_t>(pes);
    if (P * mem_bytes > kHostLimit)
        throw ConfigError("pes x mem_bytes = " + std::to_string(P * mem_bytes) +
                          " bytes exceeds the model's limit of 1 GiB of local memory");
    if (P * ext_bytes > kHostLimit)
        throw ConfigError("pes x ext_bytes = " + std::to_string(P * ext_bytes) +
                          " bytes exceeds the model's limit of 1 GiB of external memory");
    if (pe_regs < 1 || pe_regs > 64) bad("pe_regs", std::to_string(pe_regs), "1..64");
    if (mask_depth < 1 || mask_depth > 255) bad("mask_depth", std::to_string(mask_depth), "1..255");
    if (call_depth < 0 || call_depth > 255) bad("call_depth", std::to_string(call_depth), "0..255");
    if (watchdog_cycles < 1 || watchdog_cycles > (1ull << 62))
        bad("watchdog_cycles", std::to_string(watchdog_cycles), "1..4611686018427387904");
    costs.validate();
    board.validate();
    energy.validate();
}

std::vector<ParamInfo> MachineConfig::list() const {
    std::vector<ParamInfo> out;
    auto add = [&](const MachineField& f, std::string value) {
        out.push_back(
            {f.name, std::move(value), f.range, f.unit, "machine", f.doc, f.assumption, f.faster});
    };
    std::ostringstream clk;
    clk << clock_mhz;
    add(kMachineFields[0], std::to_string(pes));
    add(kMachineFields[1], clk.str());
    add(kMachineFields[2], std::to_string(mem_bytes));
    add(kMachineFields[3], std::to_string(ext_bytes));
    add(kMachineFields[4], std::to_string(pe_regs));
    add(kMachineFields[5], std::to_string(mask_depth));
    add(kMachineFields[6], std::to_string(call_depth));
    add(kMachineFields[7], indirect ? "on" : "off");
    add(kMachineFields[8], std::to_string(watchdog_cycles));
    for (ParamInfo& p : costs.list()) out.push_back(std::move(p));
    for (ParamInfo& p : board.list()) out.push_back(std::move(p));
    for (ParamInfo& p : energy.list()) out.push_back(std::move(p));
    return out;
}

void MachineConfig::set(std::string_view name, std::string_view value) {
    set_one(name, value);
    if (name == "xfer_setup" || name == "ext_bytes_per_cycle" || name == "ext_beat")
        board.ext_mb_s = 0;  // the cycle costs as set
    derive_board_costs();
}

void MachineConfig::set_one(std::string_view name, std::string_view value) {
    const std::string v(value);
    auto in = [&](int64_t lo, int64_t hi) {
        const int64_t x = parse_int(name, value);
        if (x < lo || x > hi) bad(name, v, range_str(lo, hi));
        return x;
    };
    if (name == "pes")
        pes = static_cast<int>(in(2, 65536));
    else if (name == "mem_bytes")
        mem_bytes = static_cast<uint32_t>(in(1, 1 << 20));
    else if (name == "ext_bytes")
        ext_bytes = static_cast<uint32_t>(in(0, 1 << 24));
    else if (name == "pe_regs")
        pe_regs = static_cast<int>(in(1, 64));
    else if (name == "mask_depth")
        mask_depth = static_cast<int>(in(1, 255));
    else if (name == "call_depth")
        call_depth = static_cast<int>(in(0, 255));
    else if (name == "watchdog_cycles")
        watchdog_cycles = static_cast<uint64_t>(in(1, 1ll << 62));
    else if (name == "indirect") {
        if (v == "on" || v == "1" || v == "true")
            indirect = true;
        else if (v == "off" || v == "0" || v == "false")
            indirect = false;
        else
            bad(name, "'" + v + "'", "on|off");
    } else if (name == "clock_mhz") {
        errno = 0;
        char* end = nullptr;
        const double d = std::strtod(v.c_str(), &end);
        if (v.empty() || errno != 0 || *end != '\0' || !(d > 0.0) || d > 100000.0)
            bad(name, "'" + v + "'", "a number > 0 and <= 100000");
        clock_mhz = d;
    } else if (name == "tech") {
        energy.apply_preset(value);
    } else if (EnergyTable::has(name) || BoardTiming::has(name)) {
        errno = 0;
        char* end = nullptr;
        const double d = std::strtod(v.c_str(), &end);
        if (v.empty() || errno != 0 || end == v.c_str() || *end != '\0' || !std::isfinite(d))
            throw ConfigError("invalid value '" + v + "' for " + std::string(name) +
                              ": expected a number");
        if (BoardTiming::has(name))
            board.set(name, d);
        else
            energy.set(name, d);
    } else {
        bool is_cost = false;
        for (const CostTable::Field& f : CostTable::fields()) is_cost |= name == f.name;
        if (!is_cost) {
            std::string names;
            for (const MachineField& f : kMachineFields) names += std::string(f.name) + ", ";
            for (const CostTable::Field& f : CostTable::fields())
                names += std::string(f.name) + ", ";
            for (const BoardTiming::Field& f : BoardTiming::fields())
                names += std::string(f.name) + ", ";
            for (const EnergyTable::Field& f : EnergyTable::fields())
                names += std::string(f.name) + (&f == &EnergyTable::fields().back() ? "" : ", ");
            throw ConfigError("unknown machine parameter '" + std::string(name) +
                              "' (known: " + names + ")");
        }
        costs.set(name, parse_int(name, value));
    }
}

}  // namespace imap::isa
