#include "imap/rtl/config.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <string>

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

void RtlConfig::validate(const isa::MachineConfig& cfg) const {
    if (trace_pe_first < 0 || trace_pe_first > cfg.pes)
        throw isa::ConfigError("trace_pe_first = " + std::to_string(trace_pe_first) +
                               " out of range (0.." + std::to_string(cfg.pes) + ")");
    if (trace_pe_count < -1 || (trace_pe_count > 0 && trace_pe_first + trace_pe_count > cfg.pes))
        throw isa::ConfigError("trace_pe_count = " + std::to_string(trace_pe_count) +
                               " out of range (-1 = to the last PE, 0.." +
                               std::to_string(cfg.pes - trace_pe_first) + ")");
    for (int r : trace_regs)
        if (r < 0 || r >= cfg.pe_regs)
            throw isa::ConfigError("trace_regs: register " + std::to_string(r) +
                                   " out of range (0.." + std::to_string(cfg.pe_regs - 1) + ")");
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
}

int RtlConfig::traced_first(const isa::MachineConfig& cfg) const {
    return std::min(trace_pe_first, cfg.pes);
}

int RtlConfig::traced_count(const isa::MachineConfig& cfg) const {
    return trace_pe_count < 0 ? cfg.pes - traced_first(cfg) : trace_pe_count;
}

std::vector<int> RtlConfig::traced_regs(const isa::MachineConfig& cfg) const {
    if (!trace_regs.empty()) return trace_regs;
    std::vector<int> all;
    for (int r = 0; r < cfg.pe_regs; ++r) all.push_back(r);
    return all;
}

}  // namespace imap::rtl
