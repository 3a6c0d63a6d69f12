#include "imap/rtl/config.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <filesystem>
#include <set>
#include <string>

#include <iostream>

#include "model.hpp"
#include "rtl_cache_impl.hpp"

namespace imap::rtl {

namespace {
bool parse_u64(const std::string& s, uint64_t& v) {
    if (s.empty()) return false;
    char* end = nullptr;
    const bool hex = s.size() > 2 && s[0] == '0' && (s[1] == 'x' || s[1] == 'X');
    if (s[0] == '-' || s[0] == '+') return false;
    v = std::strtoull(s.c_str(), &end, hex ? 16 : 10);
    return end && *end == '\0';
}

std::string spec_of(const isa::MachineConfig& cfg) {
    return std::to_string(cfg.pes) + ":" + std::to_string(cfg.mem_bytes) + ":" +
           std::to_string(cfg.ext_bytes);
}
}  // namespace

std::string reg_name(int reg) {
    switch (reg) {
        case FaultInjection::kRegC:
            return "C";
        case FaultInjection::kRegT:
            return "T";
        case FaultInjection::kRegM:
            return "M";
        default:
            return "r" + std::to_string(reg);
    }
}

FaultInjection parse_fault_injection(const std::string& spec) {
    auto bad = [&](const std::string& why) {
        return isa::ConfigError("invalid fault injection '" + spec +
                                "': expected INSTR:PE:REG:MASK (e.g. 120:3:r5:0x10; REG = rN, N, "
                                "c, t or m; MASK 1..255): " +
                                why);
    };
    std::string parts[4];
    size_t start = 0;
    for (int i = 0; i < 4; ++i) {
        const size_t colon = spec.find(':', start);
        if ((i < 3) != (colon != std::string::npos)) throw bad("need exactly four fields");
        parts[i] = spec.substr(start, i < 3 ? colon - start : std::string::npos);
        start = colon + 1;
    }
    FaultInjection f;
    f.enabled = true;
    uint64_t v = 0;
    if (!parse_u64(parts[0], v)) throw bad("INSTR '" + parts[0] + "' is not a number");
    f.instruction = v;
    if (!parse_u64(parts[1], v) || v > 65536) throw bad("PE '" + parts[1] + "' is not a PE index");
    f.pe = static_cast<int>(v);
    std::string r = parts[2];
    for (char& ch : r) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
    if (r == "c")
        f.reg = FaultInjection::kRegC;
    else if (r == "t")
        f.reg = FaultInjection::kRegT;
    else if (r == "m")
        f.reg = FaultInjection::kRegM;
    else {
        if (!r.empty() && r[0] == 'r') r = r.substr(1);
        if (!parse_u64(r, v) || v >= 64) throw bad("REG '" + parts[2] + "' is not a register");
        f.reg = static_cast<int>(v);
    }
    if (!parse_u64(parts[3], v) || v == 0 || v > 255)
        throw bad("MASK '" + parts[3] + "' is not in 1..255");
    f.mask = static_cast<uint8_t>(v);
    return f;
}

const std::vector<Mutant>& mutants() {
    // ids as imap_pkg::MUT_* (rtl_model/hdl/imap_pkg.sv)
    static const std::vector<Mutant> m = {
        {1, "adc_carry", "adc / adci: the carry out ignores the carry in"},
        {2, "sub_mask", "sub: written back on masked PEs too (mask gating of one opcode)"},
        {3, "ring_wrap", "rxr: PE P-1 receives 0 instead of PE 0's value (one wrap-around)"},
        {4, "xfer_len", "xld: one row (byte per PE) less than the length (off by one)"},
        {5, "stale_fwd",
         "PE preload: the ring source / per-PE address ignore the register written at the same "
         "edge (stale forwarded register)"},
        {6, "cp_fwd",
         "decode: cB of ld / st read without forwarding from execute (stale CP register)"},
        {7, "shr_carry", "shri / shrv: C is the bit above the last one shifted out"},
        {8, "rall_mask", "rall: the AND includes the masked PEs"},
        {9, "mif_depth", "mif: the mask stack overflows one level late"},
        {10, "loop_bubble", "loop: a taken loop pays no refill bubble"},
        {11, "melse_top", "melse: uses M instead of the saved mask (forgets the enclosing mif)"},
        {12, "xst_last_row", "xst: the last row of a transfer is not written"},
        {13, "xld_mask", "xld: rows written on masked PEs too (ignores the mask)"},
        {14, "xfer_all_pes", "xld / xst: the cost counts every PE, not the active ones"},
        {15, "xst_mask", "xst: the external memory of masked PEs written too"},
        {16, "bank_bypass",
         "PE memory: a byte written at a row read's edge reads as the bank's old byte (the "
         "banks' bypass off)"},
    };
    return m;
}

const std::vector<Assertion>& assertions() {
    // as labelled in rtl_model/hdl (imap_assert.svh, docs/rtl.md "Assertions")
    static const std::vector<Assertion> a = {
        {"a_pe_masked_wb", "imap_pe", "a masked PE writes no register and no memory byte back"},
        {"a_pe_masked_row", "imap_pe", "xld writes its rows on the active PEs only"},
        {"a_pe_mask_nest", "imap_pe",
         "after mif / melse a PE is active only if it was active where the block opened"},
        {"a_pe_preload", "imap_pe",
         "a preload (ring source, per-PE address, the ld / ldx / vout / xst row) sees the "
         "registers and memory as the same edge leaves them (write-back and memory bypass)"},
        {"a_pe_mem_write", "imap_pe",
         "the local memory's one write port: a st / stx byte or rows per edge, never both, "
         "and inside the memory"},
        {"a_ring_rotate", "imap_array",
         "after a ring hop every PE holds its neighbour's previous ring value (the ring wraps)"},
        {"a_maskbus_status", "imap_array", "rany / rall reduce T over exactly the active PEs"},
        {"a_maskbus_memx", "imap_array",
         "the ldx / stx address check names an active PE out of range, exactly when one exists"},
        {"a_cw_legal", "imap_cp",
         "the control word of an instruction cycle is a legal one (function, mask command, "
         "register writes, shifter / ring steps)"},
        {"a_cw_row_legal", "imap_cp", "a row-bus operation names 1..XROWS rows"},
        {"a_mask_ovf", "imap_cp", "mif commits only below the configured mask-stack depth"},
        {"a_mask_unf", "imap_cp", "melse / mend commit only on a non-empty mask stack"},
        {"a_call_ovf", "imap_cp", "call commits only below the configured return-stack depth"},
        {"a_call_unf", "imap_cp", "ret commits only on a non-empty return stack"},
        {"a_stack_depth", "imap_cp",
         "the mask / return stack depths stay within the configuration"},
        {"a_cp_operands", "imap_cp",
         "the CP operands taken in decode (cA, cB, cB + off) equal the register file once the "
         "instructions before have committed (forwarding)"},
        {"a_cp_refill", "imap_cp",
         "a taken branch is followed by branch_taken refill bubbles before the next instruction "
         "executes"},
        {"a_cp_stopped", "imap_cp", "a halted or faulted machine retires nothing more"},
        {"a_xfer_local", "imap_cp",
         "xld writes local rows inside the transfer's range, which is inside the local memory"},
        {"a_xfer_ext", "imap_cp",
         "xst writes external rows inside the transfer's range, which is inside the external "
         "memory"},
        {"a_xfer_rows", "imap_cp", "a transfer that moves bytes moves all its rows (cD)"},
        {"a_xfer_active", "imap_top",
         "the transfer engine's active-PE count equals the PEs whose M the row interface "
         "carries (xe_pm)"},
    };
    return a;
}

std::string assertion_what(const std::string& name) {
    for (const Assertion& a : assertions())
        if (name == a.name) return a.what;
    return "";
}

uint32_t mutant_id(const std::string& name) {
    if (name == "none") return 0;  // the mutation-check model, no bug selected
    std::string known = "none";
    for (const Mutant& m : mutants()) {
        if (name == m.name) return m.id;
        known += ", " + std::string(m.name);
    }
    throw isa::ConfigError("invalid value '" + name + "' for the planted bug: expected one of " +
                           known);
}

std::vector<std::string> RtlWaves::scopes(const std::string& top, int pes_total) const {
    auto has = [&](const char* g) {
        return groups.empty() || std::find(groups.begin(), groups.end(), g) != groups.end();
    };
    const std::string tb = top + ".imap_tb", t = tb + ".u_chip";
    std::vector<std::string> s;
    if (groups.empty() && pes.empty()) return s;  // everything
    // the testbench top's ports (clk, straps, done) and the signals of the
    // chip imap_top itself (its board interface, the strap registers), not
    // the units below them ("!", model_impl.hpp)
    s.push_back(tb + "!");
    s.push_back(t + "!");
    if (has("cp")) s.push_back(t + ".u_cp");
    if (has("board")) s.push_back(tb + ".u_board");
    if (has("array")) s.push_back(t + ".u_array!");  // ring links, mask bus; the PEs below
    if (has("pe")) {
        if (pes.empty())
            for (int p = 0; p < pes_total; ++p)
                s.push_back(t + ".u_array.g_pe[" + std::to_string(p) + "]");
        else
            for (int p : pes) s.push_back(t + ".u_array.g_pe[" + std::to_string(p) + "]");
    }
    return s;
}

void RtlWaves::validate(const isa::MachineConfig& cfg) const {
    for (int p : pes)
        if (p < 0 || p >= cfg.pes)
            throw isa::ConfigError("waves: PE " + std::to_string(p) + " out of range (0.." +
                                   std::to_string(cfg.pes - 1) + ")");
    for (const std::string& g : groups)
        if (g != "cp" && g != "array" && g != "board" && g != "pe")
            throw isa::ConfigError("waves: invalid group '" + g +
                                   "' for the RTL model: expected cp, array, board, pe");
    if (t1 < t0) throw isa::ConfigError("waves: window end before its start");
}

void RtlConfig::validate(const isa::MachineConfig& cfg) const {
    if (inject.enabled) {
        if (inject.pe < 0 || inject.pe >= cfg.pes)
            throw isa::ConfigError("inject: PE " + std::to_string(inject.pe) +
                                   " out of range (0.." + std::to_string(cfg.pes - 1) + ")");
        if (inject.reg < FaultInjection::kRegM || inject.reg >= cfg.pe_regs)
            throw isa::ConfigError("inject: register " + reg_name(inject.reg) +
                                   " out of range (r0..r" + std::to_string(cfg.pe_regs - 1) +
                                   ", C, T, M)");
        if (inject.mask == 0) throw isa::ConfigError("inject: mask 0 injects nothing (1..255)");
        if (inject.reg < 0 && (inject.mask & 1u) == 0)
            throw isa::ConfigError("inject: a flag (C, T, M) is one bit: mask must be odd");
    }
    if (!mutant.empty()) mutant_id(mutant);
    if (!waves.path.empty()) waves.validate(cfg);
}

std::string gtkw_path(const std::string& waves_path) {
    const size_t slash = waves_path.find_last_of('/');
    const size_t dot = waves_path.find_last_of('.');
    if (dot == std::string::npos || (slash != std::string::npos && dot < slash))
        return waves_path + ".gtkw";
    return waves_path.substr(0, dot) + ".gtkw";
}

std::vector<std::string> built_configurations() {
    std::vector<std::string> v;
    for (const detail::ConfigInfo& c : detail::built_configs())
        v.push_back(std::string(c.name) + (c.mutants      ? " (mutation check)"
                                           : c.trace == 1 ? " (VCD waves)"
                                           : c.trace == 2 ? " (FST waves)"
                                                          : ""));
    return v;
}

namespace {
const detail::ConfigInfo* find(const isa::MachineConfig& cfg, int trace, bool mut) {
    return detail::find_config(cfg.pes, cfg.mem_bytes, cfg.ext_bytes, trace, mut);
}

// The configurations (any variant: 0; traced in that format: 1 VCD, 2 FST).
std::string built_list(int waves) {
    std::set<std::string> names;
    for (const detail::ConfigInfo& c : detail::built_configs())
        if (!c.mutants && (waves == 0 || c.trace == waves))
            names.insert(std::to_string(c.pes) + ":" + std::to_string(c.mem_bytes) + ":" +
                         std::to_string(c.ext_bytes));
    std::string s;
    for (const std::string& n : names) s += (s.empty() ? "" : ", ") + n;
    return s.empty() ? "none" : s;
}
}  // namespace

namespace {
// any variant runs untraced (IMAP_RTL_FST_ALL builds them all traced)
bool any_variant(const isa::MachineConfig& cfg, bool mut) {
    return find(cfg, 0, mut) || find(cfg, 1, mut) || find(cfg, 2, mut);
}
}  // namespace

bool has_configuration(const isa::MachineConfig& cfg) {
    return any_variant(cfg, false);
}

int waves_format(const std::string& path) {
    if (path.empty()) return 0;
    return path.size() > 4 && path.compare(path.size() - 4, 4, ".fst") == 0 ? 2 : 1;
}

std::string build_command(const isa::MachineConfig& cfg, int waves) {
    // FST: every configuration of an IMAP_RTL_FST_ALL build has it, so the
    // configuration is added like any other; VCD variants are listed apart.
    const bool trace_list = waves == 1 || (waves == 2 && !detail::build_fst_all());
    const std::string current =
        trace_list ? detail::build_trace_configs() : detail::build_extra_configs();
    const std::string list = current.empty() ? spec_of(cfg) : current + ";" + spec_of(cfg);
    const std::string bin = detail::build_binary_dir();
    std::error_code ec;
    if (!std::filesystem::is_directory(detail::build_source_dir(), ec) ||
        !std::filesystem::is_directory(bin, ec))
        // an installed binary whose build tree is gone: name the option
        return std::string("rebuild imapsim from its source tree with ") +
               (trace_list ? "-DIMAP_RTL_TRACE_CONFIGS=\"" : "-DIMAP_RTL_EXTRA_CONFIGS=\"") + list +
               "\" (docs/rtl.md)";
    return std::string("cmake -S ") + detail::build_source_dir() + " -B " + bin +
           (trace_list ? " -DIMAP_RTL_TRACE_CONFIGS=\"" : " -DIMAP_RTL_EXTRA_CONFIGS=\"") + list +
           "\" && cmake --build " + bin + " --target imapsim";
}

void check_runnable(const isa::MachineConfig& cfg, int waves, bool needs_mutants,
                    size_t program_words, size_t phases) {
    using namespace detail;
    const std::string what = "pes=" + std::to_string(cfg.pes) +
                             " mem_bytes=" + std::to_string(cfg.mem_bytes) +
                             " ext_bytes=" + std::to_string(cfg.ext_bytes);
    if (cfg.pe_regs > kHdlRegs)
        throw isa::ConfigError("RTL: pe_regs = " + std::to_string(cfg.pe_regs) +
                               " needs more registers than the design has per PE (" +
                               std::to_string(kHdlRegs) + ", imap_top parameter NREGS)");
    if (cfg.mask_depth > kHdlMaskDepth)
        throw isa::ConfigError("RTL: mask_depth = " + std::to_string(cfg.mask_depth) +
                               " needs a deeper mask stack than the design has (" +
                               std::to_string(kHdlMaskDepth) + ", imap_top parameter MASK_DEPTH)");
    if (cfg.call_depth > kHdlCallDepth)
        throw isa::ConfigError("RTL: call_depth = " + std::to_string(cfg.call_depth) +
                               " needs a deeper return stack than the design has (" +
                               std::to_string(kHdlCallDepth) + ", imap_top parameter CALL_DEPTH)");
    // A transfer row holds one byte per active PE, so with one PE active a
    // cycle completes ext_bytes_per_cycle rows: the row port must take them.
    if (cfg.costs.ext_bytes_per_cycle > static_cast<uint32_t>(kHdlXrows))
        throw isa::ConfigError(
            "RTL: ext_bytes_per_cycle = " + std::to_string(cfg.costs.ext_bytes_per_cycle) +
            " is more than the design's transfer path writes per cycle (" +
            std::to_string(kHdlXrows) +
            " rows, one byte each when a single PE is active; imap_top parameter XROWS)");
    if (cfg.mem_bytes > (1u << 20))
        throw isa::ConfigError("RTL: mem_bytes = " + std::to_string(cfg.mem_bytes) +
                               " is beyond the control word's 20-bit address (1048576)");
    if (program_words > kHdlImemWords)
        throw isa::ConfigError("RTL: the program has " + std::to_string(program_words) +
                               " instructions, the instruction memory holds " +
                               std::to_string(kHdlImemWords) + " (imap_top parameter IMEM_WORDS)");
    if (phases > static_cast<size_t>(kHdlPhases))
        throw isa::ConfigError("RTL: the program names " + std::to_string(phases) +
                               " phases, the design counts " + std::to_string(kHdlPhases) +
                               " (imap_top parameter PHASES)");
    if (cfg.watchdog_cycles > (UINT64_MAX >> 2))
        throw isa::ConfigError("RTL: watchdog_cycles too large");
    // (the limits first: nothing is built for a run that cannot run)
    if (needs_mutants) {
        bool any = false;
        for (const ConfigInfo& c : built_configs()) any |= c.mutants != 0;
        if (!any)
            throw isa::ConfigError(
                "RTL: this build has no mutation-check model (configure with "
                "-DIMAP_RTL_MUTANTS=ON)");
        if (!any_variant(cfg, true))
            throw isa::ConfigError(
                "RTL: the mutation-check model is built for pes=8 mem_bytes=1024 "
                "ext_bytes=65536 only (asked: " +
                what + ")");
    } else if (cache_enabled() &&
               (!has_configuration(cfg) || (waves != 0 && !find(cfg, waves, false)))) {
        // not built in: from the RTL cache (built on first use)
        CacheConfig c;
        c.pes = cfg.pes;
        c.mem_bytes = cfg.mem_bytes;
        c.ext_bytes = cfg.ext_bytes;
        c.trace = waves == 1 ? 1 : 2;
        cache_load(c, std::cerr);
    } else if (!has_configuration(cfg)) {
        throw isa::ConfigError("RTL: no configuration " + what +
                               " in this build (built: " + built_list(0) +
                               ") and building on demand is off (IMAP_RTL_CACHE=off); PE "
                               "count and memory sizes are HDL parameters: give the RTL cache a "
                               "folder (--rtl-cache DIR), or build it in with: " +
                               build_command(cfg, waves));
    } else if (waves != 0 && !find(cfg, waves, false)) {
        const char* fmt = waves == 2 ? "FST" : "VCD";
        throw isa::ConfigError(std::string("RTL waves: no ") + fmt + "-traced configuration " +
                               what + " in this build (" + fmt + ": " + built_list(waves) +
                               ") and building on demand is off (IMAP_RTL_CACHE=off); build it "
                               "in with: " +
                               build_command(cfg, waves));
    }
}

}  // namespace imap::rtl
