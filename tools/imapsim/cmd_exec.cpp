// imapsim exec: runs a user's program (IMAPFW01 file, or assembler source
// ending in .s / .asm) on a model of the machine, with optional video inputs
// and an output image on port 0 (docs/exec.md).
#include <algorithm>
#include <cerrno>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <iostream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>

#include "asm_flags.hpp"
#include "cli_common.hpp"
#include "imap/firmware/run.hpp"
#include "imap/isa/assembler.hpp"
#include "imap/isa/machine.hpp"
#include "imap/isa/program.hpp"
#include "imap/vision/image_io.hpp"
#include "model_runner.hpp"
#ifdef IMAPSIM_HAVE_TLM
#include "imap/tlm/system.hpp"
#endif

namespace imapsim {

namespace isa = imap::isa;
namespace v = imap::vision;
namespace fw = imap::firmware;

namespace {

struct ExecOptions {
    std::string program, left, right, out_left, out_size, report;
    std::string dump_pes, dump_mem;
    std::string model = kDefaultModel;
    std::vector<std::string> params, defines;
    MachineFlags machine;
    WaveFlags waves;
};

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
        } catch (const UserError&) {
            throw UserError("invalid value '" + text + "' for --dump-pes: expected " + want);
        }
        if (b < a) throw UserError("invalid value '" + text + "' for --dump-pes: expected " + want);
        for (long long q = a; q <= b; ++q) pes.push_back(static_cast<int>(q));
        if (comma == std::string::npos) break;
        at = comma + 1;
    }
    std::sort(pes.begin(), pes.end());
    pes.erase(std::unique(pes.begin(), pes.end()), pes.end());
    if (pes.size() > 64)
        throw UserError("invalid value '" + text + "' for --dump-pes: expected " + want);
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
            throw UserError("invalid value '" + text + "' for --dump-mem: expected " + want);
        return v;
    };
    if (colon == std::string::npos)
        throw UserError("invalid value '" + text + "' for --dump-mem: expected " + want);
    const long long a = num(text.substr(0, colon)), b = num(text.substr(colon + 1));
    if (b < a || b - a >= 4096)
        throw UserError("invalid value '" + text + "' for --dump-mem: expected " + want);
    return {static_cast<uint32_t>(a), static_cast<uint32_t>(b)};
}

// The registers, flags and (with a range) local memory of the chosen PEs,
// printed and as JSON for the report.
nlohmann::json dump_state(const isa::Machine& m, const std::vector<int>& pes, bool mem,
                          std::pair<uint32_t, uint32_t> range) {
    nlohmann::json out = nlohmann::json::array();
    if (pes.empty()) return out;
    const int nregs = m.config().pe_regs;
    std::printf("  PE state at the end (registers hex r0..r%d, flags C T M):\n", nregs - 1);
    for (const int pe : pes) {
        std::string line;
        nlohmann::json regs = nlohmann::json::array();
        char b[8];
        for (int r = 0; r < nregs; ++r) {
            const uint8_t v = m.reg_lanes(r)[pe];
            std::snprintf(b, sizeof b, "%s%02x", r == 0 ? "" : " ", v);
            line += b;
            regs.push_back(v);
        }
        const int c = m.carry_lanes()[pe], t = m.test_lanes()[pe], mk = m.mask_lanes()[pe];
        std::printf("    pe %d: %s  C=%d T=%d M=%d\n", pe, line.c_str(), c, t, mk);
        nlohmann::json j = {{"pe", pe}, {"regs", regs}, {"C", c}, {"T", t}, {"M", mk}};
        if (mem) {
            nlohmann::json bytes = nlohmann::json::array();
            for (uint32_t a = range.first; a <= range.second; ++a)
                bytes.push_back(m.mem_read(pe, a));
            j["mem"] = {{"first", range.first}, {"bytes", bytes}};
        }
        out.push_back(j);
    }
    if (mem) {
        std::printf("  PE local memory [0x%x..0x%x] (hex, 16 bytes a row):\n", range.first,
                    range.second);
        for (const int pe : pes)
            for (uint32_t a = range.first; a <= range.second; a += 16) {
                std::string line;
                char b[8];
                for (uint32_t k = a; k <= range.second && k < a + 16; ++k) {
                    std::snprintf(b, sizeof b, " %02x", m.mem_read(pe, k));
                    line += b;
                }
                std::printf("    pe %d @0x%04x:%s\n", pe, a, line.c_str());
            }
    }
    return out;
}

