// The waves of a run (models.hpp): the instruction-set tracer of a core or
// tlm run (VCD and GTKWave view), the checks made before the run, and for
// --model rtl the selection handed to the design's own tracing and the line
// that says where its waves went.
#include <cstdio>
#include <string>

#include "imap/engine/error.hpp"
#include "imap/engine/models.hpp"
#include "imap/engine/output_files.hpp"
#include "imap/firmware/run.hpp"
#include "wave_rtl.hpp"
#ifdef IMAP_ENGINE_HAVE_WAVES
#include <filesystem>
#include <memory>

#include "imap/waves/isa_trace.hpp"
#endif

namespace imap::engine {

namespace fw = imap::firmware;

void check_wave_outputs(const WaveOptions& f, const std::string& model) {
    if (f.vcd.empty()) return;
    if (lower_extension(f.vcd) == ".fst" && model != "rtl")
        throw Error("--vcd '" + f.vcd + "': --model " + model +
                    " writes VCD, not FST: name it .vcd (GTKWave's vcd2fst converts it), "
                    "or trace --model rtl, which writes FST");
    check_output_file("--vcd", f.vcd, false);
#ifdef IMAP_ENGINE_HAVE_WAVES
    const std::string view = imap::waves::detail::gtkw_path_of(f.vcd);
    if (view == f.vcd)
        throw Error("--vcd '" + f.vcd + "': the GTKWave view would overwrite it (use a .vcd name)");
    check_output_file("--vcd (its GTKWave view)", view, false);
#endif
}

#if defined(IMAP_ENGINE_HAVE_RTL) && defined(IMAP_ENGINE_HAVE_WAVES)
// --vcd with --model rtl: the design's own signals (Verilator tracing); the
// selection of PEs and the window as for the other models, the signal
// groups mapped onto the design's hierarchy (docs/rtl.md, "Waves").
imap::rtl::RtlWaves rtl_waves(const std::string& path, const imap::waves::TraceSelection& s) {
    imap::rtl::RtlWaves w;
    w.path = path;
    w.t0 = s.t0;
    w.t1 = s.t1 == UINT64_MAX ? UINT64_MAX : s.t1 - 1;
    w.limit_bytes = s.limit_bytes;
    w.pes = s.pes;
    if (s.cp) w.groups.push_back("cp"), w.groups.push_back("board");
    if (s.ring || s.mask) w.groups.push_back("array");
    if (s.regs || s.mem) w.groups.push_back("pe");
    return w;
}

// The waves line of an RTL run, as the ISA tracer's: a "->" line only for a
// file that exists, and the same warnings (stopped at the size limit; an
// empty window).
void print_rtl_waves(const imap::rtl::RtlWaves& w, const imap::rtl::RtlRunResult* rr,
                     const std::string& window, const std::string& limit_name) {
    if (w.path.empty()) return;
    std::error_code ec;
    const auto bytes = std::filesystem::file_size(w.path, ec);
    if (ec) {
        std::fflush(stdout);
        std::fprintf(stderr, "warning: --vcd: no waves were written to %s\n", w.path.c_str());
        return;
    }
    const bool limited = rr && rr->waves_limited;
    std::printf("  waves -> %s (%.2f MB, the design's signals%s) + %s\n", w.path.c_str(),
                static_cast<double>(bytes) / 1048576.0,
                limited ? ", stopped at --trace-limit-mb" : "",
                imap::rtl::gtkw_path(w.path).c_str());
    std::fflush(stdout);
    if (limited)
        std::fprintf(stderr,
                     "warning: --vcd: the trace stopped at %s (valid up to there); narrow "
                     "--trace-window / --trace-pes or raise the limit\n",
                     limit_name.c_str());
    if (rr && rr->waves_empty)
        std::fprintf(stderr,
                     "warning: --trace-window %s starts at cycle %llu, after the end of the run "
                     "(cycle %llu): the trace holds the final state only\n",
                     window.c_str(), static_cast<unsigned long long>(w.t0),
                     static_cast<unsigned long long>(rr->cycles));
}
#endif

#ifdef IMAP_ENGINE_HAVE_WAVES
struct WaveSession::Impl {
    WaveOptions flags;
    imap::waves::TraceSelection sel;
    std::unique_ptr<imap::waves::IsaTracer> tracer;
};

WaveSession::WaveSession(const WaveOptions& f, const isa::MachineConfig& cfg,
                         const isa::Program& prog)
    : impl_(std::make_unique<Impl>()) {
    if (f.vcd.empty()) return;
    impl_->flags = f;
    try {
        imap::waves::TraceSelection sel =
            imap::waves::parse_trace_selection(f.pes, f.window, f.signals, f.limit_mb, cfg);
        for (const fw::WaveGroup& g : fw::wave_groups()) sel.groups.push_back({g.name, g.regs});
        if (sel.t1 != UINT64_MAX) {
            const double est = imap::waves::IsaTracer::estimate_bytes(sel, sel.t1 - sel.t0);
            if (est > static_cast<double>(sel.limit_bytes))
                std::fprintf(stderr,
                             "warning: --vcd: the selection (%zu PEs x %llu cycles) is "
                             "estimated at %.0f MB, above %s: the trace will stop there\n",
                             sel.pes.size(), static_cast<unsigned long long>(sel.t1 - sel.t0),
                             est / 1048576.0, sel.limit_name.c_str());
        }
        impl_->sel = sel;
        impl_->tracer = std::make_unique<imap::waves::IsaTracer>(f.vcd, cfg, prog, sel);
    } catch (const imap::waves::WaveError& e) {
        throw Error(e.what());
    }
}

WaveSession::~WaveSession() = default;

bool WaveSession::active() const {
    return impl_->tracer != nullptr;
}

isa::Observer* WaveSession::observer() {
    return impl_->tracer.get();
}

void WaveSession::finish(uint64_t end_cycle) {
    namespace w = imap::waves;
    const w::TraceSelection& sel = impl_->sel;
    uint64_t traced = 0;
    std::string what;
    if (impl_->tracer) {
        w::IsaTracer& t = *impl_->tracer;
        try {
            t.finish(end_cycle);
        } catch (const w::WaveError& e) {
            throw Error(std::string("--vcd: ") + e.what());
        }
        traced = t.traced_instructions();
        const bool view = t.gtkw_error().empty();
        std::printf("  waves -> %s (%.2f MB, %llu instructions traced%s)%s%s\n",
                    t.vcd_path().c_str(), static_cast<double>(t.bytes()) / 1048576.0,
                    static_cast<unsigned long long>(traced),
                    t.limit_reached() ? ", stopped at --trace-limit-mb" : "", view ? " + " : "",
                    view ? t.gtkw_path().c_str() : "");
        std::fflush(stdout);  // the warning after the line it is about
        if (!view)
            std::fprintf(stderr,
                         "warning: --vcd: the GTKWave view was not written (%s); the VCD %s is "
                         "complete and kept\n",
                         t.gtkw_error().c_str(), t.vcd_path().c_str());
        what = "instruction";
    } else {
        return;
    }
    std::fflush(stdout);
    if (traced == 0) {
        const std::string window = impl_->flags.window.empty() ? "all" : impl_->flags.window;
        if (sel.t0 >= end_cycle)
            std::fprintf(stderr,
                         "warning: --trace-window %s starts at cycle %llu, after the end of the "
                         "run (cycle %llu): the trace is empty\n",
                         window.c_str(), static_cast<unsigned long long>(sel.t0),
                         static_cast<unsigned long long>(end_cycle));
        else
            std::fprintf(stderr,
                         "warning: --trace-window %s: no %s of the run (cycles 0..%llu) starts "
                         "in it: the trace is empty\n",
                         window.c_str(), what.c_str(), static_cast<unsigned long long>(end_cycle));
    }
}
#else
struct WaveSession::Impl {};
WaveSession::WaveSession(const WaveOptions& f, const isa::MachineConfig&, const isa::Program&)
    : impl_(std::make_unique<Impl>()) {
    if (!f.vcd.empty()) throw Error("--vcd: this imapsim has no waves library");
}
WaveSession::~WaveSession() = default;
bool WaveSession::active() const {
    return false;
}
isa::Observer* WaveSession::observer() {
    return nullptr;
}
void WaveSession::finish(uint64_t) {}
#endif

}  // namespace imap::engine
