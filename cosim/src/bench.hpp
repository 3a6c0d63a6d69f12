// The SystemC testbench of the RTL design (docs/rtl.md, "Testbench"):
//
//   bench            Bench
//   +- dut           the verilated design (one configuration, Model)
//   +- replay        optional second instance of a traced variant that re-runs
//                    a job to write the waves before a lockstep divergence
//
// The bench drives the clock (a clock process that a checker can hold
// while the reference model catches up), the reset, the straps (the cost
// table and the run-time configuration) and the host port that loads the
// program and the param block; it is the video line port (camera and
// display model) and the sink of the design's trace port: it keeps the CP
// state the retire records report and hands every retire record, with the
// backdoor into the design's state, to a Listener (the lockstep checker). It runs a queue of
// jobs (programs), so one elaboration can run many programs (the random
// suite).
#pragma once

#include <array>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <systemc>
#include <vector>

#include "imap/isa/config.hpp"
#include "imap/isa/machine.hpp"
#include "imap/isa/program.hpp"
#include "model.hpp"

namespace imap::rtl::detail {

using Image = isa::ImageVideoPort::Image;

// The design's retire record (imap_dpi_pkg::imap_rtl_retire, made by the
// retire monitor imap_cp_monitor.sv bound into the CP).
struct RetireRecord {
    uint64_t index = 0;
    uint32_t pc = 0;
    uint64_t word = 0;
    uint64_t cycle = 0, cycle_end = 0;  // machine cycle at issue / after the last cycle
    uint32_t phase = 0;
    int creg = -1;  // CP register written, -1 none
    uint32_t cval = 0;
    int msp = 0, csp = 0, active = 0;
    bool halted = false;
};

// The fault that stopped the design (imap_pkg::fault_t codes).
struct FaultRecord {
    bool valid = false;
    uint64_t index = 0;  // instructions retired before it (its execution index)
    int code = 0;
    uint32_t pc = 0;
    uint64_t cycle = 0;
    int64_t pe = -1;
    int64_t address = 0;
};
enum FaultCode {
    kFltNone,
    kFltIllegal,
    kFltPcEnd,
    kFltWatchdog,
    kFltMem,
    kFltMemX,
    kFltParam,
    kFltMaskOvf,
    kFltMaskUnf,
    kFltCallOvf,
    kFltCallUnf,
    kFltExtNone,
    kFltXferLen,
    kFltXferLocal,
    kFltXferExt,
    kFltVidPort,
    kFltVidLine,
    kFltVidMem
};
const char* fault_code_name(int code);

// A failing assertion of the design (imap_dpi_pkg::imap_rtl_assert, docs/rtl.md
// "Assertions"): the first of a job stops it. cycle, pc and index are the
// machine's at the failing edge (before it: the machine cycle in progress,
// the instruction in execute and its execution index).
struct AssertionRecord {
    bool valid = false;
    std::string name;
    int64_t pe = -1;  // -1: the CP, array-wide
    uint64_t cycle = 0, index = 0;
    uint32_t pc = 0;
};

// The CP state as reported by the trace port (retire records, param
// writes). The PE state (registers, flags, local and external memory) is not
// reported: the checker reads it from the design through the Backdoor.
struct Shadow {
    int P = 0, NR = 0;
    uint32_t mem_bytes = 0, ext_bytes = 0;
    std::array<uint32_t, 16> creg{};
    std::array<uint32_t, 256> param{};
    int msp = 0, csp = 0;
    uint32_t phase = 0;
    void reset(int P, int NR, uint32_t mem_bytes, uint32_t ext_bytes);
};

// What the trace port reported written by the instruction being retired.
struct Touched {
    bool param = false;
    void clear() { param = false; }
};

// The design's state through the backdoor, in the RtlState layout.
struct RtlStateData {
    int pes = 0, pe_regs = 0;
    std::vector<uint8_t> lanes, mem, ext;
    std::array<uint32_t, 16> creg{};
    std::array<uint32_t, 256> param{};
    int msp = 0, csp = 0;
    uint32_t phase = 0;
};
RtlStateData read_state(const Backdoor& b, int pe_regs);

class Listener {
  public:
    enum class Verdict { Go, Wait, Stop };
    virtual ~Listener() = default;
    // After the rising edge at which the instruction retired (the design's
    // state, readable through `bd`, is the one after it). Wait: the bench
    // holds the clock and asks again when wake_event() fires.
    virtual Verdict on_retire(const RetireRecord& r, const Shadow& s, const Backdoor& bd,
                              const Touched& t) = 0;
    virtual Verdict on_fault(const FaultRecord& f, const Shadow& s) = 0;
    virtual const sc_core::sc_event* wake_event() { return nullptr; }
};

// One program run.
struct Job {
    isa::MachineConfig cfg;  // cost table and run-time configuration (straps)
    const isa::Program* prog = nullptr;
    std::vector<std::pair<int, uint32_t>> params;
    Image input[2];
    Image output[2];                  // sized by the caller
    bool attached[2] = {true, true};  // video input ports present
    Listener* listener = nullptr;     // trace port on when set
    uint32_t mutant = 0;              // planted bug (mutation-check model)
    // waves of this run (traced models): a window of machine cycles
    std::string waves_path;
    std::vector<std::string> waves_scopes;  // dumpvars prefixes (empty = all)
    uint64_t waves_t0 = 0, waves_t1 = UINT64_MAX;
    uint64_t waves_limit_bytes = 0;  // stop tracing beyond this file size (0: no limit)
    // results
    bool halted = false, stopped = false;
    FaultRecord fault;
    AssertionRecord assertion;  // the first failing assertion (it stopped the job)
    uint64_t cycles = 0, instructions = 0, clocks = 0;
    std::string error;  // testbench-level failure (model stopped making progress, ...)
    double wall_s = 0;
    bool waves_written = false;
    bool waves_empty = false;    // the window held no cycle of the run: one sample at its end
    bool waves_limited = false;  // stopped at waves_limit_bytes
    uint64_t waves_open_ps = 0;  // time of the first dump (the waves' time axis: 0 = reset
                                 // released, the machine's cycle 0, as in the TLM's waves)
};

class Bench : public sc_core::sc_module {
  public:
    SC_HAS_PROCESS(Bench);
    // `dut`: the model of configuration `cfg`; `replay`: a traced instance of
    // the same configuration used by replay_waves() (nullptr: none). Built
    // by the caller at the top of the hierarchy (make_model), so that their
    // names ("dut", "replay") are the scopes of their waves.
    Bench(sc_core::sc_module_name name, const ConfigInfo& cfg, std::unique_ptr<Model> dut,
          std::unique_ptr<Model> replay, double clock_mhz);
    ~Bench() override;
    const char* kind() const override { return "imap::rtl::Bench"; }

