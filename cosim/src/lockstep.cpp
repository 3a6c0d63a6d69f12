#include "imap/rtl/lockstep.hpp"
#include "imap/tlm/sanitizer.hpp"

#include <chrono>
#include <sstream>
#include <stdexcept>

#include "checker.hpp"
#include "support.hpp"

namespace imap::rtl {

std::string Divergence::message() const {
    std::ostringstream o;
    if (!assertion.empty()) {
        o << "RTL assertion " << assertion << " failed at instruction " << instruction << " (cycle "
          << cycle << ", pc " << pc << ": " << disassembly << ")";
        if (pe >= 0) o << " in PE " << pe;
        o << ": " << what;
        if (!waves.empty()) o << "; " << waves;
        return o.str();
    }
    o << "lockstep divergence at instruction " << instruction << " (cycle " << cycle << ", pc "
      << pc << ": " << disassembly << "): " << what;
    if (pe >= 0) o << " of PE " << pe;
    if (address >= 0) o << " at address " << address;
    o << ": " << reference << " " << tlm_value << ", RTL " << rtl_value;
    if (!detail.empty()) o << " (" << detail << ")";
    if (!waves.empty()) o << "; " << waves;
    return o.str();
}

void LockstepConfig::validate(const isa::MachineConfig& cfg) const {
    rtl.validate(cfg);
    if (!rtl.waves.path.empty())
        throw isa::ConfigError(
            "lockstep: waves of the design are written on a divergence only "
            "(trace the models one at a time)");
    if (waves_cycles == 0 || waves_cycles > 100000000)
        throw isa::ConfigError("lockstep: waves_cycles = " + std::to_string(waves_cycles) +
                               " out of range (1..100000000)");
}

LockstepResult run_lockstep(const isa::MachineConfig& cfg, const isa::Program& prog,
                            const std::vector<std::pair<int, uint32_t>>& params,
                            const ImageInput& left, const ImageInput& right, int out_w, int out_h,
                            OutputImages* out, const LockstepConfig& lcfg) {
    using namespace detail;
    cfg.validate();
    lcfg.validate(cfg);
    check_runnable(cfg, false, !lcfg.rtl.mutant.empty(), prog.code.size(), prog.phases.size());
    const ConfigInfo& ci = pick_config(cfg, lcfg.rtl);
    const std::string& wpath = lcfg.divergence_waves;
    const int wformat = waves_format(wpath);
    // the replay that writes the waves runs the same model (with the same
    // planted bug for the mutation check)
    const ConfigInfo* replay =
        wformat == 0 ? nullptr : traced_config(cfg, wformat, !lcfg.rtl.mutant.empty());
    claim_process("run_lockstep");

    tlm::TlmConfig tc;
    tc.hosted = true;
    tc.quantum_ns = 1e9;  // the checker meets the TLM model at every instruction
    tlm::TlmSystem sys("tlm", cfg, prog, tc);
    for (const auto& [i, v] : params) sys.set_param(i, v);
    sys.set_input(0, left);
    sys.set_input(1, right);
    sys.make_output(0, out_w, out_h);
    sys.make_output(1, out_w, out_h);
    TlmReference ref("ref", sys);
    std::unique_ptr<Model> dut(ci.make("dut"));
    std::unique_ptr<Model> rep(replay ? replay->make("replay") : nullptr);
    Bench bench("rtl", ci, std::move(dut), std::move(rep), cfg.clock_mhz);
    Checker chk(ref, prog, cfg.pes);
    chk.reg_every = chk.mem_every = lcfg.full_compare_every;
    Job job;
    fill_job(job, cfg, prog, params, left, right, out_w, out_h);
    job.listener = &chk;
    job.mutant = lcfg.rtl.mutant.empty() ? 0 : mutant_id(lcfg.rtl.mutant);
    if (lcfg.rtl.inject.enabled)
        chk.after_compare = [&](const RetireRecord& r) {
            if (r.index == lcfg.rtl.inject.instruction) inject(bench.backdoor(), lcfg.rtl.inject);
        };
    int calls = 0;
    bench.next_job = [&]() -> Job* {
        if (calls++ == 0) return &job;
        // let the TLM model finish its run after the halt
        for (int i = 0; i < 1000 && !chk.diverged && !ref.finished(); ++i)
            sc_core::wait(sc_core::sc_time(1, sc_core::SC_US));
        return nullptr;
    };
    RtlRunResult rres;
    bench.job_done = [&](Job& j) {
        rres = collect(j, bench, cfg, prog);
        if (j.assertion.valid && !chk.diverged) {
            chk.diverged = true;
            chk.div = assertion_divergence(j.assertion, prog);
        }
        if (!chk.diverged) return;
        if (!replay) {
            if (wpath.empty())
                chk.div.waves = "";
            else if (!lcfg.rtl.mutant.empty())
                chk.div.waves =
                    std::string("no waves: the mutation-check model of this build has no ") +
                    (wformat == 2 ? "FST" : "VCD") + "-traced variant (FST: IMAP_RTL_FST_ALL=ON)";
            else
                chk.div.waves = std::string("no waves: configuration ") + ci.name + " has no " +
                                (wformat == 2 ? "FST" : "VCD") +
                                "-traced variant (build one: " + build_command(cfg, wformat) + ")";
            return;
        }
        j.waves_path = wpath;
        j.waves_scopes = {"replay.imap_tb"};
        j.waves_t1 = chk.div.cycle;
        j.waves_t0 = chk.div.cycle > lcfg.waves_cycles ? chk.div.cycle - lcfg.waves_cycles : 0;
        j.listener = nullptr;
        bench.replay_waves(j);
        j.listener = &chk;
    };
    const auto t0 = std::chrono::steady_clock::now();
    sc_core::sc_start();
    imap::tlm::declare_main_stack_to_sanitizer();  // docs/testing.md (ASan and ended SystemC
                                                   // threads)
    const double wall =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (!job.error.empty()) throw std::runtime_error("RTL testbench: " + job.error);
    if (chk.diverged && job.waves_written) {
        finish_waves(
            job, bench, cfg, "replay",
            chk.div.pe >= 0 ? std::vector<int>{static_cast<int>(chk.div.pe)} : std::vector<int>{});
        chk.div.waves = "waves of machine cycles " + std::to_string(job.waves_t0) + ".." +
                        std::to_string(job.waves_t1) + " -> " + wpath;
    }
    if (!chk.diverged) {
        chk.final_check(job, bench.shadow(), bench.backdoor());
        if (!chk.diverged)
            for (int p = 0; p < 2 && !chk.diverged; ++p)
                if (sys.output(p).pixels != job.output[p].pixels) {
                    const auto& a = sys.output(p).pixels;
                    const auto& b = job.output[p].pixels;
                    for (size_t i = 0; i < a.size() && i < b.size(); ++i)
                        if (a[i] != b[i]) {
                            chk.diverged = true;
                            Divergence& d = chk.div;
                            d.instruction = job.instructions;
                            d.cycle = job.cycles;
                            d.what = "video output " + std::to_string(p) + " pixel (" +
                                     std::to_string(i % static_cast<size_t>(out_w)) + "," +
                                     std::to_string(i / static_cast<size_t>(out_w)) + ")";
                            d.tlm_value = a[i];
                            d.rtl_value = b[i];
                            d.disassembly = "end of run";
                            break;
                        }
                }
    }
    LockstepResult r;
    r.diverged = chk.diverged;
    r.divergence = chk.div;
    r.compared = chk.compared;
    r.instructions = job.instructions;
    r.tlm = sys.result();
    r.rtl = rres;
    r.rtl.wall_s = wall;
    r.wall_s = wall;
    if (!r.diverged && ref.fault()) throw *ref.fault();
    if (!r.diverged && !ref.error().empty()) throw std::runtime_error(ref.error());
    if (out) *out = sys.outputs();
    return r;
}

}  // namespace imap::rtl
