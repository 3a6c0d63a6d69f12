// The executor: PE array state kept as lanes (structure of arrays), the
// control processor, and a run loop that makes one indirect call per
// instruction. Shared by the TLM model, the RTL model (as reference) and the
// tools; no SystemC here.
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

#include "imap/isa/config.hpp"
#include "imap/isa/encoding.hpp"
#include "imap/isa/interconnect.hpp"
#include "imap/isa/opcodes.hpp"
#include "imap/isa/program.hpp"

namespace imap::isa {

// A run-time fault of the modeled machine (bad address, stack error,
// runaway program, ...). State is left as it was before the faulting
// instruction (except for the watchdog, which fires between instructions).
class Fault : public std::runtime_error {
  public:
    static constexpr int64_t kNone = -1;  // pe / address not applicable
    Fault(const std::string& what, uint32_t pc, int64_t pe, int64_t address, uint64_t cycle)
        : std::runtime_error(what), pc_(pc), pe_(pe), address_(address), cycle_(cycle) {}
    uint32_t pc() const { return pc_; }
    int64_t pe() const { return pe_; }            // kNone when all PEs / not a PE fault
    int64_t address() const { return address_; }  // kNone when not an address fault
    uint64_t cycle() const { return cycle_; }

  private:
    uint32_t pc_;
    int64_t pe_, address_;
    uint64_t cycle_;
};

// A program that cannot be loaded on this configuration (unknown opcode,
// register out of range, branch outside the program, ...). Names the PC.
class LoadError : public std::runtime_error {
  public:
    LoadError(const std::string& what, uint32_t pc) : std::runtime_error(what), pc_(pc) {}
    uint32_t pc() const { return pc_; }

  private:
    uint32_t pc_;
};

// Video line I/O, implemented by the host / testbench. `n` is the PE count.
// Implementations may throw std::exception (e.g. for a line outside the
// image); the machine reports it as a Fault naming the PC.
class VideoPort {
  public:
    virtual ~VideoPort() = default;
    // dst[i] = pixel (x0 + i, y) of input image `port` (0 = left, 1 = right);
    // pixels outside the image width read as 0.
    virtual void read_line(int port, int y, int x0, uint8_t* dst, int n) = 0;
    // Pixel (x0 + i, y) of output image `port` = src[i]; pixels outside the
    // image width are ignored.
    virtual void write_line(int port, int y, int x0, const uint8_t* src, int n) = 0;

    // Optional row-level path, for a port that reaches the PE memories itself
    // (the TLM model moves the line through the array's DMI pointer). `addr`
    // is the local-memory row of the vin / vout (already range-checked); the
    // row is the n bytes at mem_data() + addr * n. Return true when the port
    // moved the line; it must then leave memory (vin) or the output image
    // (vout) unchanged when it throws. The defaults return false and the
    // machine uses read_line / write_line with its own row copy.
    virtual bool read_row(int /*port*/, int /*y*/, int /*x0*/, uint32_t /*addr*/, int /*n*/) {
        return false;
    }
    virtual bool write_row(int /*port*/, int /*y*/, int /*x0*/, uint32_t /*addr*/, int /*n*/) {
        return false;
    }
};

// A VideoPort over in-memory 8-bit images (tests and tools).
class ImageVideoPort : public VideoPort {
  public:
    struct Image {
        int width = 0, height = 0;
        std::vector<uint8_t> pixels;  // row-major, width * height
    };
    Image input[2];
    Image output[2];
    // Allocates output image `port` (zero-filled).
    void make_output(int port, int width, int height);
    void read_line(int port, int y, int x0, uint8_t* dst, int n) override;
    void write_line(int port, int y, int x0, const uint8_t* src, int n) override;
};

class Machine;

// Called after every instruction when attached (VCD, lockstep, profiling).
struct TraceEvent {
    uint32_t pc;            // PC of the instruction just executed
    uint64_t word;          // its encoding
    uint64_t cycle_before;  // cycle counter before / after it
    uint64_t cycle_after;
};
class Observer {
  public:
    virtual ~Observer() = default;
    virtual void on_instruction(const Machine& m, const TraceEvent& e) = 0;
};

struct StepResult {
    bool halted = false;
    uint32_t pc = 0;      // PC after the step
    uint64_t cycles = 0;  // cycles the instruction took
};

enum class RunStatus { Halted, CycleLimit };
struct RunResult {
    RunStatus status = RunStatus::Halted;
    uint64_t cycles = 0;        // total cycle counter after the run
    uint64_t instructions = 0;  // total executed instructions
};

// A decoded instruction: built once at load, executed by one indirect call.
struct Decoded;
using Handler = void (*)(Machine&, const Decoded&);
struct Decoded {
    Handler fn = nullptr;
    uint64_t cost = 0;             // fixed cycles (variable parts are added by the handler)
    uint32_t d = 0, a = 0, b = 0;  // lane offsets of PE registers, or CP register numbers
    int32_t imm = 0;
    uint32_t aux = 0;  // format-specific (ldx CP register, video cY/cX, ...)
    uint8_t op = 0;
    uint8_t cls = 0;  // CostClass
    uint8_t flags = 0;
};

// Cycle statistics beyond the total.
struct Stats {
    uint64_t instructions = 0;
    std::array<uint64_t, kCostClassCount> class_cycles{};  // by CostClass
    std::array<uint64_t, 256> op_counts{};                 // executions by opcode
    uint64_t pe_cycles = 0;           // cycles of ALU / memory / ring instructions
    uint64_t active_lane_cycles = 0;  // sum over them of cycles x active PEs
};

class Machine {
  public:
    // Validates the configuration (ConfigError) and allocates the state.
    explicit Machine(const MachineConfig& cfg);
    Machine(const Machine&) = delete;
    Machine& operator=(const Machine&) = delete;

