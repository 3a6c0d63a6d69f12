// Firmware cost ESTIMATE of the SPEC A.9 options on the modeled machine, for
// the trade-off table of `imapsim eval --tradeoff` until the firmware
// implements them. It counts the instructions each option adds per DP node
// and per line-buffer pixel, at the default cost table (docs/isa.md: one
// cycle per ALU/memory instruction, two per per-PE load, one per ring hop),
// on top of the paper's algorithm as the firmware runs it. The reasoning
// behind every count is in docs/golden.md ("Firmware cost estimates"). These
// are estimates, not modeled cycles: they must be replaced by the measured
// firmware once it exists.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "imap/golden/params.hpp"

namespace imap::golden {

struct OptionCost {
    int64_t nodes = 0;        // DP nodes the busier PE computes (columns x D, as the firmware)
    int64_t pixels = 0;       // line-buffer pixels per PE (right + left, with the padding)
    double per_node = 0;      // cycles added per DP node
    double per_pixel = 0;     // cycles added per line-buffer pixel
    int64_t per_batch = 0;    // cycles added per batch of lines (joint: the meeting)
    int64_t cycles = 0;       // nodes * per_node + pixels * per_pixel + per_batch (one batch)
    int64_t local_bytes = 0;  // local memory added per PE
    std::vector<std::string> items;  // one line per option: "census: 14 cycles/node, ..."
};

// Added cost of the A.9 options of `p` for one batch of lines of a ROI of
// width N (p.D levels); zero for the paper's algorithm. Joint mode is
// costed as bidir plus the meeting of the two wavefronts. in_firmware: the
// firmware runs every A.9 option (--ad-max, --mode joint, --dissim bt, the
// census and the window; docs/firmware.md, section 10), so their cost is in
// the measured part and nothing is estimated.
OptionCost estimate_options(const Params& p, int N, bool in_firmware = false);

// The paper part of `p`: the same parameters with every A.9 option off and
// joint mode replaced by bidir (what today's firmware runs and measures).
Params paper_part(const Params& p);

// The parameter sets of the trade-off table (docs/golden.md, "Trade-off"):
// the two presets and variants that add or remove one option at a time.
struct Variant {
    std::string name;
    std::string what;  // one line: what differs from the preset it derives from
    Params p;
};
const std::vector<Variant>& tradeoff_variants();

}  // namespace imap::golden
