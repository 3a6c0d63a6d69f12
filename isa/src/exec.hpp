// Internal to imap_isa: what machine.cpp and exec.cpp share.
#pragma once

#include <cstddef>
#include <cstdint>

#include "imap/isa/machine.hpp"

namespace imap::isa::detail {

constexpr uint32_t kZeroCp = 16;     // index of the always-zero CP slot (absolute addresses)
constexpr uint8_t kFlagNoHigh = 1;   // ldx / stx: single-byte offset register
constexpr uint8_t kFlagPeWork = 2;   // ALU / memory / ring: counts towards PE utilisation
constexpr size_t kChunk = 64;        // lanes per step of a lane loop; rows are padded to it
constexpr size_t kFixedLanes = 256;  // lane count with handlers of their own (the board's)

// The handler of opcode `code` on `path`, masked (full = false) or for a
// machine whose PEs are all active; `fixed`: only for machines whose lane
// rows are kFixedLanes long. nullptr when `code` is not an opcode.
Handler handler_of(SimdPath path, uint8_t code, bool full, bool fixed);
// The sentinel after the last instruction (faults: PC ran off the end).
Handler end_of_program_handler();
// True when this CPU can run `path`.
bool cpu_supports(SimdPath path);

}  // namespace imap::isa::detail
