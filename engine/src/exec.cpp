// Running a user's program (exec.hpp): source or program file, loading onto
// a machine, the run on the core or TLM model, the PEs' state and the report.
#include "imap/engine/exec.hpp"

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <map>

#include "imap/engine/error.hpp"
#include "imap/engine/flag_values.hpp"
#include "imap/engine/output_files.hpp"
#include "imap/engine/params_json.hpp"
#include "imap/firmware/run.hpp"
#ifdef IMAP_ENGINE_HAVE_TLM
#include "imap/tlm/system.hpp"
#endif

namespace imap::engine::exec {

namespace {

// `m` has the program loaded.
Result run_core(isa::Machine& m, const Inputs& in) {
    const isa::MachineConfig& cfg = m.config();
    for (const auto& [i, val] : in.params) m.set_param(i, val);
    isa::ImageVideoPort video;
    video.input[0] = in.left;
    video.input[1] = in.right;
    video.make_output(0, in.out_w, in.out_h);
    video.make_output(1, in.out_w, in.out_h);
    m.set_video(&video);
    const auto t0 = std::chrono::steady_clock::now();
    m.run();
    Result r;
    r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.cycles = m.cycles();
    r.modeled_ms = cfg.milliseconds(r.cycles);
    r.phase_cycles = m.phase_cycles();
    r.stats = m.stats();
    for (int i = 0; i < isa::kCpRegs; ++i) r.cp[static_cast<size_t>(i)] = m.cp(i);
    r.out = video.output[0];
    return r;
}

#ifdef IMAP_ENGINE_HAVE_TLM
Result run_tlm_model(const isa::MachineConfig& cfg, const isa::Program& prog, const Inputs& in,
                     isa::Observer* observer) {
    imap::tlm::OutputImages out;
    imap::tlm::TlmConfig tcfg;
    tcfg.observer = observer;
    const imap::tlm::TlmRunResult tr =
        imap::tlm::run_tlm(cfg, prog, in.params, in.left, in.right, in.out_w, in.out_h, &out, tcfg);
    Result r;
    r.cycles = tr.cycles;
    r.modeled_ms = tr.modeled_ms;
    r.wall_s = tr.wall_s;
    r.phase_cycles = tr.phase_cycles;
    r.stats = tr.stats;
    if (tr.machine)
        for (int i = 0; i < isa::kCpRegs; ++i) r.cp[static_cast<size_t>(i)] = tr.machine->cp(i);
    r.out = out.image[0];
    r.final = tr.machine;
    return r;
}
#endif

}  // namespace

std::string model_names() {
#ifdef IMAP_ENGINE_HAVE_TLM
    return "tlm (SystemC TLM-2.0) or core (the bare instruction-set executor)";
#else
    return "core (the bare instruction-set executor)";
#endif
}

void check_model(const std::string& model) {
    if (model != "core"
#ifdef IMAP_ENGINE_HAVE_TLM
        && model != "tlm"
#endif
    )
        throw Error("invalid value '" + model + "' for --model: exec runs " + model_names());
}

// --dump-pes: "a:b" (inclusive) or a list "1,5,9" or both, PEs of 0..P-1.
std::vector<int> parse_pe_list(const std::string& text, int P) {
    const std::string want = "PEs as a:b (inclusive) or a list 1,5,9 with PEs in 0.." +
                             std::to_string(P - 1) + ", at most 64";
    std::vector<int> pes;
    size_t at = 0;
    while (at <= text.size()) {
        const size_t comma = text.find(',', at);
        const std::string item =
            text.substr(at, comma == std::string::npos ? std::string::npos : comma - at);
        const size_t colon = item.find(':');
        long long a = 0, b = 0;
        try {
            if (colon == std::string::npos) {
                a = b = parse_int_flag("--dump-pes", item, 0, P - 1);
            } else {
                a = parse_int_flag("--dump-pes", item.substr(0, colon), 0, P - 1);
                b = parse_int_flag("--dump-pes", item.substr(colon + 1), 0, P - 1);
            }
        } catch (const Error&) {
            throw Error("invalid value '" + text + "' for --dump-pes: expected " + want);
        }
        if (b < a) throw Error("invalid value '" + text + "' for --dump-pes: expected " + want);
        for (long long q = a; q <= b; ++q) pes.push_back(static_cast<int>(q));
        if (comma == std::string::npos) break;
        at = comma + 1;
    }
    std::sort(pes.begin(), pes.end());
    pes.erase(std::unique(pes.begin(), pes.end()), pes.end());
    if (pes.size() > 64)
        throw Error("invalid value '" + text + "' for --dump-pes: expected " + want);
    return pes;
}

// --dump-mem A:B: local addresses A..B (inclusive), decimal or 0x hex.
std::pair<uint32_t, uint32_t> parse_mem_range(const std::string& text, uint32_t mem_bytes) {
    const std::string want = "A:B, local addresses (decimal or 0x hex) with A <= B in 0.." +
                             std::to_string(mem_bytes - 1) + ", at most 4096 bytes";
    const size_t colon = text.find(':');
    auto num = [&](const std::string& t) -> long long {
        errno = 0;
        char* end = nullptr;
        const long long v = std::strtoll(t.c_str(), &end, 0);
        if (t.empty() || errno != 0 || *end != '\0' || v < 0 ||
            v >= static_cast<long long>(mem_bytes))
            throw Error("invalid value '" + text + "' for --dump-mem: expected " + want);
        return v;
    };
    if (colon == std::string::npos)
        throw Error("invalid value '" + text + "' for --dump-mem: expected " + want);
    const long long a = num(text.substr(0, colon)), b = num(text.substr(colon + 1));
    if (b < a || b - a >= 4096)
        throw Error("invalid value '" + text + "' for --dump-mem: expected " + want);
    return {static_cast<uint32_t>(a), static_cast<uint32_t>(b)};
}

// --param INDEX=VALUE: INDEX a param-block word, VALUE a 32-bit word (signed
// or unsigned).
std::vector<std::pair<int, uint32_t>> parse_params(const std::vector<std::string>& items) {
    std::map<int, uint32_t> words;
    for (const std::string& s : items) {
        const size_t eq = s.find('=');
        if (eq == std::string::npos || eq == 0 || eq + 1 == s.size())
            throw Error("invalid value '" + s + "' for --param: expected INDEX=VALUE (INDEX 0.." +
                        std::to_string(isa::kParamWords - 1) + ")");
        const int i = static_cast<int>(
            parse_int_flag("--param " + s + " (index)", s.substr(0, eq), 0, isa::kParamWords - 1));
        const long long val = parse_int_flag("--param " + s + " (value)", s.substr(eq + 1),
                                             -2147483648LL, 4294967295LL);
        if (!words.emplace(i, static_cast<uint32_t>(val)).second)
            throw Error("--param " + std::to_string(i) + " given more than once");
    }
    return {words.begin(), words.end()};
}

bool is_source(const std::string& path) {
    const std::string ext = lower_extension(path);
    if (ext == ".s" || ext == ".asm" || ext == ".inc") return true;
    std::ifstream f(path, std::ios::binary);
    char buf[4096];
    f.read(buf, sizeof buf);
    const std::streamsize n = f.gcount();
    if (n <= 0) return false;  // missing or empty: the program loader says so
    if (n >= 8 && std::memcmp(buf, "IMAPFW01", 8) == 0) return false;
    return std::find(buf, buf + n, '\0') == buf + n;
}

std::unique_ptr<isa::Machine> load_machine(const isa::MachineConfig& cfg, const isa::Program& prog,
                                           const std::string& name) {
    auto machine = std::make_unique<isa::Machine>(cfg);
    try {
        machine->load(prog);
    } catch (const isa::LoadError& e) {
        throw Error(name + ": " + e.what());
    }
    return machine;
}

Result run(const std::string& model, std::unique_ptr<isa::Machine>& machine,
           const isa::Program& prog, const Inputs& in, isa::Observer* observer) {
    const isa::MachineConfig cfg = machine->config();
    Result r;
    try {
#ifdef IMAP_ENGINE_HAVE_TLM
        if (model == "tlm") {
            machine.reset();
            r = run_tlm_model(cfg, prog, in, observer);
        } else
#endif
        {
            machine->set_observer(observer);
            r = run_core(*machine, in);
        }
    } catch (const isa::LoadError& e) {
        throw Error(in.name + ": " + e.what());
    } catch (const isa::ConfigError& e) {
        throw Error(e.what());
    }
    r.phases = firmware::phase_table(prog, r.phase_cycles);
    return r;
}

nlohmann::json pe_state(const isa::Machine& m, const std::vector<int>& pes, bool mem,
                        std::pair<uint32_t, uint32_t> range) {
    nlohmann::json out = nlohmann::json::array();
    const int nregs = m.config().pe_regs;
    for (const int pe : pes) {
        nlohmann::json regs = nlohmann::json::array();
        for (int r = 0; r < nregs; ++r) regs.push_back(m.reg_lanes(r)[pe]);
        nlohmann::json j = {{"pe", pe},
                            {"regs", regs},
                            {"C", m.carry_lanes()[pe]},
                            {"T", m.test_lanes()[pe]},
                            {"M", m.mask_lanes()[pe]}};
        if (mem) {
            nlohmann::json bytes = nlohmann::json::array();
            for (uint32_t a = range.first; a <= range.second; ++a)
                bytes.push_back(m.mem_read(pe, a));
            j["mem"] = {{"first", range.first}, {"bytes", bytes}};
        }
        out.push_back(j);
    }
    return out;
}

nlohmann::json report(const std::string& program, const std::string& model,
                      const isa::MachineConfig& cfg, const Inputs& in, const Result& r,
                      const nlohmann::json& pes, const std::string& left,
                      const std::string& right) {
    nlohmann::json j;
    j["program"] = program;
    j["model"] = model;
    j["halted"] = true;
    j["cycles"] = r.cycles;
    j["instructions"] = r.stats.instructions;
    j["modeled_ms"] = r.modeled_ms;
    j["wall_s"] = r.wall_s;
    nlohmann::json ph = nlohmann::json::object();
    for (const auto& [name, cyc] : r.phases) ph[name] = cyc;
    j["phases"] = ph;
    j["cp"] = r.cp;
    nlohmann::json pb = nlohmann::json::object();
    for (const auto& [i, val] : in.params) pb[std::to_string(i)] = val;
    j["params"] = {{"machine", machine_params_json(cfg)},
                   {"machine_info", machine_param_info_json(cfg)},
                   {"param_block", pb}};
    if (!pes.empty()) j["pes"] = pes;
    j["video"] = {
        {"left", left}, {"right", right}, {"out_width", in.out_w}, {"out_height", in.out_h}};
    return j;
}

}  // namespace imap::engine::exec
