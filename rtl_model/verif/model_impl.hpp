// ModelImpl<V, Trace>: the Model of one verilated configuration (V is the
// Verilator --sc class, e.g. Vimap_p256_m1024_x65536_fast). Included only by
// the generated per-configuration factories (rtl_model/CMakeLists.txt).
#pragma once

#include <cstdlib>
#include <stdexcept>
#include <string>
#include <type_traits>

#include "model.hpp"
#include "verilated.h"
#include "verilated_fst_c.h"
#include "verilated_syms.h"
#include "verilated_vcd_c.h"
#if VM_COVERAGE
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#include "verilated_cov.h"
#endif

namespace imap::rtl::detail {

#if VM_COVERAGE
// Coverage build (IMAP_RTL_COVERAGE, scripts/rtl-coverage.sh): when a model
// is destroyed, the design's line, branch and toggle counts of this process
// are written to $IMAP_RTL_COVERAGE_DIR/cov-PID-N.dat (nothing without the
// variable) and the coverage items are dropped: they point into the models'
// counters, which go with them. Models of one process are destroyed after
// their simulation, so the first writes all of them.
inline void write_coverage() {
    static int n = 0;
    const char* dir = std::getenv("IMAP_RTL_COVERAGE_DIR");
    VerilatedCovContext* cov = Verilated::threadContextp()->coveragep();
    if (dir != nullptr && *dir != '\0') {
        const std::string path = std::string(dir) + "/cov-" +
                                 std::to_string(static_cast<long>(::getpid())) + "-" +
                                 std::to_string(n++) + ".dat";
        cov->write(path.c_str());
    }
    cov->clear();
}
#else
inline void write_coverage() {}
#endif

template <class V, class = void>
struct HasMutantPort : std::false_type {};
template <class V>
struct HasMutantPort<V, std::void_t<decltype(std::declval<V&>().mutant)>> : std::true_type {};

struct NoTrace {
    void close() {}
};

// Tracing must be switched on before a traced model is built.
template <int Trace>
struct TraceOn {
    TraceOn() {
        if (Trace != 0) Verilated::traceEverOn(true);
    }
};

template <class V, int Trace>
class ModelImpl final : private TraceOn<Trace>, public Model {
  public:
    explicit ModelImpl(const char* name) : dut_(name) {
        // IMAP_RTL_ASSERTIONS=0: the design's assertions are not evaluated
        // (Verilator's run-time switch: to measure what they cost,
        // docs/rtl.md "Assertions")
        const char* a = std::getenv("IMAP_RTL_ASSERTIONS");
        if (a && std::string(a) == "0") Verilated::assertOn(false);
    }
    ~ModelImpl() override {
        trace_close();
        write_coverage();  // coverage build only
    }

    sc_core::sc_module& module() override { return dut_; }
    TraceFormat trace_format() const override { return static_cast<TraceFormat>(Trace); }
    bool mutants() const override { return HasMutantPort<V>::value; }

    void bind(Ports& p) override {
        dut_.clk(p.clk);
        dut_.rst_n(p.rst_n);
        dut_.host_we(p.host_we);
        dut_.host_sel(p.host_sel);
        dut_.host_addr(p.host_addr);
        dut_.host_data(p.host_data);
        dut_.c_alu(p.c_alu);
        dut_.c_mem(p.c_mem);
        dut_.c_indirect_extra(p.c_indirect_extra);
        dut_.c_ring_hop(p.c_ring_hop);
        dut_.c_mask(p.c_mask);
        dut_.c_status(p.c_status);
        dut_.c_cp(p.c_cp);
        dut_.c_branch_taken(p.c_branch_taken);
        dut_.c_video_line(p.c_video_line);
        dut_.c_xfer_setup(p.c_xfer_setup);
        dut_.c_ext_bpc(p.c_ext_bpc);
        dut_.c_ext_beat(p.c_ext_beat);
        dut_.c_shift_bits(p.c_shift_bits);
        dut_.c_minmax_extra(p.c_minmax_extra);
        dut_.cfg_prog_len(p.cfg_prog_len);
        dut_.cfg_pe_regs(p.cfg_pe_regs);
        dut_.cfg_mask_depth(p.cfg_mask_depth);
        dut_.cfg_call_depth(p.cfg_call_depth);
        dut_.cfg_indirect(p.cfg_indirect);
        dut_.cfg_ext_on(p.cfg_ext_on);
        dut_.cfg_watchdog(p.cfg_watchdog);
        dut_.cfg_trace(p.cfg_trace);
        if constexpr (HasMutantPort<V>::value) dut_.mutant(p.mutant);
        dut_.done(p.done);
    }

