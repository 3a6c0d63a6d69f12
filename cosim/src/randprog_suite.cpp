// The random suite (run_random_suite): generated programs (generate_program)
// run one after another in one SystemC elaboration through the RTL (or the
// mutation-check model with a planted bug) and, in lockstep, a stepped
// instruction-set model; per program pass or the first divergence or
// failing assertion, and the functional coverage of what ran.
#include <chrono>
#include <memory>

#include "checker.hpp"
#include "imap/rtl/random.hpp"
#include "imap/tlm/sanitizer.hpp"
#include "model.hpp"
#include "support.hpp"

namespace imap::rtl {

SuiteResult run_random_suite(const SuiteOptions& opt) {
    using namespace detail;
    SuiteResult res;
    res.coverage = Coverage(opt.gen.pes);
    isa::MachineConfig base;
    base.pes = opt.gen.pes;
    base.mem_bytes = opt.gen.mem_bytes;
    base.ext_bytes = opt.gen.ext_bytes;
    RtlConfig rc;
    rc.mutant = opt.mutant;
    rc.validate(base);
    check_runnable(base, false, !opt.mutant.empty());
    const ConfigInfo& ci = pick_config(base, rc);
    claim_process("run_random_suite");
    tlm::detail::ElaborationGuard guard;
    Bench bench("top", ci, std::unique_ptr<Model>(ci.make("dut")), nullptr, 40.0);
    const uint32_t mut = opt.mutant.empty() ? 0 : mutant_id(opt.mutant);

    int index = -1;
    RandomProgram cur;
    std::unique_ptr<StepReference> ref;
    std::unique_ptr<Checker> chk;
    Job job;
    int active_before = opt.gen.pes, depth_before = 0;
    const auto t0 = std::chrono::steady_clock::now();
    bench.next_job = [&]() -> Job* {
        if (++index >= opt.programs || (opt.stop_at_divergence && res.caught)) return nullptr;
        cur = generate_program(opt.seed + static_cast<uint64_t>(index), opt.gen);
        job = Job();
        fill_job(job, cur.cfg, cur.prog, cur.params, cur.left, cur.right, cur.out_w, cur.out_h);
        job.mutant = mut;
        if (!opt.lockstep) return &job;  // the RTL alone (its assertions)
        ref = std::make_unique<StepReference>(cur.cfg, cur.prog, cur.params, cur.left, cur.right,
                                              cur.out_w, cur.out_h);
        chk = std::make_unique<Checker>(*ref, cur.prog, cur.cfg.pes);
        chk->reg_every = chk->mem_every = opt.full_compare_every;
        active_before = opt.gen.pes;
        depth_before = 0;
        chk->on_compared = [&](const RetireRecord& r, const isa::Machine& m) {
            res.coverage.sample(r.word, r.pc, active_before, depth_before, m);
            active_before = m.active_pes();
            depth_before = m.mask_stack_size();
        };
        job.listener = chk.get();
        return &job;
    };
    bench.job_done = [&](Job& j) {
        ++res.programs;
        if (j.assertion.valid || !opt.lockstep) {
            // an assertion of the design failed (it stopped the program),
            // or the RTL alone ran: a failure only if an assertion failed
            // or the testbench gave up
            const uint64_t n = j.instructions;
            if (j.assertion.valid || !j.error.empty()) {
                const std::string msg =
                    "program " + std::to_string(index) + " (seed " + std::to_string(cur.seed) +
                    ", ends with " + cur.ending + "): " +
                    (j.assertion.valid ? assertion_divergence(j.assertion, cur.prog).message()
                                       : j.error);
                res.failures.push_back(msg);
                if (!res.caught) {
                    res.caught = true;
                    res.caught_program = index;
                    res.caught_instruction = j.assertion.valid ? j.assertion.index : n;
                    res.instructions_to_catch = res.instructions + res.caught_instruction + 1;
                    res.caught_message = msg;
                    res.caught_assertion = j.assertion.valid ? j.assertion.name : "";
                }
            } else {
                ++res.passed;
            }
            res.instructions += n;
            res.cycles += j.cycles;
            return;
        }
        if (!chk->diverged && j.error.empty())
            chk->final_check(j, bench.shadow(), bench.backdoor());
        if (!chk->diverged && j.error.empty())
            for (int p = 0; p < 2 && !chk->diverged; ++p)
                if (j.output[p].pixels != ref->video().output[p].pixels) {
                    chk->diverged = true;
                    chk->div.what = "video output " + std::to_string(p);
                    chk->div.instruction = j.instructions;
                }
        const uint64_t n = j.instructions;
        if (chk->diverged || !j.error.empty()) {
            const std::string msg = "program " + std::to_string(index) + " (seed " +
                                    std::to_string(cur.seed) + ", ends with " + cur.ending +
                                    "): " + (j.error.empty() ? chk->div.message() : j.error);
            res.failures.push_back(msg);
            if (!res.caught) {
                res.caught = true;
                res.caught_program = index;
                res.caught_instruction = chk->div.instruction;
                res.instructions_to_catch = res.instructions + chk->div.instruction + 1;
                res.caught_message = msg;
            }
        } else {
            ++res.passed;
        }
        res.instructions += n;
        res.cycles += j.cycles;
    };
    sc_core::sc_start();
    imap::tlm::declare_main_stack_to_sanitizer();  // docs/testing.md (ASan and ended SystemC
                                                   // threads)
    res.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return res;
}

}  // namespace imap::rtl
