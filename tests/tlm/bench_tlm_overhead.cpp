// Speed of the TLM wrapper: the same ALU loop on a bare isa::Machine and
// through run_tlm; prints wall ns per instruction and the overhead.
//   bench_tlm_overhead [iterations (x100), default 10000] [quantum_ns] [instruction]
// The loop body is 100 copies of `instruction` (default "add r1, r1, r2").
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>

#include "imap/isa/isa.hpp"
#include "imap/tlm/tlm.hpp"

namespace isa = imap::isa;
namespace itlm = imap::tlm;

int main(int argc, char** argv) {
    const long iters = argc > 1 ? std::atol(argv[1]) : 10000;
    itlm::TlmConfig tc;
    if (argc > 2) tc.quantum_ns = std::atof(argv[2]);
    const std::string insn = argc > 3 ? argv[3] : "add r1, r1, r2";
    isa::MachineConfig cfg;
    cfg.pes = 256;
    const std::string src = "cli c0, #" + std::to_string(iters) +
                            "\nli r2, #3\nbody:\n.rept 100\n" + insn +
                            "\n.endr\nloop c0, body\nhalt\n";
    const isa::Program prog = isa::assemble_string(src, "bench.s");

    double bare_best = 1e30;
    uint64_t instr = 0, cycles = 0;
    for (int rep = 0; rep < 3; ++rep) {
        isa::Machine m(cfg);
        m.load(prog);
        const auto t0 = std::chrono::steady_clock::now();
        m.run();
        const double s =
            std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        bare_best = std::min(bare_best, s);
        instr = m.stats().instructions;
        cycles = m.cycles();
    }
    const itlm::TlmRunResult r = itlm::run_tlm(cfg, prog, {}, {}, {}, 0, 0, nullptr, tc);
    if (r.stats.instructions != instr || r.cycles != cycles) {
        std::fprintf(stderr, "mismatch: %llu/%llu instructions\n",
                     static_cast<unsigned long long>(r.stats.instructions),
                     static_cast<unsigned long long>(instr));
        return 1;
    }
    const double bare_ns = bare_best * 1e9 / static_cast<double>(instr);
    const double tlm_ns = r.wall_s * 1e9 / static_cast<double>(instr);
    std::printf("'%s' x 100 per loop\n", insn.c_str());
    std::printf(
        "P=256, %llu instructions, %llu cycles, quantum %.0f ns (%llu syncs, %llu chunks)\n",
        static_cast<unsigned long long>(instr), static_cast<unsigned long long>(cycles),
        r.quantum_ns, static_cast<unsigned long long>(r.syncs),
        static_cast<unsigned long long>(r.chunks));
    std::printf("bare machine: %.2f ns/instruction (best of 3)\n", bare_ns);
    std::printf("run_tlm:      %.2f ns/instruction\n", tlm_ns);
    std::printf("overhead:     %.1f %%\n", (tlm_ns / bare_ns - 1.0) * 100.0);
    return 0;
}