    Backdoor backdoor() override {
        Backdoor b;
        // the testbench top (imap_tb): the chip u_chip and the board model u_board
        const std::string top = std::string(dut_.name()) + ".imap_tb";
        const std::string chip = top + ".u_chip";
        auto find = [&](const std::string& scope, const std::string& name) {
            const VerilatedScope* s = Verilated::scopeFind(scope.c_str());
            if (!s) throw std::runtime_error("RTL backdoor: no scope " + scope);
            const VerilatedVar* v = s->varFind(name.c_str());
            if (!v)
                throw std::runtime_error("RTL backdoor: no state element " + scope + "." + name);
            return v;
        };
        auto var = [&](const std::string& scope, const char* name, size_t bytes) -> void* {
            const VerilatedVar* v = find(scope, name);
            if (bytes != 0 && static_cast<size_t>(v->totalSize()) != bytes)
                throw std::runtime_error("RTL backdoor: " + scope + "." + name + " has " +
                                         std::to_string(v->totalSize()) + " bytes, expected " +
                                         std::to_string(bytes));
            return v->datap();
        };
        const std::string cp = chip + ".u_cp", perf = chip + ".u_perf", arr = chip + ".u_array";
        b.creg = static_cast<uint32_t*>(var(cp, "creg", 64));
        b.param = static_cast<uint32_t*>(var(cp, "param", 1024));
        b.csp = static_cast<uint16_t*>(var(cp, "csp", 2));
        b.msp = static_cast<uint16_t*>(var(cp, "msp", 2));
        b.phase = static_cast<uint16_t*>(var(cp, "phase_q", 2));
        b.instret = static_cast<uint64_t*>(var(cp, "instret", 8));
        b.mcycle = static_cast<uint64_t*>(var(cp, "mcycle", 8));
        b.x_pc = static_cast<uint32_t*>(var(cp, "x_pc", 4));
        b.halted = static_cast<uint8_t*>(var(cp, "halted", 1));
        b.faulted = static_cast<uint8_t*>(var(cp, "faulted", 1));
        b.f_code = static_cast<uint8_t*>(var(cp, "f_code", 1));
        b.f_pc = static_cast<uint32_t*>(var(cp, "f_pc_q", 4));
        b.f_cyc = static_cast<uint64_t*>(var(cp, "f_cyc", 8));
        b.f_pe = static_cast<uint32_t*>(var(cp, "f_pe", 4));
        b.f_addr = static_cast<uint64_t*>(var(cp, "f_addr", 8));
        b.kind_cyc = static_cast<uint64_t*>(var(perf, "kind_cyc", 12 * 8));
        b.op_cnt = static_cast<uint64_t*>(var(perf, "op_cnt", 256 * 8));
        b.phase_cyc = static_cast<uint64_t*>(var(perf, "phase_cyc", kHdlPhases * 8));
        b.pe_cyc = static_cast<uint64_t*>(var(perf, "pe_cyc", 8));
        b.active_cyc = static_cast<uint64_t*>(var(perf, "active_cyc", 8));
        b.phases = kHdlPhases;
        b.nregs = kHdlRegs;
        // the PEs
        for (int p = 0;; ++p) {
            const std::string pe = arr + ".g_pe[" + std::to_string(p) + "].u_pe";
            if (!Verilated::scopeFind(pe.c_str())) {
                b.P = p;
                break;
            }
            b.regs.push_back(static_cast<uint8_t*>(var(pe, "regs", kHdlRegs)));
            b.mem_bytes = *static_cast<const uint32_t*>(var(pe, "MEM_BYTES", 4));
            Backdoor::PeMem m;
            for (int k = 0; k < kHdlXrows; ++k) {
                const VerilatedVar* v = find(pe, "bank" + std::to_string(k));
                m.bank_bytes = static_cast<size_t>(v->totalSize());
                m.bank[static_cast<size_t>(k)] = static_cast<uint8_t*>(v->datap());
            }
            if (m.bank_bytes * kHdlXrows < b.mem_bytes)
                throw std::runtime_error("RTL backdoor: the banks of " + pe + " hold fewer than " +
                                         std::to_string(b.mem_bytes) + " bytes");
            b.mem.push_back(std::move(m));
            b.carry.push_back(static_cast<uint8_t*>(var(pe, "c_q", 1)));
            b.st.push_back(static_cast<uint8_t*>(var(pe, "st_q", 1)));
            const VerilatedVar* sv = find(pe, "mstk");
            b.mstk_bytes = static_cast<int>(sv->totalSize());
            b.mstk.push_back(sv->datap());
        }
        const std::string board = top + ".u_board";
        const VerilatedVar* ev = find(board, "ext");
        b.ext = static_cast<uint8_t*>(ev->datap());
        b.ext_bytes = b.P > 0 ? static_cast<uint32_t>(ev->totalSize() / b.P) : 0;
        return b;
    }

    void trace_open(const std::string& path, const std::vector<std::string>& scopes) override {
        if constexpr (Trace == 0) {
            (void)path;
            (void)scopes;
            throw std::logic_error("RTL model built without tracing");
        } else {
            trace_close();
            tf_ = std::make_unique<TraceFile>();
            // "scope" = everything under it; "scope!" = its own signals only
            // (Verilator's level 1: one name below the prefix)
            for (const std::string& s : scopes) {
                if (!s.empty() && s.back() == '!')
                    tf_->dumpvars(1, s.substr(0, s.size() - 1));
                else
                    tf_->dumpvars(99, s);
            }
            dut_.trace(tf_.get(), 99);
            tf_->set_time_unit("1ps");
            tf_->set_time_resolution("1ps");
            tf_->open(path.c_str());
            if (!tf_->isOpen()) {
                tf_.reset();
                throw std::runtime_error("cannot create " + path);
            }
        }
    }
    void trace_dump(uint64_t t) override {
        if constexpr (Trace != 0)
            if (tf_) tf_->dump(t);
        (void)t;
    }
    void trace_close() override {
        if constexpr (Trace != 0)
            if (tf_) {
                tf_->close();
                tf_.reset();
            }
    }

  private:
    using TraceFile = std::conditional_t<Trace == 2, VerilatedFstC,
                                         std::conditional_t<Trace == 1, VerilatedVcdC, NoTrace>>;
    V dut_;
    std::unique_ptr<TraceFile> tf_;
};

}  // namespace imap::rtl::detail
