// The GTKWave save file of the design's waves (waves_view.cpp).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace imap::rtl::detail {

struct WavesView {
    std::string waves_path, gtkw_path;
    std::string top;       // the model's SystemC name ("dut")
    std::vector<int> pes;  // PEs shown
    int pes_total = 8;     // PEs of the configuration
    int nregs = 16, addr_bits = 10, mask_depth = 8;
    uint64_t start_time = 0, span_time = 0;  // the view at start (ps)
};

// Verilator's default --trace-max-array: larger unpacked arrays are not traced.
inline constexpr int kTraceMaxArray = 32;

// Writes v.gtkw_path (waves::WaveError on failure).
void write_gtkw(const WavesView& v);

}  // namespace imap::rtl::detail
