// imapsim exec: runs a user's program (IMAPFW01 file, or assembler source
// ending in .s / .asm) on a model of the machine, with optional video inputs
// and an output image on port 0 (docs/exec.md). Its flags, their parse and
// the printed lines; the checks (exec_request.hpp) and the run (exec.hpp)
// are the engine's.
#include <algorithm>
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "asm_flags.hpp"
#include "cli_common.hpp"
#include "imap/engine/exec.hpp"
#include "imap/engine/exec_request.hpp"
#include "imap/isa/assembler.hpp"
#include "imap/isa/machine.hpp"
#include "imap/isa/program.hpp"
#include "imap/vision/image_io.hpp"
#include "model_runner.hpp"

namespace imapsim {

namespace isa = imap::isa;
namespace v = imap::vision;
namespace ex = imap::engine::exec;

namespace {

struct ExecOptions : ex::Request {
    ExecOptions() { model = kDefaultModel; }
};

// The PE state of ex::pe_state: registers and flags, then (with `mem`) the
// local memory, 16 bytes a row.
void print_pe_state(const nlohmann::json& pes, bool mem) {
    if (pes.empty()) return;
    std::printf("  PE state at the end (registers hex r0..r%d, flags C T M):\n",
                static_cast<int>(pes[0]["regs"].size()) - 1);
    for (const auto& j : pes) {
        std::string line;
        char b[8];
        for (size_t r = 0; r < j["regs"].size(); ++r) {
            std::snprintf(b, sizeof b, "%s%02x", r == 0 ? "" : " ", j["regs"][r].get<unsigned>());
            line += b;
        }
        std::printf("    pe %d: %s  C=%d T=%d M=%d\n", j["pe"].get<int>(), line.c_str(),
                    j["C"].get<int>(), j["T"].get<int>(), j["M"].get<int>());
    }
    if (!mem) return;
    const uint32_t first = pes[0]["mem"]["first"].get<uint32_t>();
    const uint32_t last = first + static_cast<uint32_t>(pes[0]["mem"]["bytes"].size()) - 1;
    std::printf("  PE local memory [0x%x..0x%x] (hex, 16 bytes a row):\n", first, last);
    for (const auto& j : pes)
        for (uint32_t a = first; a <= last; a += 16) {
            std::string line;
            char b[8];
            for (uint32_t k = a; k <= last && k < a + 16; ++k) {
                std::snprintf(b, sizeof b, " %02x", j["mem"]["bytes"][k - first].get<unsigned>());
                line += b;
            }
            std::printf("    pe %d @0x%04x:%s\n", j["pe"].get<int>(), a, line.c_str());
        }
}

isa::Program read_program(const ExecOptions& o) {
    if (!ex::is_source(o.program)) {
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

void print_header(const ExecOptions& o, const isa::Program& prog, const isa::MachineConfig& cfg,
                  const ex::Inputs& in) {
    std::printf("imapsim exec: %s, %zu instructions, %zu phase%s, model %s\n", o.program.c_str(),
                prog.code.size(), prog.phases.size(), prog.phases.size() == 1 ? "" : "s",
                o.model.c_str());
    std::printf(
        "  machine: %d PEs at %g MHz, %u B local + %u B external per PE, watchdog "
        "%llu cycles\n",
        cfg.pes, cfg.clock_mhz, cfg.mem_bytes, cfg.ext_bytes,
        static_cast<unsigned long long>(cfg.watchdog_cycles));
    if (in.out_w > 0)
        std::printf("  video: inputs %s%s%s, output port 0 %dx%d\n",
                    o.left.empty() ? "" : ("0 = " + o.left).c_str(),
                    !o.left.empty() && !o.right.empty() ? ", " : "",
                    o.right.empty() ? "" : ("1 = " + o.right).c_str(), in.out_w, in.out_h);
    else
        std::printf("  video: no input images\n");
    std::fflush(stdout);
}

void print_result(const ex::Result& r, const isa::MachineConfig& cfg, const std::string& model) {
    std::printf("  halted: yes, %llu instructions\n",
                static_cast<unsigned long long>(r.stats.instructions));
    std::printf("  cycles: %llu, modeled time %.6f ms at %g MHz\n",
                static_cast<unsigned long long>(r.cycles), r.modeled_ms, cfg.clock_mhz);
    std::printf("  phases:\n");
    for (const auto& [name, cyc] : r.phases)
        std::printf(
            "    %-14s %10llu cycles  %5.1f%%  %10.6f ms\n", name.c_str(),
            static_cast<unsigned long long>(cyc),
            r.cycles ? 100.0 * static_cast<double>(cyc) / static_cast<double>(r.cycles) : 0.0,
            cfg.seconds(cyc) * 1e3);
    std::string regs;
    for (int i = 0; i < isa::kCpRegs; ++i)
        if (r.cp[static_cast<size_t>(i)] != 0)
            regs += " c" + std::to_string(i) + "=" + std::to_string(r.cp[static_cast<size_t>(i)]);
    std::printf("  CP registers (non-zero):%s\n", regs.empty() ? " none" : regs.c_str());
    std::printf("  wall: %.3f s (%s)\n", r.wall_s, model.c_str());
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
    sub->add_option("--model", o->model, "model to run: " + ex::model_names())
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

    return {sub, [o]() {
                // Everything is checked before the run: a bad flag never costs a run.
                const ex::Checked c =
                    ex::check(*o, [&] { check_wave_outputs(o->waves, o->model); });
                const isa::MachineConfig& cfg = c.cfg;
                const ex::Inputs& in = c.in;
                const std::vector<int>& dump_pes = c.dump_pes;
                const auto mem_range = c.mem_range;
                const isa::Program prog = read_program(*o);
                // Decoding checks every word against this machine before the run;
                // the core model runs this machine, the TLM model builds its own.
                std::unique_ptr<isa::Machine> machine = ex::load_machine(cfg, prog, o->program);
                print_header(*o, prog, cfg, in);
                ex::Result r;
                WaveSession waves(o->waves, cfg, prog);
                const bool mem = !o->dump_mem.empty();
                try {
                    r = ex::run(o->model, machine, prog, in, waves.observer());
                } catch (const isa::Fault& e) {
                    // The waves and the state up to the fault are what one debugs with.
                    waves.finish(e.cycle());
                    if (machine)
                        print_pe_state(ex::pe_state(*machine, dump_pes, mem, mem_range), mem);
                    throw UserError(std::string("machine fault: ") + e.what(), kExitFault);
                }
                waves.finish(r.cycles);
                print_result(r, cfg, o->model);
                const isa::Machine* final = r.final ? r.final.get() : machine.get();
                nlohmann::json pe_dump = nlohmann::json::array();
                if (final) pe_dump = ex::pe_state(*final, dump_pes, mem, mem_range);
                print_pe_state(pe_dump, mem);
                if (!o->out_left.empty()) {
                    cv::Mat img(r.out.height, r.out.width, CV_8UC1, r.out.pixels.data());
                    v::write_image_atomic(o->out_left, img);
                    std::printf("  output port 0 -> %s\n", o->out_left.c_str());
                }
                if (!o->report.empty()) {
                    const nlohmann::json j =
                        ex::report(o->program, o->model, cfg, in, r, pe_dump, o->left, o->right);
                    v::write_text_atomic(o->report, j.dump(2) + "\n");
                    std::printf("  report -> %s\n", o->report.c_str());
                }
                return static_cast<int>(kExitOk);
            }};
}

}  // namespace imapsim
