// Constrained-random verification of the RTL design (docs/rtl.md, "Random
// suite"): a seeded generator of valid programs over every opcode, operand
// class, mask state and nesting, ring distance and direction, transfer
// length and branch shape, run in lockstep against the instruction-set
// model with a random cost table per program; a functional-coverage model
// of what ran; and the mutation check (the same suite against the
// mutation-check model with one planted bug at a time).
#pragma once

#include <cstdint>
#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <utility>
#include <vector>

#include "imap/isa/config.hpp"
#include "imap/isa/machine.hpp"
#include "imap/isa/program.hpp"

namespace imap::rtl {

struct GenOptions {
    int pes = 8;
    uint32_t mem_bytes = 1024, ext_bytes = 65536;
    int blocks = 40;         // top-level blocks per program
    bool vary_costs = true;  // a random cost table per program (some keep the defaults)
    int fault_percent = 20;  // programs that end in a deliberate machine fault (one of ten kinds)
    // The strap sweep instead of random programs: each program runs one
    // instruction of every cost class (and a phase, a call) under straps
    // (cost table, pe_regs, mask_depth, call_depth, watchdog; the program's
    // length and the phase id) drawn from
    // two or three complementary values by the seed, so that consecutive
    // seeds flip every bit a strap can hold on this design; every cost near
    // the top of its range (docs/rtl.md, "Code coverage").
    bool strap_sweep = false;
};

struct RandomProgram {
    uint64_t seed = 0;
    isa::MachineConfig cfg;
    isa::Program prog;
    std::vector<std::pair<int, uint32_t>> params;
    isa::ImageVideoPort::Image left, right;
    int out_w = 0, out_h = 0;
    std::string ending;  // "halt" or the deliberate fault
};

RandomProgram generate_program(uint64_t seed, const GenOptions& opt = {});

// Functional coverage: bins named "group/bin", sampled per retired
// instruction.
class Coverage {
  public:
    explicit Coverage(int pes = 8);
    // After instruction (word at pc) retired; `before` = state before it
    // (active PEs, mask depth), `m` = the reference's state after it.
    void sample(uint64_t word, uint32_t pc, int active_before, int mask_depth_before,
                const isa::Machine& m);
    void merge(const Coverage& o);
    size_t bins() const { return bins_.size(); }
    size_t covered() const;
    std::vector<std::string> uncovered() const;
    std::string table() const;  // printable, one row per group
    nlohmann::json json() const;

  private:
    void hit(const std::string& bin);
    int P_;
    std::map<std::string, uint64_t> bins_;  // every bin declared, with its hits
};

struct SuiteOptions {
    uint64_t seed = 1;
    int programs = 300;
    GenOptions gen;
    std::string mutant;  // planted bug (mutation-check model), "" = none
    bool stop_at_divergence = false;
    // The checker's full compares of all PE registers and flags / the whole
    // local memory every this many instructions (0: automatic, Checker's
    // auto_reg_every / auto_mem_every; a huge value: only what each
    // instruction names, and the final state).
    uint64_t full_compare_every = 0;
    // false: the RTL alone, no reference and no trace port (the design's
    // assertions are then the only check: docs/rtl.md, "Assertions"); a
    // program that ends in a machine fault passes.
    bool lockstep = true;
};

struct SuiteResult {
    int programs = 0, passed = 0;
    uint64_t instructions = 0, cycles = 0;
    std::vector<std::string> failures;  // one line each (program seed, divergence)
    // the first divergence: program index, instruction index in it, and the
    // instructions retired over all programs until it was caught
    bool caught = false;
    int caught_program = -1;
    uint64_t caught_instruction = 0, instructions_to_catch = 0;
    std::string caught_message;
    std::string caught_assertion;  // the first failure is this assertion of the design ("" other)
    Coverage coverage;
    double wall_s = 0;
};

// Runs the suite in one SystemC elaboration (once per process): every
// program through the RTL (P = gen.pes; with `mutant`, the mutation-check
// model) and the instruction-set model, compared at every instruction.
SuiteResult run_random_suite(const SuiteOptions& opt);

}  // namespace imap::rtl
