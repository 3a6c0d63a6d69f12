// Pieces of the instruction-level waves (IsaTracer) kept apart from the
// tracer itself: naming, widths, the disassembly cache and the per-PE
// signals with their .gtkw group.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "imap/isa/config.hpp"
#include "imap/isa/program.hpp"
#include "imap/waves/gtkw.hpp"
#include "imap/waves/vcd.hpp"

namespace imap::waves {

struct TraceSelection;

namespace detail {

inline constexpr int kInstrChars = 32;  // width of the ASCII instruction signal
inline constexpr int kOpChars = 8;      // ... of the mnemonic
inline constexpr int kArgsChars = 24;   // ... of the operands
inline constexpr int kPhaseChars = 16;  // width of the ASCII phase signal

// Bits needed to hold values 0..max_value (at least 1).
int bits_for(uint64_t max_value);
// Scope name of a PE, zero-padded to the widest index ("pe007").
std::string pe_scope(int pe, int pes);
// The .gtkw file next to a VCD (extension replaced, or appended).
std::string gtkw_path_of(const std::string& vcd);
std::string base_name(const std::string& path);
// Writer options: timescale from the clock, size limit, a header comment
// naming the trace kind.
VcdOptions vcd_options(const isa::MachineConfig& cfg, const TraceSelection& sel, const char* kind);

// Disassembly of each PC, white space collapsed, computed once.
class DisasmCache {
  public:
    explicit DisasmCache(const isa::Program& prog);
    const std::string& text(uint32_t pc);  // "" for a PC outside the program
    // The mnemonic ("ld") and the operands ("r13, [c2 + 80]") of text(pc).
    std::string mnemonic(uint32_t pc);
    std::string operands(uint32_t pc);

  private:
    const isa::Program& prog_;
    std::vector<std::string> text_;
    std::vector<bool> have_;
};

// The per-PE signals of the selected groups.
struct PeSignals {
    int pe = 0;
    std::vector<SignalId> r;
    SignalId c = 0, t = 0, m = 0, we = 0, addr = 0, data = 0, ext_we = 0, ext_addr = 0,
             ext_data = 0, ring_we = 0, ring_data = 0;
};
// Declares PE `pe`'s scope and signals; ext_bits > 0 adds the external
// memory strobes to the mem group.
PeSignals declare_pe(VcdWriter& w, const TraceSelection& sel, int pe, int pes, int nregs,
                     int addr_bits, int ext_bits);
// The PE's group in the view (its registers folded except for the first PE).
void view_pe(GtkwSave& g, const VcdWriter& w, const TraceSelection& sel, const PeSignals& s,
             bool ext, bool first);
// The selection's register groups that this trace can show (every register
// traced); WaveError naming the group otherwise.
void check_groups(const TraceSelection& sel, int nregs);

}  // namespace detail
}  // namespace imap::waves