    // Jobs run in order; next_job returns nullptr when there are no more (the
    // bench then stops the simulation). done is called after each job.
    std::function<Job*()> next_job;
    std::function<void(Job&)> job_done;

    const ConfigInfo& config() const { return cfg_; }
    Backdoor& backdoor() { return bd_; }
    Shadow& shadow() { return shadow_; }
    Model& model() { return *dut_; }
    bool has_replay() const { return replay_; }
    // Re-runs `job` on the replay model with waves in the job's window.
    // Called from the job_done callback (inside the simulation).
    void replay_waves(Job& job);

    // trace-port sink (dpi.cpp)
    void dpi_retire(const RetireRecord& r);
    void dpi_param(int addr, uint32_t v);
    void dpi_fault(const FaultRecord& f);
    void dpi_assert(const char* name, int pe);
    int dpi_vid_check(int dir_out, int port, int y);
    int dpi_vid_pixel(int port, int y, int x);
    uint64_t dpi_vid_ready(int port, int y, int x);
    void dpi_vid_put(int port, int y, int x, int v);

    uint64_t clocks() const { return clocks_; }
    double period_ps() const { return half_ps_ * 2.0; }

  private:
    struct Slot {
        std::unique_ptr<Model> model;
        std::unique_ptr<Ports> ports;
        Backdoor bd;
    };
    void control();
    void clock();
    void run_job(Slot& s, Job& j, bool replay);
    void drive_straps(Ports& p, const Job& j);
    void clear_state(Backdoor& b);
    bool process_pending();  // false: hold the clock
    void check_progress(Slot& s, Job& j);

    ConfigInfo cfg_;
    Slot main_, rep_;
    Slot* active_ = nullptr;
    Model* dut_ = nullptr;
    bool replay_ = false;
    Backdoor bd_;
    Shadow shadow_;
    Touched touched_;
    Job* job_ = nullptr;
    bool tracing_ = false;  // the trace port is on (a listener)
    bool pending_ = false;
    RetireRecord pending_rec_;
    bool pending_fault_ = false;
    FaultRecord fault_rec_;
    bool hold_ = false;
    bool stop_ = false;
    bool level_ = false;
    uint64_t half_ps_ = 12500;
    uint64_t clocks_ = 0;
    // the machine before the rising edge being evaluated (assertion reports)
    uint64_t pre_mcycle_ = 0, pre_instret_ = 0;
    uint32_t pre_pc_ = 0;
    uint64_t last_progress_ = 0, last_mcycle_ = 0, last_instret_ = 0;
    uint64_t cycle_budget_ = UINT64_MAX;
    bool waves_on_ = false;
    uint64_t run_start_ps_ = 0;  // simulation time at which the job's reset was released
    uint64_t dumps_ = 0;         // trace dumps of the job (the size limit is checked every 256)
    sc_core::sc_event clock_ev_, finished_ev_, processed_ev_;
};

}  // namespace imap::rtl::detail
