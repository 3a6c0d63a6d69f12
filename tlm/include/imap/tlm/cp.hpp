// top.cp: the control processor, the only active component of the TLM model.
//
// It owns the isa::Machine (the one implementation of the instruction
// semantics) and runs it in one SC_THREAD: the machine executes broadcast
// instructions in chunks of up to one quantum of cycles (Machine::run with a
// cycle limit), and a tlm_utils::tlm_quantumkeeper turns the cycles into
// local time and synchronises with the kernel at quantum ends and at every
// video line transfer (the I/O boundary). No process per PE, none per cycle.
#pragma once

#include <tlm_utils/simple_initiator_socket.h>
#include <tlm_utils/tlm_quantumkeeper.h>
#include <cstdint>
#include <exception>
#include <memory>
#include <systemc>
#include <tlm>
#include <vector>

#include "imap/isa/machine.hpp"
#include "imap/tlm/components.hpp"
#include "imap/tlm/config.hpp"

namespace imap::tlm {

class Cp : public sc_core::sc_module, private isa::VideoPort {
  public:
    // Video lines to / from the host (bind to top.video.socket).
    tlm_utils::simple_initiator_socket<Cp> video;
    // The PE memories as one address-major block (bind to top.array.mem's
    // socket); used for its DMI pointer: a video line goes into one row.
    tlm_utils::simple_initiator_socket<Cp> mem;

    SC_HAS_PROCESS(Cp);
    // Builds and loads the machine (isa::ConfigError / LoadError).
    Cp(sc_core::sc_module_name name, const isa::MachineConfig& cfg, const isa::Program& prog,
       const TlmConfig& tcfg);
    ~Cp() override;
    const char* kind() const override { return "imap::tlm::Cp"; }

    isa::Machine& machine() { return *m_; }
    const isa::Machine& machine() const { return *m_; }
    std::shared_ptr<const isa::Machine> machine_ptr() const { return m_; }
    const sc_core::sc_time& period() const { return period_; }
    const TlmConfig& tlm_config() const { return tcfg_; }

    // The exception that ended the (last) run (an isa::Fault, ...), or null.
    std::exception_ptr fault() const { return fault_; }
    bool finished() const { return finished_; }

    // Hosted mode (TlmConfig::hosted): resets the machine (Machine::reset:
    // state, memories, counters; program and param block kept) and starts
    // one run of the program; done_event() is notified when it halts or
    // faults. std::logic_error if not hosted or still busy.
    void start();
    bool busy() const { return start_pending_ || running_; }
    const sc_core::sc_event& done_event() const { return done_ev_; }
    // Modeled time the CP spent waiting for video lines that had not yet
    // arrived (streamed input), in the current / last run. The machine's
    // cycle count does not include it [A: the CP stalls, the array idles].
    sc_core::sc_time video_stall() const { return stall_; }
    // Width of input image `port` for a timed camera (camera_pixel_mhz):
    // TlmSystem::set_input tells it.
    void set_input_width(int port, int width) {
        if (port == 0 || port == 1) in_width_[port] = width;
    }
    uint64_t syncs() const { return syncs_; }    // quantum keeper synchronisations
    uint64_t chunks() const { return chunks_; }  // Machine::run calls
    bool used_dmi() const { return dmi_ptr_ != nullptr; }

  private:
    // A quantum keeper that also tells where the current quantum ends.
    struct QuantumKeeper : tlm_utils::tlm_quantumkeeper {
        sc_core::sc_time next_sync_point() const { return m_next_sync_point; }
    };

    void thread();
    // Runs the loaded program to halt (or fault) under the quantum keeper.
    void run_program();
    void acquire_dmi();
    void invalidate_dmi(sc_dt::uint64 start, sc_dt::uint64 end);
    // Local time = cycles executed since the last synchronisation.
    void set_local_time();
    void sync_now();
    uint64_t quantum_end_cycle() const;

    // isa::VideoPort (the machine's vin / vout land here).
    void read_line(int port, int y, int x0, uint8_t* dst, int n) override;
    void write_line(int port, int y, int x0, const uint8_t* src, int n) override;
    bool read_row(int port, int y, int x0, uint32_t addr, int n) override;
    bool write_row(int port, int y, int x0, uint32_t addr, int n) override;
    int input_width(int port) const override {
        return port == 0 || port == 1 ? in_width_[port] : -1;
    }
    // One line transaction on `video` (after synchronising time).
    void video_transfer(bool write, int port, int y, int x0, uint8_t* data, int n);
    void mem_row(bool write, uint32_t addr, uint8_t* data, int n);

    std::shared_ptr<isa::Machine> m_;
    TlmConfig tcfg_;
    sc_core::sc_time period_;
    uint64_t period_units_ = 0;  // period in time-resolution units
    QuantumKeeper qk_;
    uint64_t synced_cycles_ = 0;  // machine cycles at the last synchronisation
    std::vector<uint8_t> line_;   // the video line buffer
    int in_width_[2] = {-1, -1};  // input image widths (set_input_width)
    uint8_t* dmi_ptr_ = nullptr;  // DMI of the local-memory block, or null
    uint64_t dmi_end_ = 0;
    ::tlm::tlm_generic_payload tr_;
    VideoLine ext_;
    std::exception_ptr fault_;
    bool finished_ = false;
    bool start_pending_ = false, running_ = false;
    sc_core::sc_event start_ev_, done_ev_;
    sc_core::sc_time stall_;
    uint64_t syncs_ = 0, chunks_ = 0;
};

}  // namespace imap::tlm
