// The executor: PE array state kept as lanes (structure of arrays), the
// control processor, and a run loop that executes straight-line runs of
// decoded instructions (one indirect call each, statistics once per run).
// The lane handlers exist once per SIMD path (baseline x86-64, AVX2,
// AVX-512), chosen at run time by the CPU; every path gives the same state.
// Shared by the TLM model, the RTL model (as reference) and the tools; no
// SystemC here.
#pragma once

#include <array>
#include <cstddef>
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
    // Width in pixels of input image `port`, for the camera's line timing
    // (MachineConfig::camera_ready_cycle); -1 = unknown (a timed camera
    // then faults the vin).
    virtual int input_width(int /*port*/) const { return -1; }
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
    int input_width(int port) const override {
        return port == 0 || port == 1 ? input[port].width : -1;
    }
};

class Machine;

// The vector instruction set the lane handlers are compiled for. Every path
// computes exactly the same state (tests/isa/test_simd_paths.cpp runs each
// one this CPU supports against Generic); they differ only in speed.
enum class SimdPath : uint8_t {
    Generic,  // baseline x86-64 (SSE2), or the compiler's default elsewhere
    Avx2,     // x86-64 with AVX2
    Avx512,   // x86-64 with AVX-512 F/BW/VL
};
const char* to_string(SimdPath p);
// Paths this CPU can run, Generic first.
std::vector<SimdPath> supported_simd_paths();
// The path a new Machine uses: the environment variable IMAP_ISA_SIMD
// (generic, avx2, avx512; a path the CPU cannot run is refused with
// std::runtime_error) or else the widest supported one.
SimdPath default_simd_path();
// Parses a path name (as to_string); std::invalid_argument naming the choices.
SimdPath simd_path_from_string(const std::string& name);

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
// fn[0] honours the mask M, fn[1] is the same instruction for a machine
// whose PEs are all active (M = 1 everywhere: no blend).
struct Decoded;
using Handler = void (*)(Machine&, const Decoded&);
struct Decoded {
    Handler fn[2] = {nullptr, nullptr};
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
    // Events for the energy model (energy.hpp), counted as cheaply as the
    // executions: per opcode, the sum over its executions of the active PEs
    // (M = 1) when it started; the hops of rxl / rxr (sum of k); the bytes
    // xld / xst moved over the external path (len x active PEs).
    std::array<uint64_t, 256> op_lanes{};
    uint64_t ring_hops = 0;
    uint64_t ext_bytes = 0;
    // The counts above split by phase (index = Program::phases index; the
    // entries' own by_phase are empty): they add up to the totals. Empty
    // when the model that ran does not split them (the RTL's counters), or
    // when a program enters so many phases that the executor stopped
    // splitting (Machine::kMaxPhaseSplitEntries).
    std::vector<Stats> by_phase;
};

class Machine {
  public:
    // The executor keeps its counts by PC once per phase the program enters
    // (Stats::by_phase), up to this many entries in all (phases x program
    // size, 16 bytes each); a program that would need more keeps its totals
    // and gives no split.
    static constexpr size_t kMaxPhaseSplitEntries = size_t{1} << 22;

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

    // The SIMD path of the lane handlers (default_simd_path() at
    // construction); std::invalid_argument for one this CPU cannot run.
    void set_simd_path(SimdPath p);
    SimdPath simd_path() const { return simd_; }

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
    // A snapshot of the statistics, refreshed by every call (the run loop
    // keeps per-run counters; this call adds them up, O(program size)).
    const Stats& stats() const;
    // Cycles per phase id (index = Program::phases index).
    const std::vector<uint64_t>& phase_cycles() const { return phase_cycles_; }
    uint32_t current_phase() const { return phase_; }

    // ---- PE lanes (P bytes each, PE p at index p; flags and mask are 0/1) ----
    // Writable for testbenches and debuggers between run() / step() calls;
    // values other than 0/1 in C, T or M are not allowed, and host writes to
    // M are not seen by active_pes(). The rows of different registers are not
    // adjacent (each row is padded to a multiple of 64 bytes).
    const uint8_t* reg_lanes(int r) const { return lanes_ + lane_off(r); }
    uint8_t* reg_lanes(int r) { return lanes_ + lane_off(r); }
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
    uint8_t* mem_data() { return mem_; }
    const uint8_t* mem_data() const { return mem_; }
    // The machine clears on reset() only the external memory it knows was
    // written (xst, ext_write); once a writable pointer has been handed out
    // here it clears all of it on every reset.
    uint8_t* ext_data() {
        ext_all_dirty_ = true;
        return ext_;
    }
    const uint8_t* ext_data() const { return ext_; }
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

