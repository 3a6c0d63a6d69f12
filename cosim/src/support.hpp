// Pieces shared by run_rtl, run_lockstep and the random suite.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "bench.hpp"
#include "imap/rtl/config.hpp"
#include "imap/rtl/lockstep.hpp"
#include "imap/rtl/system.hpp"

namespace imap::rtl::detail {

// The configuration variant for cfg (fast, traced by the waves' extension,
// or the mutation-check model); isa::ConfigError when not built.
const ConfigInfo& pick_config(const isa::MachineConfig& cfg, const RtlConfig& rcfg);
// The traced variant (1 VCD, 2 FST) of cfg's configuration (of the
// mutation-check model with `mutants`), or nullptr.
const ConfigInfo* traced_config(const isa::MachineConfig& cfg, int format, bool mutants = false);
void fill_job(Job& j, const isa::MachineConfig& cfg, const isa::Program& prog,
              const std::vector<std::pair<int, uint32_t>>& params, const Image& left,
              const Image& right, int out_w, int out_h);
// The run's result from the job and the design's counters and state.
RtlRunResult collect(const Job& j, const Bench& b, const isa::MachineConfig& cfg,
                     const isa::Program& prog);
// The report of a failing assertion in the lockstep's form (a Divergence
// with `assertion` set; disassembly from prog).
Divergence assertion_divergence(const AssertionRecord& a, const isa::Program& prog);
// XOR a fault into the design's state (backdoor).
void inject(Backdoor& bd, const FaultInjection& f);
// After the wave writer closed: make the file reproducible (the FST
// header's date is cleared). Throws std::runtime_error on an I/O error.
void finish_waves_file(const std::string& path);
// finish_waves_file and the GTKWave view next to the waves.
void finish_waves(const Job& j, const Bench& b, const isa::MachineConfig& cfg,
                  const std::string& top, const std::vector<int>& pes);

}  // namespace imap::rtl::detail