    const MachineConfig& config() const { return cfg_; }
    int pes() const { return P_; }

    // Decodes the program (LoadError naming the PC) and resets the machine.
    void load(const Program& p);
    const Program& program() const { return prog_; }
    // Clears PE registers, flags, memories, CP registers, stacks, counters;
    // M = 1 everywhere, PC = 0. Keeps the program and the param block.
    void reset();

    void set_video(VideoPort* v) { video_ = v; }
    // Optional components for the shift ring and the status reduction
    // (interconnect.hpp); nullptr (the default) = the built-in code. Same
    // semantics either way; one virtual call per rxl / rxr / rany / rall.
    void set_ring(RingPort* r) { ring_ = r; }
    void set_status(StatusPort* s) { status_ = s; }
    RingPort* ring() const { return ring_; }
    StatusPort* status() const { return status_; }
    // Attach / detach (nullptr) an observer. Costs nothing when detached.
    void set_observer(Observer* o) { observer_ = o; }

    // Executes one instruction (Fault on error). Does nothing once halted.
    StepResult step();
    // Runs until halt, or until the cycle counter reaches max_cycles
    // (RunStatus::CycleLimit). Exceeding config().watchdog_cycles is a Fault.
    RunResult run(uint64_t max_cycles = UINT64_MAX);

    bool halted() const { return halted_; }
    uint32_t pc() const { return pc_; }
    uint64_t cycles() const { return cycles_; }
    const Stats& stats() const { return stats_; }
    // Cycles per phase id (index = Program::phases index).
    const std::vector<uint64_t>& phase_cycles() const { return phase_cycles_; }
    uint32_t current_phase() const { return phase_; }

    // ---- PE lanes (P bytes each, PE p at index p; flags and mask are 0/1) ----
    // Writable for testbenches and debuggers; values other than 0/1 in C, T or
    // M are not allowed, and host writes to M are not seen by active_pes().
    const uint8_t* reg_lanes(int r) const { return lanes_.data() + lane_off(r); }
    uint8_t* reg_lanes(int r) { return lanes_.data() + lane_off(r); }
    const uint8_t* carry_lanes() const { return c_; }
    const uint8_t* test_lanes() const { return t_; }
    const uint8_t* mask_lanes() const { return m_; }
    uint8_t* carry_lanes() { return c_; }
    uint8_t* test_lanes() { return t_; }
    uint8_t* mask_lanes() { return m_; }
    int mask_stack_size() const { return msp_; }
    const uint8_t* mask_stack_lanes(int level) const;  // level < mask_stack_size()
    int active_pes() const { return active_; }

    uint8_t reg(int pe, int r) const;
    void set_reg(int pe, int r, uint8_t v);

    // ---- memories: address-major, byte (pe, addr) at [addr * P + pe] ----
    uint8_t* mem_data() { return mem_.data(); }
    const uint8_t* mem_data() const { return mem_.data(); }
    uint8_t* ext_data() { return ext_.data(); }
    const uint8_t* ext_data() const { return ext_.data(); }
    uint8_t mem_read(int pe, uint32_t addr) const;  // std::out_of_range on bad pe/addr
    void mem_write(int pe, uint32_t addr, uint8_t v);
    uint8_t ext_read(int pe, uint32_t addr) const;
    void ext_write(int pe, uint32_t addr, uint8_t v);

    // ---- control processor ----
    uint32_t cp(int i) const;
    void set_cp(int i, uint32_t v);
    uint32_t param(int i) const;
    void set_param(int i, uint32_t v);
    const std::array<uint32_t, kParamWords>& params() const { return params_; }
    int call_stack_size() const { return csp_; }

  private:
    friend struct Exec;

    size_t lane_off(int r) const;
    template <bool Traced>
    RunResult run_loop(uint64_t max_cycles);
    template <bool Traced>
    void exec_one();
    [[noreturn]] void fault(const std::string& msg, int64_t pe = Fault::kNone,
                            int64_t address = Fault::kNone) const;
    void recount_active();

    MachineConfig cfg_;
    int P_;
    size_t NR_;
    std::vector<uint8_t> lanes_;  // regs | C | T | M | mask stack | pidx bytes | scratch
    uint8_t *c_, *t_, *m_, *mstack_, *pidx_, *scratch_;
    std::vector<uint8_t> mem_, ext_;
    int msp_ = 0;
    int active_ = 0;

    std::array<uint32_t, kCpRegs + 1> creg_{};  // [16] is always 0 (absolute addresses)
    std::array<uint32_t, kParamWords> params_{};
    std::vector<uint32_t> cstack_;
    int csp_ = 0;

    Program prog_;
    std::vector<Decoded> code_;  // + a sentinel that faults when the PC runs off the end
    uint32_t pc_ = 0, next_pc_ = 0;
    uint64_t extra_ = 0;
    bool halted_ = false;
    uint64_t cycles_ = 0;
    uint32_t phase_ = 0;
    std::vector<uint64_t> phase_cycles_;
    Stats stats_;

    VideoPort* video_ = nullptr;
    Observer* observer_ = nullptr;
    RingPort* ring_ = nullptr;
    StatusPort* status_ = nullptr;
};

}  // namespace imap::isa
