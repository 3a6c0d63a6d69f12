#include "imap/tlm/system.hpp"
#include "imap/tlm/sanitizer.hpp"

#include <atomic>
#include <chrono>
#include <cstdio>
#include <stdexcept>

namespace imap::tlm {

detail::ElaborationGuard::ElaborationGuard() {
    if (sc_core::sc_get_status() != sc_core::SC_ELABORATION)
        throw std::logic_error(
            "imap::tlm: a TLM model can only be built while SystemC is elaborating; this process "
            "has already started a simulation (one elaboration per process: run each TLM "
            "simulation in its own process)");
}

TlmSystem::TlmSystem(sc_core::sc_module_name name, const isa::MachineConfig& cfg,
                     const isa::Program& prog, const TlmConfig& tcfg)
    : sc_module(name),
      cp("cp", cfg, prog, tcfg),
      array("array", cp.machine(), cp.period()),
      ring("ring", cp.machine().pes()),
      maskbus("maskbus"),
      video("video") {
    cp.video.bind(video.socket);
    cp.mem.bind(array.mem.socket);
    cp.machine().set_ring(&ring);
    cp.machine().set_status(&maskbus);
}

OutputImages TlmSystem::outputs() const {
    OutputImages o;
    o.image[0] = output(0);
    o.image[1] = output(1);
    return o;
}

void TlmSystem::rethrow_if_faulted() const {
    if (cp.fault()) std::rethrow_exception(cp.fault());
}

TlmRunResult TlmSystem::result() const {
    const isa::Machine& m = cp.machine();
    TlmRunResult r;
    static_cast<isa::ModelRun&>(r) = isa::model_run_of(m);
    r.ring = ring.stats();
    r.maskbus = maskbus.stats();
    for (isa::Op o : {isa::Op::MIF, isa::Op::MELSE, isa::Op::MEND, isa::Op::MALL})
        r.maskbus.mask_commands += m.stats().op_counts[static_cast<uint8_t>(o)];
    r.video = video.stats();
    r.syncs = cp.syncs();
    r.chunks = cp.chunks();
    r.quantum_ns = ::tlm::tlm_global_quantum::instance().get().to_seconds() * 1e9;
    r.sim_time_s = sc_core::sc_time_stamp().to_seconds();
    r.video_dmi = cp.used_dmi();
    r.machine = cp.machine_ptr();
    return r;
}

TlmRunResult run_tlm(const isa::MachineConfig& cfg, const isa::Program& prog,
                     const std::vector<std::pair<int, uint32_t>>& params, const ImageInput& left,
                     const ImageInput& right, int out_w, int out_h, OutputImages* out,
                     const TlmConfig& tcfg) {
    static std::atomic<bool> used{false};
    if (used.exchange(true))
        throw std::logic_error(
            "run_tlm: called a second time in this process; SystemC elaborates once per process, "
            "so run each TLM simulation in its own process");
    auto sys = std::make_unique<TlmSystem>("top", cfg, prog, tcfg);
    for (const auto& [i, v] : params) sys->set_param(i, v);
    sys->set_input(0, left);
    sys->set_input(1, right);
    sys->make_output(0, out_w, out_h);
    sys->make_output(1, out_w, out_h);
    if (tcfg.observer) sys->machine().set_observer(tcfg.observer);
    const auto t0 = std::chrono::steady_clock::now();
    sc_core::sc_start();
    imap::tlm::declare_main_stack_to_sanitizer();
    const auto t1 = std::chrono::steady_clock::now();
    sys->rethrow_if_faulted();
    if (!sys->cp.finished())
        throw std::runtime_error("run_tlm: the simulation ended before the program halted");
    TlmRunResult r = sys->result();
    r.wall_s = std::chrono::duration<double>(t1 - t0).count();
    if (out) *out = sys->outputs();
    return r;
}

}  // namespace imap::tlm

// libsystemc refers to sc_main (its own main() calls it). Programs that use
// the model from their own main() -- the tools, the Boost.Test executables --
// have none; this weak definition satisfies the linker and yields to a real
// sc_main wherever one is defined.
extern "C" __attribute__((weak)) int sc_main(int, char**) {
    std::fprintf(stderr,
                 "imap_tlm: this program has no sc_main; call imap::tlm::run_tlm from main()\n");
    return 1;
}