// What a run of the program produced, whatever the model.
struct ExecResult {
    uint64_t cycles = 0;
    double modeled_ms = 0, wall_s = 0;
    std::vector<uint64_t> phase_cycles;
    isa::Stats stats;
    std::array<uint32_t, isa::kCpRegs> cp{};
    isa::ImageVideoPort::Image out;             // output port 0
    std::shared_ptr<const isa::Machine> final;  // --model tlm: the state at the end
};

// Assembler source: a name ending in .s, .asm or .inc (run --emit-defines
// writes .inc), or a text file (no NUL byte in its first 4 KB) that does not
// start with the program file's magic.
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

// --param INDEX=VALUE: INDEX a param-block word, VALUE a 32-bit word (signed
// or unsigned).
std::vector<std::pair<int, uint32_t>> parse_params(const std::vector<std::string>& items) {
    std::map<int, uint32_t> words;
    for (const std::string& s : items) {
        const size_t eq = s.find('=');
        if (eq == std::string::npos || eq == 0 || eq + 1 == s.size())
            throw UserError("invalid value '" + s +
                            "' for --param: expected INDEX=VALUE (INDEX 0.." +
                            std::to_string(isa::kParamWords - 1) + ")");
        const int i = static_cast<int>(
            parse_int_flag("--param " + s + " (index)", s.substr(0, eq), 0, isa::kParamWords - 1));
        const long long val = parse_int_flag("--param " + s + " (value)", s.substr(eq + 1),
                                             -2147483648LL, 4294967295LL);
        if (!words.emplace(i, static_cast<uint32_t>(val)).second)
            throw UserError("--param " + std::to_string(i) + " given more than once");
    }
    return {words.begin(), words.end()};
}

isa::Program read_program(const ExecOptions& o) {
    if (!is_source(o.program)) {
        if (!o.defines.empty())
            throw UserError("-D applies to assembler sources (.s, .asm, .inc, text); '" +
                            o.program + "' is read as a program file (IMAPFW01)");
        try {
            return isa::load_program(o.program);
        } catch (const isa::FormatError& e) {
            throw UserError(e.what());
        }
    }
    return assemble_or_report(o.program, asm_options(o.defines), "nothing run");
}

isa::ImageVideoPort::Image read_input(const std::string& path, const char* what) {
    if (path.empty()) return {};
    const cv::Mat m = v::load_grey8(path, what);
    return fw::to_video_image(v::view_of(m));
}

// `m` has the program loaded.
ExecResult run_core(isa::Machine& m, const std::vector<std::pair<int, uint32_t>>& params,
                    const isa::ImageVideoPort::Image& left, const isa::ImageVideoPort::Image& right,
                    int out_w, int out_h) {
    const isa::MachineConfig& cfg = m.config();
    for (const auto& [i, val] : params) m.set_param(i, val);
    isa::ImageVideoPort video;
    video.input[0] = left;
    video.input[1] = right;
    video.make_output(0, out_w, out_h);
    video.make_output(1, out_w, out_h);
    m.set_video(&video);
    const auto t0 = std::chrono::steady_clock::now();
    m.run();
    ExecResult r;
    r.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    r.cycles = m.cycles();
    r.modeled_ms = cfg.milliseconds(r.cycles);
    r.phase_cycles = m.phase_cycles();
    r.stats = m.stats();
    for (int i = 0; i < isa::kCpRegs; ++i) r.cp[static_cast<size_t>(i)] = m.cp(i);
    r.out = video.output[0];
    return r;
}

#ifdef IMAPSIM_HAVE_TLM
ExecResult run_tlm_model(const isa::MachineConfig& cfg, const isa::Program& prog,
                         const std::vector<std::pair<int, uint32_t>>& params,
                         const isa::ImageVideoPort::Image& left,
                         const isa::ImageVideoPort::Image& right, int out_w, int out_h,
                         isa::Observer* observer) {
    imap::tlm::OutputImages out;
    imap::tlm::TlmConfig tcfg;
    tcfg.observer = observer;
    const imap::tlm::TlmRunResult tr =
        imap::tlm::run_tlm(cfg, prog, params, left, right, out_w, out_h, &out, tcfg);
    ExecResult r;
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

std::string exec_model_names() {
#ifdef IMAPSIM_HAVE_TLM
    return "tlm (SystemC TLM-2.0) or core (the bare instruction-set executor)";
#else
    return "core (the bare instruction-set executor)";
#endif
}

}  // namespace

