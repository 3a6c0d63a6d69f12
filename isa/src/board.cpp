// Board timing: the external path's cycle costs and the camera's line
// arrival at the array clock (docs/isa.md section 2.3).
#include "imap/isa/board.hpp"

#include <algorithm>
#include <cmath>

#include "imap/isa/config.hpp"
#include "num_fields.hpp"

namespace imap::isa {

namespace {

// ceil(x) for a value computed in floating point that should be exact
// (200 ns x 40 MHz / 1000 = 8, not 8.000000001).
uint64_t ceil_exact(double x) {
    const double r = std::round(x);
    if (std::fabs(x - r) <= 1e-9 * std::max(1.0, std::fabs(x))) return static_cast<uint64_t>(r);
    return static_cast<uint64_t>(std::ceil(x));
}

}  // namespace

const std::vector<BoardTiming::Field>& BoardTiming::fields() {
    using T = BoardTiming;
    static const std::vector<Field> f = {
        {"ext_mb_s", &T::ext_mb_s, 0, 1e6, "MB/s",
         "external-memory path bandwidth of the whole board; 0 = off (xfer_setup, "
         "ext_bytes_per_cycle and ext_beat apply as set, in cycles)"},
        {"ext_bus_bytes", &T::ext_bus_bytes, 1, 1024, "bytes/cycle",
         "bytes the external path moves per array cycle at most (its width; IMAPCAR: 8)"},
        {"ext_latency_ns", &T::ext_latency_ns, 0, 1e6, "ns",
         "fixed part of an xld / xst (SDRAM row activation, controller turnaround)"},
        {"camera_pixel_mhz", &T::camera_pixel_mhz, 0, 1e5, "MHz",
         "camera pixel clock; 0 = ideal camera (lines already in the line buffer)"},
        {"camera_hblank_px", &T::camera_hblank_px, 0, 1e6, "pixels",
         "camera horizontal blanking per line, in pixel times"},
    };
    return f;
}

bool BoardTiming::has(std::string_view name) {
    return detail::num_has<BoardTiming>(name);
}

void BoardTiming::set(std::string_view name, double value) {
    detail::num_set(*this, name, value, "board");
    if (name == "ext_bus_bytes" && value != std::floor(value))
        throw ConfigError("invalid value " + detail::num_text(value) +
                          " for ext_bus_bytes: allowed whole numbers 1..1024 bytes/cycle");
}

void BoardTiming::validate() const {
    detail::num_validate(*this);
}

std::vector<ParamInfo> BoardTiming::list() const {
    return detail::num_list(*this, "board");
}

void BoardTiming::derive_costs(double clock_mhz, CostTable& c) const {
    if (!ext_timed()) return;
    c.xfer_setup = static_cast<uint32_t>(
        std::min<uint64_t>(ceil_exact(ext_latency_ns * clock_mhz / 1000.0), 1000000));
    const double bus = std::floor(ext_bus_bytes);
    const double r = std::min(ext_mb_s / clock_mhz, bus);
    if (r * 16 < 1) {  // slower than a byte per 16 cycles: one byte per beat
        c.ext_bytes_per_cycle = 1;
        c.ext_beat = static_cast<uint32_t>(std::min<uint64_t>(ceil_exact(1.0 / r), 1000000));
        return;
    }
    uint32_t best_b = 1, best_k = 16;
    double best = 1.0 / 16.0;
    for (uint32_t k = 1; k <= 16; ++k) {
        // the most bytes per k cycles not above the rate (exact when r x k is whole)
        double b = std::floor(r * k + 1e-9);
        b = std::min(b, bus);
        if (b < 1) continue;
        if (b / k > best + 1e-12) {
            best = b / k;
            best_b = static_cast<uint32_t>(b);
            best_k = k;
        }
    }
    c.ext_bytes_per_cycle = best_b;
    c.ext_beat = best_k;
}

uint64_t BoardTiming::camera_ready_cycle(double clock_mhz, int width, int y, int x0, int n) const {
    const int64_t end = std::min<int64_t>(int64_t{x0} + n, width);
    if (!camera_timed() || y < 0 || end <= std::max(x0, 0)) return 0;  // no camera pixel read
    const double line = static_cast<double>(width) + camera_hblank_px;
    const double px =
        static_cast<double>(y) * line + static_cast<double>(std::max<int64_t>(end, 0));
    return ceil_exact(px / camera_pixel_mhz * clock_mhz);
}

}  // namespace imap::isa
