#include "imap/rtl/area.hpp"

#include <cmath>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace imap::rtl {

namespace detail {
const char* synth_pe_json();
const char* synth_pe_mem_json();
const char* synth_cp_json();
const char* synth_cp_mem_json();
}  // namespace detail

namespace {
UnitArea unit(const char* cells_json, const char* mem_json, const std::string& top,
              std::string* tool) {
    UnitArea u;
    const nlohmann::json c = nlohmann::json::parse(cells_json);
    const nlohmann::json m = nlohmann::json::parse(mem_json);
    const nlohmann::json& mc = c.at("modules").at("\\" + top);
    u.cells = mc.at("num_cells").get<uint64_t>();
    for (const auto& [type, n] : mc.at("num_cells_by_type").items()) {
        const uint64_t k = n.get<uint64_t>();
        if (type.rfind("$mem", 0) == 0) {
            u.cells -= k;  // counted as memory bits
            continue;
        }
        u.by_type[type] = k;
        if (type.find("DFF") != std::string::npos) u.flops += k;
    }
    u.memory_bits = m.at("modules").at("\\" + top).at("num_memory_bits").get<uint64_t>();
    if (tool) *tool = c.at("creator").get<std::string>();
    return u;
}
}  // namespace

const SynthFigures& synthesis() {
    static const SynthFigures f = [] {
        SynthFigures s;
        if (*detail::synth_pe_json() == '\0') return s;
        s.pe = unit(detail::synth_pe_json(), detail::synth_pe_mem_json(), "imap_pe", &s.tool);
        s.cp = unit(detail::synth_cp_json(), detail::synth_cp_mem_json(), "imap_cp", nullptr);
        s.params =
            "PE: NREGS 16, MEM_BYTES 1024, MASK_DEPTH 8, XROWS 8; CP: P 256, "
            "IMEM_WORDS 65536, CALL_DEPTH 16";
        s.pe_mem_bytes = 1024;
        s.cp_pes = 256;
        s.available = true;
        return s;
    }();
    return f;
}

ArrayArea array_area(const isa::MachineConfig& cfg) {
    const SynthFigures& s = synthesis();
    if (!s.available)
        throw std::runtime_error("RTL area: this build has no synthesis figures (yosys missing)");
    ArrayArea a;
    const uint64_t P = static_cast<uint64_t>(cfg.pes);
    a.pe_cells = s.pe.cells;
    a.cp_cells = s.cp.cells;
    a.cells = P * s.pe.cells + s.cp.cells;
    // registers + local memory per PE at this configuration; the CP's memories
    // (instruction memory, param block, return stack) as synthesized
    const uint64_t pe_bits = 8ull * 16 + 8ull * cfg.mem_bytes;  // NREGS = 16 in the HDL
    a.memory_bits = P * pe_bits + s.cp.memory_bits;
    a.ext_bits = 8ull * P * cfg.ext_bytes;
    return a;
}

}  // namespace imap::rtl

// libsystemc refers to sc_main (its own main() calls it); programs using the
// RTL library call run_rtl etc. from their own main(). A weak definition
// here (as in imap_tlm) satisfies the reference for programs that use only
// this library's plain parts (area, configurations).
extern "C" __attribute__((weak)) int sc_main(int, char**) {
    return 1;
}
