// Running a user's program (imapsim exec, docs/exec.md): telling assembler
// source from a program file, loading the program onto a machine, running
// it on the core or TLM model with param-block words and video images, the
// state of chosen PEs at the end, and the JSON report. In imap_engine_models.
#pragma once

#include <array>
#include <cstdint>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "imap/isa/config.hpp"
#include "imap/isa/machine.hpp"
#include "imap/isa/program.hpp"

namespace imap::engine::exec {

// The models exec runs in this build, in words ("tlm (...) or core (...)");
// check_model: Error (exit 2) for another.
std::string model_names();
void check_model(const std::string& model);

// The values of exec's flags (Error naming the flag and the allowed form):
// --dump-pes "a:b" (inclusive) and / or a list "1,5,9" of PEs in 0..P-1, at
// most 64, sorted; --dump-mem "A:B" local addresses (decimal or 0x hex)
// below mem_bytes, at most 4096 bytes; --param INDEX=VALUE words.
std::vector<int> parse_pe_list(const std::string& text, int P);
std::pair<uint32_t, uint32_t> parse_mem_range(const std::string& text, uint32_t mem_bytes);
std::vector<std::pair<int, uint32_t>> parse_params(const std::vector<std::string>& items);

// Assembler source: a name ending in .s, .asm or .inc, or a text file (no
// NUL byte in its first 4 KB) that does not start with the program file's magic.
bool is_source(const std::string& path);

// The program loaded onto a machine of `cfg`: every word is decoded and
// checked against the machine before the run; Error "<name>: ..." otherwise.
std::unique_ptr<isa::Machine> load_machine(const isa::MachineConfig& cfg, const isa::Program& prog,
                                           const std::string& name);

// What goes in: param-block words, the images on video inputs 0 and 1
// (empty = none) and the size of the output ports; `name` names the
// program in messages.
struct Inputs {
    std::string name;
    std::vector<std::pair<int, uint32_t>> params;
    isa::ImageVideoPort::Image left, right;
    int out_w = 0, out_h = 0;
};

// What a run of the program produced, whatever the model.
struct Result {
    uint64_t cycles = 0;
    double modeled_ms = 0, wall_s = 0;
    std::vector<uint64_t> phase_cycles;
    std::vector<std::pair<std::string, uint64_t>> phases;  // named, in program order
    isa::Stats stats;
    std::array<uint32_t, isa::kCpRegs> cp{};
    isa::ImageVideoPort::Image out;             // output port 0
    std::shared_ptr<const isa::Machine> final;  // --model tlm: the state at the end
};

// Runs `prog` on `model` ("core": on `machine`, which has it loaded; "tlm":
// a machine of its own, and `machine` is released). isa::Fault propagates
// (the caller dumps the state up to it); load and configuration errors are Error.
Result run(const std::string& model, std::unique_ptr<isa::Machine>& machine,
           const isa::Program& prog, const Inputs& in, isa::Observer* observer = nullptr);

// The registers, flags (C, T, M) and, with `mem`, local memory [first..last]
// of the chosen PEs: [{pe, regs, C, T, M, mem: {first, bytes}}].
nlohmann::json pe_state(const isa::Machine& m, const std::vector<int>& pes, bool mem,
                        std::pair<uint32_t, uint32_t> range);

// The exec report (docs/exec.md): program, model, cycles, phases, CP
// registers, the parameters, the PE dump (when given) and the video ports.
nlohmann::json report(const std::string& program, const std::string& model,
                      const isa::MachineConfig& cfg, const Inputs& in, const Result& r,
                      const nlohmann::json& pes, const std::string& left, const std::string& right);

}  // namespace imap::engine::exec