Subcommand register_exec(CLI::App& app) {
    auto o = std::make_shared<ExecOptions>();
    CLI::App* sub = app.add_subcommand(
        "exec",
        "Run your own program (IMAPFW01 file, or assembler source .s / .asm / .inc) on a model "
        "of the machine (docs/exec.md)");
    sub->add_option("PROGRAM", o->program,
                    "program file (IMAPFW01), or assembler source: a name ending in .s, .asm or "
                    ".inc, or any text file without the IMAPFW01 magic")
        ->required();
    sub->add_option("--model", o->model, "model to run: " + exec_model_names())
        ->capture_default_str();
    sub->add_option("--left", o->left, "image on video input port 0 (optional)");
    sub->add_option("--right", o->right, "image on video input port 1 (optional)");
    sub->add_option("--param", o->params,
                    "param-block word before the run, INDEX=VALUE (INDEX 0..255, VALUE a 32-bit "
                    "integer); repeatable");
    sub->add_option("-D,--define", o->defines,
                    "assembler constant NAME=VALUE (or NAME, = 1), sources only; repeatable")
        ->allow_extra_args(false);
    sub->add_option("--out-left", o->out_left,
                    "write video output port 0 (the size of the input images) here");
    sub->add_option("--out-size", o->out_size,
                    "size WxH of the output ports [default: the size of the input images]");
    sub->add_option("--report", o->report, "write a JSON report here");
    sub->add_option("--dump-pes", o->dump_pes,
                    "print the registers and flags of these PEs at the end (a:b or 1,5,9; also "
                    "in the report)");
    sub->add_option("--dump-mem", o->dump_mem,
                    "with --dump-pes: also their local memory A:B (inclusive, e.g. 0x100:0x13f)");
    add_machine_flags(sub, o->machine);
    add_wave_flags(sub, o->waves);

    return {
        sub, [o]() {
            // Everything is checked before the run: a bad flag never costs a run.
            const isa::MachineConfig cfg = parse_machine_flags(o->machine);
            if (o->model != "core"
#ifdef IMAPSIM_HAVE_TLM
                && o->model != "tlm"
#endif
            )
                throw UserError("invalid value '" + o->model + "' for --model: exec runs " +
                                exec_model_names());
            const auto params = parse_params(o->params);
            const std::vector<int> dump_pes =
                o->dump_pes.empty() ? std::vector<int>{} : parse_pe_list(o->dump_pes, cfg.pes);
            if (!o->dump_mem.empty() && dump_pes.empty())
                throw UserError("--dump-mem needs --dump-pes (whose memory to print)");
            const auto mem_range = o->dump_mem.empty()
                                       ? std::pair<uint32_t, uint32_t>{0, 0}
                                       : parse_mem_range(o->dump_mem, cfg.mem_bytes);
            check_output_file("--out-left", o->out_left, true);
            check_output_file("--report", o->report, false);
            check_wave_outputs(o->waves, o->model);
            const isa::ImageVideoPort::Image left = read_input(o->left, "left image");
            const isa::ImageVideoPort::Image right = read_input(o->right, "right image");
            if (!o->left.empty() && !o->right.empty())
                check_same_size(o->left, left.width, left.height, o->right, right.width,
                                right.height);
            const isa::ImageVideoPort::Image& shape = o->left.empty() ? right : left;
            int out_w = shape.width, out_h = shape.height;
            if (!o->out_size.empty()) {
                int w = 0, h = 0;
                char x = 0;
                if (std::sscanf(o->out_size.c_str(), "%d%c%d", &w, &x, &h) != 3 || x != 'x' ||
                    w < 1 || h < 1 || w > 65536 || h > 65536)
                    throw UserError("invalid value '" + o->out_size +
                                    "' for --out-size: expected WxH with W and H in 1..65536");
                out_w = w;
                out_h = h;
            }
            if (!o->out_left.empty() && out_w == 0)
                throw UserError(
                    "--out-left needs an input image (--left or --right) or --out-size: the "
                    "output image has the size of the inputs");
            const isa::Program prog = read_program(*o);
            // Decoding checks every word against this machine (LoadError) before the run;
            // the core model runs this machine, the TLM model builds its own.
            auto machine = std::make_unique<isa::Machine>(cfg);
            try {
                machine->load(prog);
            } catch (const isa::LoadError& e) {
                throw UserError(o->program + ": " + e.what());
            }

            std::printf("imapsim exec: %s, %zu instructions, %zu phase%s, model %s\n",
                        o->program.c_str(), prog.code.size(), prog.phases.size(),
                        prog.phases.size() == 1 ? "" : "s", o->model.c_str());
            std::printf(
                "  machine: %d PEs at %g MHz, %u B local + %u B external per PE, watchdog "
                "%llu cycles\n",
                cfg.pes, cfg.clock_mhz, cfg.mem_bytes, cfg.ext_bytes,
                static_cast<unsigned long long>(cfg.watchdog_cycles));
            if (out_w > 0)
                std::printf("  video: inputs %s%s%s, output port 0 %dx%d\n",
                            o->left.empty() ? "" : ("0 = " + o->left).c_str(),
                            !o->left.empty() && !o->right.empty() ? ", " : "",
                            o->right.empty() ? "" : ("1 = " + o->right).c_str(), out_w, out_h);
            else
                std::printf("  video: no input images\n");
            std::fflush(stdout);

            ExecResult r;
            WaveSession waves(o->waves, cfg, prog);
            try {
#ifdef IMAPSIM_HAVE_TLM
                if (o->model == "tlm") {
                    machine.reset();
                    r = run_tlm_model(cfg, prog, params, left, right, out_w, out_h,
                                      waves.observer());
                } else
#endif
                {
                    machine->set_observer(waves.observer());
                    r = run_core(*machine, params, left, right, out_w, out_h);
                }
            } catch (const isa::LoadError& e) {
                throw UserError(o->program + ": " + e.what());
            } catch (const isa::ConfigError& e) {
                throw UserError(e.what());
            } catch (const isa::Fault& e) {
                // The waves and the state up to the fault are what one debugs with.
                waves.finish(e.cycle());
                if (machine) dump_state(*machine, dump_pes, !o->dump_mem.empty(), mem_range);
                throw UserError(std::string("machine fault: ") + e.what(), kExitFault);
            }
            waves.finish(r.cycles);

            std::printf("  halted: yes, %llu instructions\n",
                        static_cast<unsigned long long>(r.stats.instructions));
            std::printf("  cycles: %llu, modeled time %.6f ms at %g MHz\n",
                        static_cast<unsigned long long>(r.cycles), r.modeled_ms, cfg.clock_mhz);
            const auto phases = fw::phase_table(prog, r.phase_cycles);
            std::printf("  phases:\n");
            for (const auto& [name, cyc] : phases)
                std::printf("    %-14s %10llu cycles  %5.1f%%  %10.6f ms\n", name.c_str(),
                            static_cast<unsigned long long>(cyc),
                            r.cycles
                                ? 100.0 * static_cast<double>(cyc) / static_cast<double>(r.cycles)
                                : 0.0,
                            cfg.seconds(cyc) * 1e3);
            std::string regs;
            for (int i = 0; i < isa::kCpRegs; ++i)
                if (r.cp[static_cast<size_t>(i)] != 0)
                    regs += " c" + std::to_string(i) + "=" +
                            std::to_string(r.cp[static_cast<size_t>(i)]);
            std::printf("  CP registers (non-zero):%s\n", regs.empty() ? " none" : regs.c_str());
            std::printf("  wall: %.3f s (%s)\n", r.wall_s, o->model.c_str());
            const isa::Machine* final = r.final ? r.final.get() : machine.get();
            nlohmann::json pe_dump = nlohmann::json::array();
            if (final) pe_dump = dump_state(*final, dump_pes, !o->dump_mem.empty(), mem_range);

            if (!o->out_left.empty()) {
                cv::Mat img(r.out.height, r.out.width, CV_8UC1, r.out.pixels.data());
                v::write_image_atomic(o->out_left, img);
                std::printf("  output port 0 -> %s\n", o->out_left.c_str());
            }
            if (!o->report.empty()) {
                nlohmann::json j;
                j["program"] = o->program;
                j["model"] = o->model;
                j["halted"] = true;
                j["cycles"] = r.cycles;
                j["instructions"] = r.stats.instructions;
                j["modeled_ms"] = r.modeled_ms;
                j["wall_s"] = r.wall_s;
                nlohmann::json ph = nlohmann::json::object();
                for (const auto& [name, cyc] : phases) ph[name] = cyc;
                j["phases"] = ph;
                j["cp"] = r.cp;
                nlohmann::json pb = nlohmann::json::object();
                for (const auto& [i, val] : params) pb[std::to_string(i)] = val;
                j["params"] = {{"machine", machine_params_json(cfg)},
                               {"machine_info", machine_param_info_json(cfg)},
                               {"param_block", pb}};
                if (!dump_pes.empty()) j["pes"] = pe_dump;
                j["video"] = {{"left", o->left},
                              {"right", o->right},
                              {"out_width", out_w},
                              {"out_height", out_h}};
                v::write_text_atomic(o->report, j.dump(2) + "\n");
                std::printf("  report -> %s\n", o->report.c_str());
            }
            return static_cast<int>(kExitOk);
        }};
}

}  // namespace imapsim
