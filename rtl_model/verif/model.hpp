// The testbench's view of one verilated configuration of the design
// (its testbench top rtl_model/verif/imap_tb.sv around the chip
// rtl_model/hdl/imap_top.sv): the SystemC signals bound to its ports, the
// backdoor pointers into its state elements (from Verilator's scope table;
// simulation only: final-state readout, clearing memories between programs,
// fault injection) and the Verilator wave writer of a traced variant.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <string>
#include <systemc>
#include <vector>

namespace imap::rtl::detail {

// The signals of imap_tb's ports (Verilator --sc types: 1 bit bool, up to
// 32 bits uint32_t, up to 64 bits uint64_t).
struct Ports : sc_core::sc_module {
    explicit Ports(sc_core::sc_module_name n) : sc_core::sc_module(n) {}
    sc_core::sc_signal<bool> clk{"clk"};
    sc_core::sc_signal<bool> rst_n{"rst_n"};
    sc_core::sc_signal<bool> host_we{"host_we"}, host_sel{"host_sel"};
    sc_core::sc_signal<uint32_t> host_addr{"host_addr"};
    sc_core::sc_signal<uint64_t> host_data{"host_data"};
    sc_core::sc_signal<uint32_t> c_alu{"c_alu"}, c_mem{"c_mem"},
        c_indirect_extra{"c_indirect_extra"}, c_ring_hop{"c_ring_hop"}, c_mask{"c_mask"},
        c_status{"c_status"}, c_cp{"c_cp"}, c_branch_taken{"c_branch_taken"},
        c_video_line{"c_video_line"}, c_xfer_setup{"c_xfer_setup"}, c_ext_bpc{"c_ext_bpc"},
        c_ext_beat{"c_ext_beat"}, c_shift_bits{"c_shift_bits"}, c_minmax_extra{"c_minmax_extra"};
    sc_core::sc_signal<uint32_t> cfg_prog_len{"cfg_prog_len"}, cfg_pe_regs{"cfg_pe_regs"},
        cfg_mask_depth{"cfg_mask_depth"}, cfg_call_depth{"cfg_call_depth"};
    sc_core::sc_signal<bool> cfg_indirect{"cfg_indirect"}, cfg_ext_on{"cfg_ext_on"},
        cfg_trace{"cfg_trace"};
    sc_core::sc_signal<uint64_t> cfg_watchdog{"cfg_watchdog"};
    sc_core::sc_signal<uint32_t> mutant{"mutant"};  // mutation-check model only
    sc_core::sc_signal<bool> done{"done"};
};

// The sizes fixed in the HDL of every configuration (imap_top parameters).
inline constexpr int kHdlRegs = 16;
inline constexpr int kHdlMaskDepth = 8;
inline constexpr int kHdlCallDepth = 16;
inline constexpr uint32_t kHdlImemWords = 65536;
inline constexpr int kHdlXrows = 8;
inline constexpr int kHdlPhases = 256;

// Raw pointers into the model's state (layouts as Verilator stores them).
struct Backdoor {
    int P = 0;
    uint32_t mem_bytes = 0, ext_bytes = 0;
    int nregs = 0, phases = 0;
    std::vector<uint8_t*> regs;  // per PE: nregs bytes
    // One PE's local memory: kHdlXrows banks, byte a in bank a % kHdlXrows at
    // index a / kHdlXrows (imap_pe.sv, bank0 .. bank7).
    struct PeMem {
        std::array<uint8_t*, kHdlXrows> bank{};
        size_t bank_bytes = 0;
        uint8_t& operator[](uint32_t a) const { return bank[a % kHdlXrows][a / kHdlXrows]; }
    };
    std::vector<PeMem> mem;       // per PE: mem_bytes bytes
    std::vector<uint8_t*> carry;  // per PE: C
    std::vector<uint8_t*> st;     // per PE: {oob, T, M}
    std::vector<void*> mstk;      // per PE: the mask stack (width: mstk_bytes)
    int mstk_bytes = 1;
    uint8_t* ext = nullptr;  // address-major: byte (pe, a) at a * P + pe
    uint32_t* creg = nullptr;
    uint32_t* param = nullptr;
    uint16_t* csp = nullptr;
    uint16_t* msp = nullptr;
    uint16_t* phase = nullptr;
    uint64_t* instret = nullptr;
    uint64_t* mcycle = nullptr;
    uint32_t* x_pc = nullptr;  // PC of the instruction in execute
    uint8_t* halted = nullptr;
    uint8_t* faulted = nullptr;
    uint8_t* f_code = nullptr;
    uint32_t* f_pc = nullptr;
    uint64_t* f_cyc = nullptr;
    uint32_t* f_pe = nullptr;
    uint64_t* f_addr = nullptr;
    uint64_t* kind_cyc = nullptr;  // 12
    uint64_t* op_cnt = nullptr;    // 256
    uint64_t* phase_cyc = nullptr;
    uint64_t* pe_cyc = nullptr;
    uint64_t* active_cyc = nullptr;
};

enum class TraceFormat { None = 0, Vcd = 1, Fst = 2 };

class Model {
  public:
    virtual ~Model() = default;
    virtual sc_core::sc_module& module() = 0;
    virtual void bind(Ports& p) = 0;
    virtual TraceFormat trace_format() const = 0;
    virtual bool mutants() const = 0;
    // Resolves the backdoor (after construction; throws std::runtime_error
    // naming a missing state element).
    virtual Backdoor backdoor() = 0;
    // Waves (traced variants only): scopes as Verilator's dumpvars (empty =
    // everything), then dump(time in resolution units) per dump point.
    virtual void trace_open(const std::string& path, const std::vector<std::string>& scopes) = 0;
    virtual void trace_dump(uint64_t t) = 0;
    virtual void trace_close() = 0;
};

// One verilated configuration of this build (rtl_configs.cpp, generated).
struct ConfigInfo {
    const char* name;  // "p256_m1024_x65536"
    int pes;
    uint32_t mem_bytes, ext_bytes;
    int trace;    // TraceFormat
    int mutants;  // planted bugs selectable (mutation check)
    Model* (*make)(const char* name);
};
const std::vector<ConfigInfo>& built_configs();
// The build these configurations come from (for the message that says how
// to add one).
const char* build_source_dir();
const char* build_binary_dir();
const char* build_extra_configs();
const char* build_trace_configs();
bool build_fst_all();  // IMAP_RTL_FST_ALL: every configuration FST-traced

}  // namespace imap::rtl::detail
