// Host side of the DP firmware: the per-PE memory plan for a parameter set,
// the range checks that make 24-bit costs exact, and assembly of the
// firmware with the plan's constants (docs/firmware.md).
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "imap/golden/params.hpp"
#include "imap/golden/stereo.hpp"
#include "imap/isa/config.hpp"
#include "imap/isa/program.hpp"

namespace imap::firmware {

// A parameter set the firmware cannot run (range or memory); the message
// says what is needed and what is available.
class FirmwareError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

inline constexpr int64_t kInf = int64_t{1} << 23;  // unreachable cost

// Memory plan of the forward pass for one scanline length N.
struct ForwardPlan {
    int N = 0, D = 0;
    bool bidir = false;
    int s = 0;     // seed column (bidir)
    int ds = -1;   // seed disparity, -1 = free
    int kmax = 0;  // columns computed after the start column
    int dq = 0;    // packed pointer bytes per column = ceil(D / 4)
    int imgr = 0, imgl = 0, c0 = 0, c1 = 0, c2 = 0, pbuf = 0;  // local addresses
    int vbuf = 0, kbase = 0;
    int map = 0;             // output line: reuses the line buffers after the forward pass
    int mem_needed = 0;      // bytes of local memory per PE
    int64_t ext_needed = 0;  // bytes of external memory per PE
};

// Checks the cost range (24-bit exactness) and plans the memory; throws
// FirmwareError when the set does not fit `cfg`.
ForwardPlan plan_forward(const golden::Params& p, int N, const isa::MachineConfig& cfg);

// Folder of the firmware sources.
std::string firmware_dir();

// Assembles the stand-alone forward-pass program for a plan.
isa::Program assemble_forward(const golden::Params& p, const ForwardPlan& plan);

// Assembles `file` (in firmware_dir()) with the plan's constants, the
// algorithm's (FRAME, VOTE) and `extra` (e.g. HROI, HB).
isa::Program assemble(const golden::Params& p, const ForwardPlan& plan, const std::string& file,
                      const std::map<std::string, int64_t>& extra);

// One batch of ROI lines processed together (lines first .. first+lines-1,
// of which out_count starting at batch line out_first are written out).
struct Batch {
    int first = 0, lines = 0, out_first = 0, out_count = 0;
};

// Everything the full firmware (dp.s) needs for one frame.
struct FramePlan {
    ForwardPlan f;
    golden::Roi roi;
    int P = 0;
    int lpb = 0;                    // lines per batch (P/2 bidir, P single)
    int hbmax = 0;                  // most lines in one batch
    int nseg = 0;                   // segments of P pixels per ROI line
    int inl = 0, inr = 0, out = 0;  // video rows (local addresses)
    bool split_in = false;          // input re-layout one image at a time (memory)
    std::vector<Batch> batches;
    int mem_needed = 0;      // local bytes per PE
    int64_t ext_needed = 0;  // external bytes per PE
};

inline constexpr int kMaxBatches = 62;  // batch table in the param block

// Plans a frame: the forward plan, batches (overlapping by one line at inner
// edges when the vote is on), video rows, memory. FirmwareError when the
// set cannot run on `cfg` (what is needed vs available).
FramePlan plan_frame(const golden::Params& p, const golden::Roi& roi,
                     const isa::MachineConfig& cfg);

// The source file of the full firmware (dp.s in firmware_dir()).
std::string frame_source();

// The constants (NAME -> value, given to the assembler as -D NAME=VALUE)
// with which assemble_frame assembles frame_source() for a plan: what a
// user needs to re-assemble the firmware by hand (imapsim run
// --emit-defines, docs/firmware.md).
std::map<std::string, int64_t> frame_defines(const golden::Params& p, const FramePlan& plan);

// Assembles frame_source() with frame_defines(p, plan).
isa::Program assemble_frame(const golden::Params& p, const FramePlan& plan);

// The param block words of a frame plan (index, value): set before the run
// (imapsim exec --param INDEX=VALUE).
std::vector<std::pair<int, uint32_t>> param_block(const FramePlan& plan);

// Registers that the firmware uses together as one multi-byte value (a
// cost), low byte first: the waves' GTKWave view shows each group as one
// decimal vector (docs/waves.md). `phase` names the phase where the group
// holds that value (the registers are reused elsewhere).
struct WaveGroup {
    std::string name;       // e.g. "fwd_run"
    std::string phase;      // e.g. "forward"
    std::vector<int> regs;  // PE registers, low byte first
};
const std::vector<WaveGroup>& wave_groups();

}  // namespace imap::firmware
