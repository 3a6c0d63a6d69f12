#include "imap/tlm/cp.hpp"

#include <algorithm>
#include <cstring>
#include <stdexcept>
#include <string>

namespace imap::tlm {

Cp::Cp(sc_core::sc_module_name name, const isa::MachineConfig& cfg, const isa::Program& prog,
       const TlmConfig& tcfg)
    : sc_module(name),
      video("video"),
      mem("mem"),
      m_(std::make_shared<isa::Machine>(cfg)),
      tcfg_(tcfg) {
    tcfg_.validate();
    m_->load(prog);
    period_ = clock_period(cfg);
    period_units_ = period_.value();
    line_.assign(static_cast<size_t>(m_->pes()), 0);
    m_->set_video(this);
    ::tlm::tlm_global_quantum::instance().set(sc_core::sc_time(tcfg_.quantum_ns, sc_core::SC_NS));
    mem.register_invalidate_direct_mem_ptr(this, &Cp::invalidate_dmi);
    SC_THREAD(thread);
    // The machine's fault path builds strings on this stack: be generous.
    set_stack_size(1u << 20);
}

Cp::~Cp() {
    tr_.clear_extension(&ext_);
}

void Cp::invalidate_dmi(sc_dt::uint64 start, sc_dt::uint64 /*end*/) {
    if (start < dmi_end_) {
        dmi_ptr_ = nullptr;
        dmi_end_ = 0;
    }
}

void Cp::acquire_dmi() {
    ::tlm::tlm_generic_payload t;
    t.set_command(::tlm::TLM_WRITE_COMMAND);
    t.set_address(0);
    ::tlm::tlm_dmi dmi;
    const uint64_t need = uint64_t{m_->config().mem_bytes} * static_cast<uint64_t>(m_->pes());
    if (mem->get_direct_mem_ptr(t, dmi) && dmi.is_read_write_allowed() &&
        dmi.get_start_address() == 0 && dmi.get_end_address() + 1 >= need) {
        dmi_ptr_ = dmi.get_dmi_ptr();
        dmi_end_ = need;
    }
}

uint64_t Cp::quantum_end_cycle() const {
    const sc_core::sc_time now = sc_core::sc_time_stamp();
    const sc_core::sc_time next = qk_.next_sync_point();
    uint64_t budget = 1;
    if (next > now) budget = ((next - now).value() + period_units_ - 1) / period_units_;
    return std::max(synced_cycles_ + std::max<uint64_t>(budget, 1), m_->cycles() + 1);
}

void Cp::set_local_time() {
    qk_.set(cycles_to_time(m_->cycles() - synced_cycles_, period_));
}

void Cp::sync_now() {
    qk_.sync();
    synced_cycles_ = m_->cycles();
    ++syncs_;
}

void Cp::start() {
    if (!tcfg_.hosted)
        throw std::logic_error("Cp::start: the CP is not hosted (TlmConfig::hosted)");
    if (busy()) throw std::logic_error("Cp::start: the CP is still running the previous program");
    m_->reset();
    fault_ = nullptr;
    finished_ = false;
    stall_ = sc_core::SC_ZERO_TIME;
    start_pending_ = true;
    start_ev_.notify(sc_core::SC_ZERO_TIME);
}

void Cp::run_program() {
    qk_.reset();
    synced_cycles_ = m_->cycles();
    while (!m_->halted()) {
        ++chunks_;
        m_->run(quantum_end_cycle());
        set_local_time();
        if (qk_.need_sync()) sync_now();
    }
    // Hand the last partial quantum to the kernel: at the end
    // sc_time_stamp() == start + cycles x period (+ video stalls).
    set_local_time();
    sync_now();
    finished_ = true;
}

void Cp::thread() {
    acquire_dmi();
    if (tcfg_.hosted) {
        for (;;) {
            while (!start_pending_) sc_core::wait(start_ev_);
            start_pending_ = false;
            running_ = true;
            try {
                run_program();
            } catch (...) {
                // This run ends; the testbench reads fault() and goes on.
                fault_ = std::current_exception();
                set_local_time();
                sync_now();
            }
            running_ = false;
            done_ev_.notify(sc_core::SC_ZERO_TIME);
        }
    }
    try {
        run_program();
    } catch (...) {
        fault_ = std::current_exception();
        // The fault is reported by whoever catches it; keep the kernel's
        // "Simulation stopped by user." note out of the output.
        sc_core::sc_report_handler::set_actions("/OSCI/SystemC", sc_core::SC_INFO,
                                                sc_core::SC_DO_NOTHING);
        sc_core::sc_stop();
    }
}

// ---------------------------------------------------------------------------
// Video: host <-> line buffer by TLM transactions on `video` (the I/O
// boundary: the quantum keeper synchronises first, so the video source sees
// the modeled time of the vin / vout), line buffer <-> memory row through the
// DMI pointer of top.array.mem.

void Cp::video_transfer(bool write, int port, int y, int x0, uint8_t* data, int n) {
    set_local_time();
    sync_now();
    tr_.set_command(write ? ::tlm::TLM_WRITE_COMMAND : ::tlm::TLM_READ_COMMAND);
    tr_.set_address(static_cast<sc_dt::uint64>(port < 0 ? ~0u : static_cast<unsigned>(port)));
    tr_.set_data_ptr(data);
    tr_.set_data_length(static_cast<unsigned>(n));
    tr_.set_streaming_width(static_cast<unsigned>(n));
    tr_.set_byte_enable_ptr(nullptr);
    tr_.set_byte_enable_length(0);
    tr_.set_dmi_allowed(false);
    tr_.set_response_status(::tlm::TLM_INCOMPLETE_RESPONSE);
    ext_.y = y;
    ext_.x0 = x0;
    ext_.error.clear();
    tr_.set_extension(&ext_);
    // A streamed video source may block in b_transport until the line has
    // arrived, or annotate the wait as a delay: either way the CP stalls.
    const sc_core::sc_time before = sc_core::sc_time_stamp();
    sc_core::sc_time delay = sc_core::SC_ZERO_TIME;
    video->b_transport(tr_, delay);
    tr_.clear_extension(&ext_);
    if (delay != sc_core::SC_ZERO_TIME) sc_core::wait(delay);
    if (sc_core::sc_time_stamp() != before) {
        stall_ += sc_core::sc_time_stamp() - before;
        qk_.reset();  // local time 0 from here; the quantum restarts
        synced_cycles_ = m_->cycles();
    }
    if (tr_.is_response_error())
        throw std::runtime_error(ext_.error.empty()
                                     ? std::string(video.name()) + ": " + tr_.get_response_string()
                                     : ext_.error);
}

void Cp::mem_row(bool write, uint32_t addr, uint8_t* data, int n) {
    const uint64_t a = uint64_t{addr} * static_cast<uint64_t>(n);
    if (dmi_ptr_ && a + static_cast<uint64_t>(n) <= dmi_end_) {
        if (write)
            std::memcpy(dmi_ptr_ + a, data, static_cast<size_t>(n));
        else
            std::memcpy(data, dmi_ptr_ + a, static_cast<size_t>(n));
        return;
    }
    // No DMI: a plain transaction (its delay is part of the video_line cost
    // the machine charges, so it is not added again).
    ::tlm::tlm_generic_payload t;
    t.set_command(write ? ::tlm::TLM_WRITE_COMMAND : ::tlm::TLM_READ_COMMAND);
    t.set_address(a);
    t.set_data_ptr(data);
    t.set_data_length(static_cast<unsigned>(n));
    t.set_streaming_width(static_cast<unsigned>(n));
    t.set_response_status(::tlm::TLM_INCOMPLETE_RESPONSE);
    sc_core::sc_time delay = sc_core::SC_ZERO_TIME;
    mem->b_transport(t, delay);
    if (t.is_response_error())
        throw std::runtime_error(std::string(mem.name()) + ": " + t.get_response_string());
}

bool Cp::read_row(int port, int y, int x0, uint32_t addr, int n) {
    video_transfer(false, port, y, x0, line_.data(), n);
    mem_row(true, addr, line_.data(), n);
    return true;
}

bool Cp::write_row(int port, int y, int x0, uint32_t addr, int n) {
    mem_row(false, addr, line_.data(), n);
    video_transfer(true, port, y, x0, line_.data(), n);
    return true;
}

void Cp::read_line(int port, int y, int x0, uint8_t* dst, int n) {
    video_transfer(false, port, y, x0, dst, n);
}

void Cp::write_line(int port, int y, int x0, const uint8_t* src, int n) {
    line_.assign(src, src + n);
    video_transfer(true, port, y, x0, line_.data(), n);
}

}  // namespace imap::tlm
