// Board timing (docs/isa.md section 2.3): the parts of the board that the
// array does not clock run on their own clocks. The external-memory path has
// a bandwidth in MB/s and a latency per transfer in ns; the camera has a pixel
// clock. Their cycle costs follow from the array clock: BoardTiming derives
// the external path's CostTable fields (xfer_setup, ext_bytes_per_cycle,
// ext_beat) and the cycle at which a camera line's pixels have arrived.
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

namespace imap::isa {

struct ParamInfo;
struct CostTable;

struct BoardTiming {
    // External-memory path of the whole board. ext_mb_s = 0 turns the board
    // timing of the path off: the cost fields xfer_setup, ext_bytes_per_cycle
    // and ext_beat then apply as set, in cycles at any clock.
    double ext_mb_s = 800.0;      // MB/s (IMAPCAR: ~0.8 GB/s) [A]
    double ext_bus_bytes = 8.0;   // bytes the path moves per array cycle at most (64-bit) [A]
    double ext_latency_ns = 200;  // fixed part of a block transfer (SDRAM activation) [A]
    // Camera: 0 = ideal (every line already in the video line buffer); else
    // the pixel clock in MHz, with camera_hblank_px pixel times of blanking
    // per line. Line y is complete (y + 1) x (width + hblank) pixel times
    // after the run starts (the run starts with the frame's first line).
    double camera_pixel_mhz = 0.0;
    double camera_hblank_px = 140.0;  // NTSC square pixels: 780 total - 640 active [A]

    struct Field {
        const char* name;
        double BoardTiming::*ptr;
        double min, max;
        const char* unit;
        const char* doc;
    };
    static const std::vector<Field>& fields();
    static bool has(std::string_view name);
    void set(std::string_view name, double value);  // ConfigError out of range
    void validate() const;
    std::vector<ParamInfo> list() const;

    bool ext_timed() const { return ext_mb_s > 0; }
    bool camera_timed() const { return camera_pixel_mhz > 0; }

    // The external path's cycle costs at clock_mhz, written into `c` when the
    // path is timed (ext_timed()); otherwise `c` is left as it is.
    //   xfer_setup = ceil(ext_latency_ns x clock / 1000)
    //   bytes per cycle r = min(ext_mb_s / clock, ext_bus_bytes), moved as
    //   ext_bytes_per_cycle bytes every ext_beat cycles: the pair with
    //   ext_beat <= 16 and ext_bytes_per_cycle <= ext_bus_bytes whose rate is
    //   the largest not above r (the smallest ext_beat among equals).
    void derive_costs(double clock_mhz, CostTable& c) const;

    // Array cycle (from the run's start, at clock_mhz) at which pixels
    // [x0, x0 + n) of camera line y of a `width`-pixel image have arrived; 0
    // with an ideal camera or when no pixel of the range is inside the width.
    uint64_t camera_ready_cycle(double clock_mhz, int width, int y, int x0, int n) const;
};

}  // namespace imap::isa