    // The straight-line run that starts at a PC: up to and including the
    // next instruction that ends a run (control flow, phase, mask, xld / xst,
    // video, the end sentinel). Only that last instruction can change the
    // PC flow, the phase, the mask or add variable cycles.
    struct RunInfo {
        uint32_t end = 0;        // PC of the last instruction
        uint32_t len = 0;        // instructions
        uint64_t pe_cycles = 0;  // fixed cycles of its PE-work instructions
    };
    // A zero-initialised heap block (calloc: untouched pages stay unmapped).
    struct Block {
        uint8_t* p = nullptr;
        Block() = default;
        Block(const Block&) = delete;
        Block& operator=(const Block&) = delete;
        ~Block();
        uint8_t* alloc(size_t n, size_t align);
    };

    size_t lane_off(int r) const;
    template <bool Traced>
    RunResult run_loop(uint64_t max_cycles);
    template <bool Traced>
    void exec_one();
    void exec_run(uint32_t start, uint64_t limit);
    void book_partial_run(uint32_t start, uint32_t stop, uint64_t start_cycles, uint64_t active,
                          uint32_t phase);
    // The running totals the handlers keep, for the split by phase.
    struct Running {
        uint64_t instructions = 0, pe_cycles = 0, active_lane_cycles = 0, ext_bytes = 0;
        std::array<uint64_t, kCostClassCount> class_extra{};
    };
    Running running() const;
    // A `phase` marker left phase `old` for phase_: the running totals since
    // the last change go to `old`, the counts by PC to phase_'s row. O(1).
    void change_phase(uint32_t old);
    void select_phase_row();  // exec_diff_ / lane_diff_ = phase_'s row
    // Adds the counts of difference-array row `r` to `s` (O(program size)).
    void add_row(Stats& s, size_t r) const;
    [[noreturn]] void fault(const std::string& msg, int64_t pe = Fault::kNone,
                            int64_t address = Fault::kNone) const;
    void recount_active();
    void refresh_full();
    void bind_handlers();
    void note_ext_write(size_t lo, size_t hi) {
        if (lo < ext_lo_) ext_lo_ = lo;
        if (hi > ext_hi_) ext_hi_ = hi;
    }

    MachineConfig cfg_;
    int P_;
    size_t S_;  // lane row stride: P rounded up to a multiple of 64
    size_t NR_;
    Block lane_block_, mem_block_, ext_block_;
    uint8_t* lanes_ = nullptr;  // regs | C | T | M | mask stack | pidx | zero | scratch | lane_no
    uint8_t *c_, *t_, *m_, *mstack_, *pidx_, *zero_, *scratch_;
    uint32_t* lane_no_;                      // lane_no_[p] = p
    uint8_t* mem_ = nullptr;                 // mem_bytes * P (+ 64 bytes of slack for row loads)
    uint8_t* ext_ = nullptr;                 // ext_bytes * P
    size_t ext_lo_ = SIZE_MAX, ext_hi_ = 0;  // bytes of ext_ written since the last reset
    bool ext_all_dirty_ = false;
    int msp_ = 0;
    int active_ = 0;
    bool full_ = true;  // M = 1 on every PE (fn[1] may be used)
    SimdPath simd_ = SimdPath::Generic;

    std::array<uint32_t, kCpRegs + 1> creg_{};  // [16] is always 0 (absolute addresses)
    std::array<uint32_t, kParamWords> params_{};
    std::vector<uint32_t> cstack_;
    int csp_ = 0;

    Program prog_;
    std::vector<Decoded> code_;  // + a sentinel that faults when the PC runs off the end
    std::vector<RunInfo> runs_;  // by start PC (code_.size() entries)
    uint32_t pc_ = 0, next_pc_ = 0;
    uint64_t extra_ = 0;
    bool halted_ = false;
    uint64_t cycles_ = 0;
    uint32_t phase_ = 0;
    std::vector<uint64_t> phase_cycles_;

    // Statistics as the run loop keeps them: executions by PC as a
    // difference array (a run from s to e adds 1 at s, -1 at e + 1; the
    // active PE count likewise in lane_diff_), one row per phase entered
    // (exec_diff_ / lane_diff_ point at the current phase's), the
    // variable cycles by cost class, and the running totals.
    std::vector<std::vector<int64_t>> exec_rows_;
    std::vector<std::vector<uint64_t>> lane_rows_;  // active PEs by PC (mod 2^64)
    std::vector<int32_t> row_of_phase_;             // -1: not entered since load
    bool phase_split_ = true;  // false: a phase shares row 0 (over kMaxPhaseSplitEntries)
    int64_t* exec_diff_ = nullptr;
    uint64_t* lane_diff_ = nullptr;
    uint64_t ext_bytes_ = 0;
    std::array<uint64_t, kCostClassCount> class_extra_{};
    uint64_t instructions_ = 0, pe_cycles_ = 0, active_lane_cycles_ = 0;
    std::vector<Running> phase_running_;  // each phase's share of the running totals
    Running phase_mark_;                  // running() at the last phase change
    mutable Stats stats_;

    VideoPort* video_ = nullptr;
    Observer* observer_ = nullptr;
    RingPort* ring_ = nullptr;
    StatusPort* status_ = nullptr;
};

}  // namespace imap::isa
