// Machine parameters: everything the unpublished hardware leaves open is a
// named, documented, listable parameter (SPEC Part B). docs/isa.md explains
// each default and marks the assumptions.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "imap/isa/board.hpp"
#include "imap/isa/energy.hpp"

namespace imap::isa {

// Invalid parameter: the message names the parameter, the value and the range.
class ConfigError : public std::invalid_argument {
  public:
    using std::invalid_argument::invalid_argument;
};

// One row of a parameter report.
struct ParamInfo {
    std::string name;
    std::string value;
    std::string range;  // allowed values, e.g. "2..65536"
    std::string unit;   // "cycles", "bytes", ...
    std::string group;  // "machine", "cost" or "energy"
    std::string doc;
    bool assumption = false;  // not published for the real board: a modelling choice
    bool faster = false;      // ... and one that makes the machine faster than the published facts
};

// Cycles per instruction class. Every instruction is charged exactly one
// class (opcodes.hpp); the named fields are the only place costs live.
struct CostTable {
    uint32_t alu = 1;             // PE ALU, shifter, comparator, moves, selects
    uint32_t mem = 1;             // ld / st with a broadcast address
    uint32_t indirect_extra = 1;  // added to mem for ldx / stx
    uint32_t ring_hop = 1;        // per hop of rxl / rxr
    uint32_t mask = 1;            // mif / melse / mend / mall
    uint32_t status = 1;          // rany / rall (status reduction over the mask bus)
    uint32_t cp = 1;              // CP ALU, param-block access, branches, nop, halt
    uint32_t branch_taken = 1;    // added when a jump / branch / call / ret / loop is taken
    uint32_t video_line = 1;      // vin / vout (line already in the line buffer)
    uint32_t xfer_setup = 8;      // xld / xst fixed part
    uint32_t ext_bytes_per_cycle =
        8;                      // external-memory path of the whole array (shared by all PEs)
    uint32_t ext_beat = 1;      // cycles per ext_bytes_per_cycle bytes (rates below a byte/cycle)
    uint32_t shift_bits = 7;    // bits the shifter moves per cycle (7 = barrel, 1 = serial)
    uint32_t minmax_extra = 0;  // extra cycles of min / max over alu (0 = one-cycle select)

    struct Field {
        const char* name;
        uint32_t CostTable::*ptr;
        uint32_t min, max;
        const char* unit;
        const char* doc;
        bool faster;  // the default makes the machine faster than the published facts
    };
    static const std::vector<Field>& fields();

    // Set / get by name ("ring_hop"); throws ConfigError for an unknown name
    // or a value outside the field's range.
    void set(std::string_view name, int64_t value);
    uint32_t get(std::string_view name) const;
    void validate() const;
    std::vector<ParamInfo> list() const;

    // Cycles of the variable-cost classes (docs/isa.md section 2.2).
    // Shifter: shift by n bits (0..7; shlv / shrv count as 7).
    uint64_t shift_cycles(unsigned n) const {
        return uint64_t{alu} + (n == 0 ? 0 : (n + shift_bits - 1) / shift_bits - 1);
    }
    // xld / xst of len bytes per PE on A active PEs: their bytes share one
    // path that moves ext_bytes_per_cycle bytes every ext_beat cycles.
    uint64_t xfer_cycles(uint64_t len, uint64_t A) const {
        return uint64_t{xfer_setup} +
               (len * A + ext_bytes_per_cycle - 1) / ext_bytes_per_cycle * ext_beat;
    }
};

struct MachineConfig {
    int pes = 256;                             // PEs in the linear array (runtime)
    double clock_mhz = 40.0;                   // array clock, for modeled time only
    uint32_t mem_bytes = 1024;                 // local memory per PE
    uint32_t ext_bytes = 65536;                // external memory per PE (0 disables xld / xst)
    int pe_regs = 16;                          // general registers per PE
    int mask_depth = 8;                        // mif nesting depth
    int call_depth = 8;                        // CP return stack depth
    bool indirect = true;                      // per-PE addressing (ldx / stx) present
    uint64_t watchdog_cycles = 2000000000ull;  // runaway-program limit
    CostTable costs;     // with the external path's costs derived from `board` (set())
    BoardTiming board;   // external memory and camera timing (docs/isa.md 2.3)
    EnergyTable energy;  // energies per event (docs/energy.md); no effect on the run

    // Throws ConfigError naming the first invalid parameter and its range.
    void validate() const;
    // Every parameter (machine, cost and energy), for reports.
    std::vector<ParamInfo> list() const;
    // Set any parameter (machine, cost, board or energy) from text, as on a
    // command line: set("pes", "128"), set("ring_hop", "2"), set("indirect",
    // "off"), set("e_alu_pj", "0.5"), set("ext_mb_s", "400"). After every
    // set the external path's cycle costs follow the board timing at the
    // clock (BoardTiming::derive_costs); setting xfer_setup,
    // ext_bytes_per_cycle or ext_beat itself turns that off (ext_mb_s = 0):
    // the cycle costs then apply as set.
    void set(std::string_view name, std::string_view value);
    // set() of one parameter without the derivation that follows it.
    void set_one(std::string_view name, std::string_view value);
    // The external path's costs from the board timing at clock_mhz (set()
    // calls it; call it after changing clock_mhz or board directly).
    void derive_board_costs() { board.derive_costs(clock_mhz, costs); }
    // Cycle at which camera pixels [x0, x0 + n) of line y have arrived.
    uint64_t camera_ready_cycle(int width, int y, int x0, int n) const {
        return board.camera_ready_cycle(clock_mhz, width, y, x0, n);
    }
    // Modeled time of `cycles` at clock_mhz.
    double seconds(uint64_t cycles) const {
        return static_cast<double>(cycles) / (clock_mhz * 1e6);
    }
    // ... in milliseconds, with one rounding (cycles / (clock_mhz x 1000)),
    // so 288878 cycles at 40 MHz are 7.22195 ms, not 7.2219500000000005.
    double milliseconds(uint64_t cycles) const {
        return static_cast<double>(cycles) / (clock_mhz * 1e3);
    }
};

}  // namespace imap::isa
