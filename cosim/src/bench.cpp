#include "bench.hpp"

#include "imap/tlm/sanitizer.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <stdexcept>

namespace imap::rtl::detail {

void set_dpi_bench(Bench* b);  // dpi.cpp

const char* fault_code_name(int code) {
    static const char* const n[] = {"none",
                                    "illegal instruction",
                                    "PC past the end of the program",
                                    "watchdog",
                                    "local memory address",
                                    "per-PE address",
                                    "param-block address",
                                    "mask stack overflow",
                                    "mask stack underflow",
                                    "return stack overflow",
                                    "return stack underflow",
                                    "no external memory",
                                    "negative transfer length",
                                    "transfer local range",
                                    "transfer external range",
                                    "video port missing",
                                    "video line outside the image",
                                    "video row address"};
    return code >= 0 && code < static_cast<int>(sizeof n / sizeof n[0]) ? n[code] : "?";
}

void Shadow::reset(int P_, int NR_, uint32_t mem_bytes_, uint32_t ext_bytes_) {
    P = P_;
    NR = NR_;
    mem_bytes = mem_bytes_;
    ext_bytes = ext_bytes_;
    creg.fill(0);
    param.fill(0);
    msp = csp = 0;
    phase = 0;
}

RtlStateData read_state(const Backdoor& b, int pe_regs) {
    RtlStateData s;
    const size_t P = static_cast<size_t>(b.P);
    s.pes = b.P;
    s.pe_regs = pe_regs;
    s.lanes.assign((static_cast<size_t>(pe_regs) + 3) * P, 0);
    for (size_t p = 0; p < P; ++p) {
        for (int r = 0; r < pe_regs; ++r) s.lanes[static_cast<size_t>(r) * P + p] = b.regs[p][r];
        s.lanes[static_cast<size_t>(pe_regs) * P + p] = *b.carry[p] & 1u;
        s.lanes[static_cast<size_t>(pe_regs + 1) * P + p] = (*b.st[p] >> 1) & 1u;
        s.lanes[static_cast<size_t>(pe_regs + 2) * P + p] = *b.st[p] & 1u;
    }
    s.mem.assign(static_cast<size_t>(b.mem_bytes) * P, 0);
    for (size_t p = 0; p < P; ++p)
        for (uint32_t a = 0; a < b.mem_bytes; ++a) s.mem[a * P + p] = b.mem[p][a];
    s.ext.assign(b.ext, b.ext + static_cast<size_t>(b.ext_bytes) * P);
    std::copy(b.creg, b.creg + 16, s.creg.begin());
    std::copy(b.param, b.param + 256, s.param.begin());
    s.msp = *b.msp;
    s.csp = *b.csp;
    s.phase = *b.phase;
    return s;
}

Bench::Bench(sc_core::sc_module_name name, const ConfigInfo& cfg, std::unique_ptr<Model> dut,
             std::unique_ptr<Model> replay, double clock_mhz)
    : sc_core::sc_module(name), cfg_(cfg), replay_(replay != nullptr) {
    // half a period in ps (the default SystemC resolution)
    half_ps_ = std::max<uint64_t>(1, static_cast<uint64_t>(std::llround(5e5 / clock_mhz)));
    main_.ports = std::make_unique<Ports>("ports");
    main_.model = std::move(dut);
    main_.model->bind(*main_.ports);
    main_.bd = main_.model->backdoor();
    main_.bd.ext_bytes = cfg.ext_bytes;
    if (replay) {
        rep_.ports = std::make_unique<Ports>("replay_ports");
        rep_.model = std::move(replay);
        rep_.model->bind(*rep_.ports);
        rep_.bd = rep_.model->backdoor();
        rep_.bd.ext_bytes = cfg.ext_bytes;
    }
    dut_ = main_.model.get();
    bd_ = main_.bd;
    SC_THREAD(control);
    SC_METHOD(clock);
}

Bench::~Bench() {
    set_dpi_bench(nullptr);
}

void Bench::drive_straps(Ports& p, const Job& j) {
    const isa::CostTable& c = j.cfg.costs;
    p.c_alu = c.alu;
    p.c_mem = c.mem;
    p.c_indirect_extra = c.indirect_extra;
    p.c_ring_hop = c.ring_hop;
    p.c_mask = c.mask;
    p.c_status = c.status;
    p.c_cp = c.cp;
    p.c_branch_taken = c.branch_taken;
    p.c_video_line = c.video_line;
    p.c_xfer_setup = c.xfer_setup;
    p.c_ext_bpc = c.ext_bytes_per_cycle;
    p.c_ext_beat = c.ext_beat;
    p.c_shift_bits = c.shift_bits;
    p.c_minmax_extra = c.minmax_extra;
    p.cfg_prog_len = static_cast<uint32_t>(j.prog->code.size());
    p.cfg_pe_regs = static_cast<uint32_t>(j.cfg.pe_regs);
    p.cfg_mask_depth = static_cast<uint32_t>(j.cfg.mask_depth);
    p.cfg_call_depth = static_cast<uint32_t>(j.cfg.call_depth);
    p.cfg_indirect = j.cfg.indirect;
    p.cfg_ext_on = j.cfg.ext_bytes != 0;
    p.cfg_watchdog = j.cfg.watchdog_cycles;
    p.cfg_trace = j.listener != nullptr;
    p.mutant = j.mutant;
}

void Bench::clear_state(Backdoor& b) {
    for (const Backdoor::PeMem& m : b.mem)
        for (uint8_t* bank : m.bank) std::memset(bank, 0, m.bank_bytes);
    std::memset(b.ext, 0, static_cast<size_t>(b.ext_bytes) * b.P);
}

// The longest any one instruction can take with this cost table: the
// bench's bound for "the model stopped making progress".
static uint64_t max_instruction_cycles(const isa::MachineConfig& cfg) {
    const isa::CostTable& c = cfg.costs;
    uint64_t m =
        std::max<uint64_t>({c.cp, c.alu + 6ull, c.alu + uint64_t{c.minmax_extra},
                            c.mem + uint64_t{c.indirect_extra}, c.mask, c.status, c.video_line});
    m = std::max<uint64_t>(m, 65535ull * c.ring_hop);
    m = std::max<uint64_t>(m, c.xfer_cycles(cfg.mem_bytes, static_cast<uint64_t>(cfg.pes)));
    return m + c.branch_taken;
}

void Bench::run_job(Slot& s, Job& j, bool replay) {
    active_ = &s;
    dut_ = s.model.get();
    bd_ = s.bd;
    job_ = &j;
    tracing_ = j.listener != nullptr && !replay;
    stop_ = false;
    pending_ = pending_fault_ = false;
    touched_.clear();
    set_dpi_bench(this);
    Ports& p = *s.ports;
    drive_straps(p, j);
    if (replay) p.cfg_trace = false;
    p.rst_n = false;
    clear_state(s.bd);
    shadow_.reset(s.bd.P, j.cfg.pe_regs, s.bd.mem_bytes, s.bd.ext_bytes);
    for (const auto& [i, v] : j.params) shadow_.param[static_cast<size_t>(i)] = v;
    cycle_budget_ = j.cfg.watchdog_cycles + max_instruction_cycles(j.cfg) + 16;
    clock_ev_.notify(sc_core::SC_ZERO_TIME);
    // host port: the program, then all 256 param words
    wait(p.clk.posedge_event());
    p.host_we = true;
    p.host_sel = false;
    for (size_t i = 0; i < j.prog->code.size(); ++i) {
        p.host_addr = static_cast<uint32_t>(i);
        p.host_data = j.prog->code[i];
        wait(p.clk.posedge_event());
    }
    p.host_sel = true;
    for (int i = 0; i < 256; ++i) {
        p.host_addr = static_cast<uint32_t>(i);
        p.host_data = shadow_.param[static_cast<size_t>(i)];
        wait(p.clk.posedge_event());
    }
    p.host_we = false;
    wait(p.clk.posedge_event());
    wait(p.clk.posedge_event());
    // run
    // The waves' time axis starts where the machine does (reset released,
    // cycle 0), not at the program load before it: the TLM's waves start
    // there too, so a window lines up in both (docs/waves.md).
    run_start_ps_ = sc_core::sc_time_stamp().value();
    dumps_ = 0;
    if (!j.waves_path.empty() && j.waves_t0 == 0) {
        s.model->trace_open(j.waves_path + ".part", j.waves_scopes);
        waves_on_ = true;
        j.waves_written = true;
        j.waves_open_ps = 0;
    }
    const auto t0 = std::chrono::steady_clock::now();
    const uint64_t c0 = clocks_;
    last_progress_ = clocks_;
    last_mcycle_ = last_instret_ = 0;
    p.rst_n = true;
    while (!p.done.read() && !stop_ && j.error.empty()) wait(p.done.posedge_event() | finished_ev_);
    while ((pending_ || pending_fault_) && !stop_ && j.error.empty()) wait(processed_ev_);
    j.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    j.clocks = clocks_ - c0;
    j.stopped = stop_;
    j.halted = *s.bd.halted != 0;
    j.cycles = *s.bd.mcycle;
    j.instructions = *s.bd.instret;
    if (*s.bd.faulted) {
        j.fault.valid = true;
        j.fault.code = *s.bd.f_code;
        j.fault.pc = *s.bd.f_pc;
        j.fault.cycle = *s.bd.f_cyc;
        j.fault.pe = *s.bd.f_pe == 0xFFFFFFFFu ? -1 : static_cast<int64_t>(*s.bd.f_pe);
        j.fault.address = static_cast<int64_t>(*s.bd.f_addr);
    }
    // one more clock so that the waves show the final state
    wait(p.clk.posedge_event());
    if (waves_on_) {
        s.model->trace_close();
        waves_on_ = false;
    }
    // A window that starts after the end of the run: a valid trace of one
    // sample (the final state) at the end, as the TLM's empty trace is
    // valid; the caller warns that it is empty.
    if (!j.waves_path.empty() && !j.waves_written && j.error.empty() &&
        s.model->trace_format() != TraceFormat::None) {
        const uint64_t now = sc_core::sc_time_stamp().value();
        s.model->trace_open(j.waves_path + ".part", j.waves_scopes);
        s.model->trace_dump(now > run_start_ps_ ? now - run_start_ps_ : 0);
        s.model->trace_close();
        j.waves_written = true;
        j.waves_empty = true;
        j.waves_open_ps = now > run_start_ps_ ? now - run_start_ps_ : 0;
    }
    // the design stays halted (not reset) until the next job: its final
    // state is read after the simulation
    job_ = nullptr;
    tracing_ = false;
}

void Bench::control() {
    for (;;) {
        Job* j = next_job ? next_job() : nullptr;
        if (!j) break;
        run_job(main_, *j, false);
        if (job_done) job_done(*j);
    }
    active_ = nullptr;
    set_dpi_bench(nullptr);
    // the end of the jobs, not news: keep the kernel's "stopped by user" out
    sc_core::sc_report_handler::set_actions("/OSCI/SystemC", sc_core::SC_INFO,
                                            sc_core::SC_DO_NOTHING);
    sc_core::sc_stop();
}

void Bench::replay_waves(Job& job) {
    if (!replay_) return;
    Job r;
    r.cfg = job.cfg;
    r.prog = job.prog;
    r.params = job.params;
    r.input[0] = job.input[0];
    r.input[1] = job.input[1];
    r.output[0] = job.output[0];
    r.output[1] = job.output[1];
    r.attached[0] = job.attached[0];
    r.attached[1] = job.attached[1];
    r.mutant = job.mutant;
    r.waves_path = job.waves_path;
    r.waves_scopes = job.waves_scopes;
    r.waves_t0 = job.waves_t0;
    r.waves_t1 = job.waves_t1;
    run_job(rep_, r, true);
    job.waves_written = r.waves_written;
    job.waves_open_ps = r.waves_open_ps;
    if (!r.error.empty() && job.error.empty()) job.error = r.error;
    active_ = &main_;
    dut_ = main_.model.get();
    bd_ = main_.bd;
}

void Bench::check_progress(Slot& s, Job& j) {
    const uint64_t mc = *s.bd.mcycle, ir = *s.bd.instret;
    if (mc != last_mcycle_ || ir != last_instret_) {
        last_mcycle_ = mc;
        last_instret_ = ir;
        last_progress_ = clocks_;
    } else if (s.ports->rst_n.read() && clocks_ - last_progress_ > (1u << 20)) {
        j.error =
            "the RTL model stopped making progress (no machine cycle and no retired "
            "instruction in 2^20 clocks, machine cycle " +
            std::to_string(mc) + ")";
        finished_ev_.notify(sc_core::SC_ZERO_TIME);
    }
    if (mc > cycle_budget_) {
        j.error = "the RTL model ran past the watchdog (machine cycle " + std::to_string(mc) +
                  ", watchdog " + std::to_string(j.cfg.watchdog_cycles) + ")";
        finished_ev_.notify(sc_core::SC_ZERO_TIME);
    }
}

bool Bench::process_pending() {
    Listener* l = job_ ? job_->listener : nullptr;
    if (pending_) {
        Listener::Verdict v =
            l ? l->on_retire(pending_rec_, shadow_, bd_, touched_) : Listener::Verdict::Go;
        if (v == Listener::Verdict::Wait) return false;
        pending_ = false;
        touched_.clear();
        if (v == Listener::Verdict::Stop) {
            stop_ = true;
            finished_ev_.notify(sc_core::SC_ZERO_TIME);
        }
    }
    if (pending_fault_) {
        Listener::Verdict v = l ? l->on_fault(fault_rec_, shadow_) : Listener::Verdict::Go;
        if (v == Listener::Verdict::Wait) return false;
        pending_fault_ = false;
        if (v == Listener::Verdict::Stop) {
            stop_ = true;
            finished_ev_.notify(sc_core::SC_ZERO_TIME);
        }
    }
    processed_ev_.notify(sc_core::SC_ZERO_TIME);
    return true;
}

// The clock: one process toggling the active model's clock every half
// period. After a rising edge has been evaluated it processes the trace
// port; a checker may hold the clock there until the reference catches up.
void Bench::clock() {
    imap::tlm::declare_main_stack_to_sanitizer();  // the reference's faults are thrown here
    if (!active_) {
        next_trigger(clock_ev_);
        return;
    }
    Slot& s = *active_;
    const uint64_t now = sc_core::sc_time_stamp().value();  // ps
    if (job_ && !job_->waves_path.empty() && s.model->trace_format() != TraceFormat::None) {
        const uint64_t mc = *s.bd.mcycle;
        // the edge just evaluated, on the waves' time axis (0 = reset released)
        const uint64_t edge = now > half_ps_ ? now - half_ps_ : 0;
        const uint64_t t = edge > run_start_ps_ ? edge - run_start_ps_ : 0;
        if (!waves_on_ && mc >= job_->waves_t0 && s.ports->rst_n.read() && !job_->waves_written) {
            s.model->trace_open(job_->waves_path + ".part", job_->waves_scopes);
            waves_on_ = true;
            job_->waves_written = true;
            job_->waves_open_ps = t;
        }
        if (waves_on_) {
            s.model->trace_dump(t);
            // --trace-limit-mb: the file's size, every 256 dumps (the FST
            // writer buffers, so it stops at about the limit)
            bool limit = false;
            if (job_->waves_limit_bytes && (++dumps_ & 255u) == 0) {
                std::error_code ec;
                const auto size = std::filesystem::file_size(job_->waves_path + ".part", ec);
                limit = !ec && size > job_->waves_limit_bytes;
            }
            if (mc > job_->waves_t1 || limit) {
                s.model->trace_close();
                waves_on_ = false;
                job_->waves_limited = limit;
            }
        }
    }
    if (level_) {
        if ((pending_ || pending_fault_) && job_ && job_->assertion.valid) {
            // an assertion failed at this edge: it is the report, not what
            // the edge retired (the job stops)
            pending_ = pending_fault_ = false;
            processed_ev_.notify(sc_core::SC_ZERO_TIME);
        } else if (pending_ || pending_fault_) {
            if (!process_pending()) {
                const sc_core::sc_event* ev =
                    job_ && job_->listener ? job_->listener->wake_event() : nullptr;
                if (ev)
                    next_trigger(*ev);
                else
                    next_trigger(sc_core::sc_time(static_cast<double>(half_ps_), sc_core::SC_PS));
                return;
            }
        }
        s.ports->clk = false;
        level_ = false;
    } else {
        pre_mcycle_ = *s.bd.mcycle;
        pre_instret_ = *s.bd.instret;
        pre_pc_ = *s.bd.x_pc;
        s.ports->clk = true;
        level_ = true;
        ++clocks_;
        if ((clocks_ & 4095u) == 0 && job_) check_progress(s, *job_);
    }
    next_trigger(sc_core::sc_time(static_cast<double>(half_ps_), sc_core::SC_PS));
}

// ---------------------------------------------------------------------------
// The trace port and the video port (called from the design via dpi.cpp)

void Bench::dpi_retire(const RetireRecord& r) {
    if (!tracing_) return;
    if (r.creg >= 0) shadow_.creg[static_cast<size_t>(r.creg)] = r.cval;
    shadow_.msp = r.msp;
    shadow_.csp = r.csp;
    shadow_.phase = r.phase;
    pending_rec_ = r;
    pending_ = true;
}

void Bench::dpi_param(int addr, uint32_t v) {
    if (!tracing_ || addr < 0 || addr > 255) return;
    shadow_.param[static_cast<size_t>(addr)] = v;
    touched_.param = true;
}

void Bench::dpi_fault(const FaultRecord& f) {
    if (!tracing_) return;
    fault_rec_ = f;
    fault_rec_.index = *bd_.instret;
    pending_fault_ = true;
}

void Bench::dpi_assert(const char* name, int pe) {
    // the first failure of a running job stops it; later ones (the design
    // runs on for a clock or two while the job winds down) are not news
    if (!job_ || job_->assertion.valid) return;
    AssertionRecord& a = job_->assertion;
    a.valid = true;
    a.name = name ? name : "?";
    a.pe = pe;
    a.cycle = pre_mcycle_;
    a.index = pre_instret_;
    a.pc = pre_pc_ & 0xFFFFFFu;
    stop_ = true;
    finished_ev_.notify(sc_core::SC_ZERO_TIME);
}

int Bench::dpi_vid_check(int dir_out, int port, int y) {
    if (!job_ || port < 0 || port > 1) return 1;
    const Image& im = dir_out ? job_->output[port] : job_->input[port];
    if ((!dir_out && !job_->attached[port]) || im.width <= 0) return 1;
    if (y < 0 || y >= im.height) return 2;
    return 0;
}

int Bench::dpi_vid_pixel(int port, int y, int x) {
    if (!job_ || port < 0 || port > 1) return 0;
    const Image& im = job_->input[port];
    if (y < 0 || y >= im.height || x < 0 || x >= im.width) return 0;
    return im
        .pixels[static_cast<size_t>(y) * static_cast<size_t>(im.width) + static_cast<size_t>(x)];
}

// The board's camera: the same timing as the instruction-set model's video
// port (isa::BoardTiming, a board part outside the chip).
uint64_t Bench::dpi_vid_ready(int port, int y, int x) {
    if (!job_ || port < 0 || port > 1) return 0;
    return job_->cfg.camera_ready_cycle(job_->input[port].width, y, x, job_->cfg.pes);
}

void Bench::dpi_vid_put(int port, int y, int x, int v) {
    if (!job_ || port < 0 || port > 1) return;
    Image& im = job_->output[port];
    if (y < 0 || y >= im.height || x < 0 || x >= im.width) return;
    im.pixels[static_cast<size_t>(y) * static_cast<size_t>(im.width) + static_cast<size_t>(x)] =
        static_cast<uint8_t>(v);
}

}  // namespace imap::rtl::detail
