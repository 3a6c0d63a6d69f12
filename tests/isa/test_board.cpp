// Board timing (docs/isa.md section 2.3): the external path's cycle costs at
// any clock from its bandwidth, bus width and latency; the camera's line
// arrival; the machine charging both; the parameters' ranges. Expected values
// are worked out by hand from the parameters in the comments.
#define BOOST_TEST_MODULE isa_board
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <string>

#include "helpers.hpp"

using namespace isatest;

namespace {

MachineConfig at_clock(double mhz) {
    MachineConfig c;
    c.set("clock_mhz", std::to_string(mhz));
    return c;
}

std::string config_error(const std::string& name, const std::string& value) {
    MachineConfig c;
    try {
        c.set(name, value);
    } catch (const ConfigError& e) {
        return e.what();
    }
    return "";
}

}  // namespace

BOOST_AUTO_TEST_CASE(defaults_keep_the_40_mhz_costs) {
    const MachineConfig c;  // 800 MB/s, 8-byte bus, 200 ns at 40 MHz
    BOOST_CHECK_EQUAL(c.costs.xfer_setup, 8u);
    BOOST_CHECK_EQUAL(c.costs.ext_bytes_per_cycle, 8u);
    BOOST_CHECK_EQUAL(c.costs.ext_beat, 1u);
    MachineConfig d = c;
    d.derive_board_costs();  // the defaults are what the derivation gives
    BOOST_CHECK_EQUAL(d.costs.xfer_setup, 8u);
    BOOST_CHECK_EQUAL(d.costs.ext_bytes_per_cycle, 8u);
    BOOST_CHECK_EQUAL(d.costs.ext_beat, 1u);
}

BOOST_AUTO_TEST_CASE(external_path_follows_the_clock) {
    // 10 MHz: 800 / 10 = 80 B/cycle, the 8-byte bus limits it; 200 ns = 2 cycles
    MachineConfig c = at_clock(10);
    BOOST_CHECK_EQUAL(c.costs.xfer_setup, 2u);
    BOOST_CHECK_EQUAL(c.costs.ext_bytes_per_cycle, 8u);
    BOOST_CHECK_EQUAL(c.costs.ext_beat, 1u);
    // 100 MHz: 800 / 100 = 8 B/cycle exactly (the knee); 20 cycles of setup
    c = at_clock(100);
    BOOST_CHECK_EQUAL(c.costs.xfer_setup, 20u);
    BOOST_CHECK_EQUAL(c.costs.ext_bytes_per_cycle, 8u);
    BOOST_CHECK_EQUAL(c.costs.ext_beat, 1u);
    // 200 MHz: 4 B/cycle
    c = at_clock(200);
    BOOST_CHECK_EQUAL(c.costs.ext_bytes_per_cycle, 4u);
    BOOST_CHECK_EQUAL(c.costs.ext_beat, 1u);
    // 300 MHz: 2.67 B/cycle = 8 bytes every 3 cycles
    c = at_clock(300);
    BOOST_CHECK_EQUAL(c.costs.xfer_setup, 60u);
    BOOST_CHECK_EQUAL(c.costs.ext_bytes_per_cycle, 8u);
    BOOST_CHECK_EQUAL(c.costs.ext_beat, 3u);
    // 1000 MHz: 0.8 B/cycle = 4 bytes every 5 cycles
    c = at_clock(1000);
    BOOST_CHECK_EQUAL(c.costs.ext_bytes_per_cycle, 4u);
    BOOST_CHECK_EQUAL(c.costs.ext_beat, 5u);
    // 0.01 MB/s at 40 MHz: one byte every 4000 cycles
    c = at_clock(40);
    c.set("ext_mb_s", "0.01");
    BOOST_CHECK_EQUAL(c.costs.ext_bytes_per_cycle, 1u);
    BOOST_CHECK_EQUAL(c.costs.ext_beat, 4000u);
    // the order of the settings does not matter
    MachineConfig a, b;
    a.set("ext_latency_ns", "500");
    a.set("clock_mhz", "80");
    b.set("clock_mhz", "80");
    b.set("ext_latency_ns", "500");
    BOOST_CHECK_EQUAL(a.costs.xfer_setup, 40u);
    BOOST_CHECK_EQUAL(b.costs.xfer_setup, 40u);
}

BOOST_AUTO_TEST_CASE(never_faster_than_the_bandwidth) {
    for (double mhz : {7.0, 33.0, 41.0, 99.0, 101.0, 123.0, 250.0, 777.0, 2000.0, 5000.0}) {
        const MachineConfig c = at_clock(mhz);
        const double bytes_per_s =
            c.costs.ext_bytes_per_cycle / double(c.costs.ext_beat) * mhz * 1e6;
        BOOST_TEST_CONTEXT("clock " << mhz << " MHz") {
            BOOST_CHECK_LE(bytes_per_s, 800e6 * (1 + 1e-12));
            BOOST_CHECK_LE(c.costs.ext_bytes_per_cycle, 8u);
            // within the rounding of whole bytes per beat (at most a bus width
            // per beat of at most 16 cycles): at least 6/7 of the rate
            const double want = std::min(800e6, 8 * mhz * 1e6);
            BOOST_CHECK_GE(bytes_per_s, want * 6.0 / 7.0 - 1);
        }
    }
}

BOOST_AUTO_TEST_CASE(cycle_costs_set_directly_turn_the_board_timing_off) {
    MachineConfig c;
    c.set("xfer_setup", "20");
    BOOST_CHECK_EQUAL(c.board.ext_mb_s, 0.0);
    c.set("clock_mhz", "80");
    BOOST_CHECK_EQUAL(c.costs.xfer_setup, 20u);  // kept at any clock
    BOOST_CHECK_EQUAL(c.costs.ext_bytes_per_cycle, 8u);
    c.set("ext_mb_s", "800");  // on again: derived at 80 MHz
    BOOST_CHECK_EQUAL(c.costs.xfer_setup, 16u);
    MachineConfig d;
    d.set("ext_beat", "3");
    d.set("clock_mhz", "300");
    BOOST_CHECK_EQUAL(d.costs.ext_beat, 3u);
    BOOST_CHECK_EQUAL(d.costs.xfer_setup, 8u);
}

BOOST_AUTO_TEST_CASE(transfer_cycles_with_a_beat) {
    CostTable k;
    k.xfer_setup = 5;
    k.ext_bytes_per_cycle = 4;
    k.ext_beat = 3;
    // 10 bytes x 2 PEs = 20 bytes = 5 beats of 3 cycles
    BOOST_CHECK_EQUAL(k.xfer_cycles(10, 2), 5u + 15u);
    BOOST_CHECK_EQUAL(k.xfer_cycles(1, 1), 5u + 3u);
    BOOST_CHECK_EQUAL(k.xfer_cycles(0, 4), 5u);
    // on the machine: 4 PEs x 5 bytes = 20 bytes at 3 per 2 cycles = 7 beats
    MachineConfig x = small(4);
    x.costs.ext_bytes_per_cycle = 3;
    x.costs.ext_beat = 2;
    auto m = run("cli c2, #5\nxld [#0], ext[c2], c2\nhalt", x);
    BOOST_CHECK_EQUAL(m->cycles(), 1u + 8u + 14u + 1u);
}

BOOST_AUTO_TEST_CASE(camera_line_arrival) {
    BoardTiming b;
    BOOST_CHECK_EQUAL(b.camera_ready_cycle(40, 100, 5, 0, 8), 0u);  // ideal camera
    b.camera_pixel_mhz = 10;
    b.camera_hblank_px = 20;
    // 100-pixel lines + 20 of blanking at 10 MHz = 12 us per line = 480 cycles
    // at 40 MHz. Pixels 0..7 of line 0: 8 pixel times = 0.8 us = 32 cycles.
    BOOST_CHECK_EQUAL(b.camera_ready_cycle(40, 100, 0, 0, 8), 32u);
    // line 2, pixels 96..103: 96..99 are the last of the line: 2 x 120 + 100
    BOOST_CHECK_EQUAL(b.camera_ready_cycle(40, 100, 2, 96, 8), 340u * 4u);
    // wholly beyond the width: no camera pixel is read, no wait
    BOOST_CHECK_EQUAL(b.camera_ready_cycle(40, 100, 1, 200, 8), 0u);
    // 33 MHz: 32 pixel times at 10 MHz = 3.2 us = 105.6 -> 106 cycles
    BOOST_CHECK_EQUAL(b.camera_ready_cycle(33, 100, 0, 0, 32), 106u);
}

BOOST_AUTO_TEST_CASE(vin_waits_for_the_camera) {
    ImageVideoPort video;
    video.input[0].width = 12;
    video.input[0].height = 3;
    video.input[0].pixels.assign(36, 7);
    MachineConfig c = small(4);
    c.set("camera_pixel_mhz", "10");
    c.set("camera_hblank_px", "4");
    // 16 pixel times per line at 10 MHz = 1.6 us = 64 cycles at 40 MHz.
    Machine m(c);
    m.set_video(&video);
    m.load(assemble_string(R"(
        cli c2, #1
        cli c3, #4
        vin #0, [#0], c2, c3     ; line 1, pixels 4..7: (16 + 8) x 4 = 96
        vin #0, [#1], c2, c3     ; already there: 1 cycle
        cli c2, #0
        vin #0, [#2], c2, c3     ; line 0 arrived long ago: 1 cycle
        halt)"));
    m.run();
    // cli, cli (2), the first vin ends at 96 + 1, the second 98, cli 99,
    // third vin 100, halt 101
    BOOST_CHECK_EQUAL(m.cycles(), 101u);
    Machine ideal(small(4));
    ideal.set_video(&video);
    ideal.load(assemble_string("cli c2, #2\nvin #0, [#0], c2, c3\nhalt"));
    ideal.run();
    BOOST_CHECK_EQUAL(ideal.cycles(), 3u);

    // a port that does not tell the width cannot be timed: a clear fault
    struct Blind : VideoPort {
        void read_line(int, int, int, uint8_t* d, int n) override { std::fill(d, d + n, 0); }
        void write_line(int, int, int, const uint8_t*, int) override {}
    } blind;
    Machine b(c);
    b.set_video(&blind);
    b.load(assemble_string("vin #0, [#0], c2, c3\nhalt"));
    BOOST_CHECK_EXCEPTION(b.run(), Fault, [](const Fault& f) {
        return std::string(f.what()).find("needs the image width") != std::string::npos;
    });
}

BOOST_AUTO_TEST_CASE(parameters_are_range_checked) {
    BOOST_CHECK_NE(config_error("ext_mb_s", "-1").find("allowed 0..1e+06 MB/s"), std::string::npos);
    BOOST_CHECK_NE(config_error("ext_bus_bytes", "0").find("allowed 1..1024"), std::string::npos);
    BOOST_CHECK_NE(config_error("ext_bus_bytes", "2.5").find("whole numbers"), std::string::npos);
    BOOST_CHECK_NE(config_error("ext_latency_ns", "1e9").find("ext_latency_ns"), std::string::npos);
    BOOST_CHECK_NE(config_error("camera_pixel_mhz", "-3").find("allowed 0..100000 MHz"),
                   std::string::npos);
    BOOST_CHECK_NE(config_error("camera_hblank_px", "x").find("expected a number"),
                   std::string::npos);
    BOOST_CHECK_NE(config_error("ext_beat", "0").find("ext_beat"), std::string::npos);
    // every board parameter is listed, in group "board"
    int n = 0;
    for (const ParamInfo& p : MachineConfig().list()) n += p.group == "board";
    BOOST_CHECK_EQUAL(n, 5);
}

// A clock sweep of a transfer-bound program: its modeled time falls as 1/f
// while the bus width limits the path and stays once the bandwidth does. The
// knee, found as docs/whatif.md defines it (the point where the log-log slope
// of time against the clock changes most), is at ext_mb_s / ext_bus_bytes,
// computed here from the parameters.
BOOST_AUTO_TEST_CASE(clock_sweep_of_a_transfer_bound_program_has_its_knee) {
    const double mb_s = 240, bus = 4, predicted = mb_s / bus;  // 60 MHz
    std::string src = "cli c2, #64\ncli c1, #0\n";
    for (int i = 0; i < 8; ++i) src += "xld [#0], ext[c1], c2\naddi r1, r1, #1\n";
    src += "halt\n";
    std::vector<double> clocks, ms;
    for (int k = -3; k <= 3; ++k) {
        MachineConfig c = small(16);
        c.set("ext_mb_s", std::to_string(mb_s));
        c.set("ext_bus_bytes", std::to_string(bus));
        c.set("clock_mhz", std::to_string(predicted * std::pow(2.0, k)));
        auto m = run(src, c);
        clocks.push_back(c.clock_mhz);
        ms.push_back(c.milliseconds(m->cycles()));
    }
    std::vector<double> slope;
    for (size_t i = 0; i + 1 < ms.size(); ++i)
        slope.push_back(std::log(ms[i + 1] / ms[i]) / std::log(clocks[i + 1] / clocks[i]));
    size_t knee = 0;
    double change = 0;
    for (size_t i = 1; i < slope.size(); ++i)
        if (std::fabs(slope[i] - slope[i - 1]) > change) {
            change = std::fabs(slope[i] - slope[i - 1]);
            knee = i;
        }
    BOOST_TEST_MESSAGE("knee at " << clocks[knee] << " MHz, slope " << slope[knee - 1] << " -> "
                                  << slope[knee]);
    BOOST_CHECK_CLOSE(clocks[knee], predicted, 1e-9);
    BOOST_CHECK_LT(slope[knee - 1], -0.8);  // bus-bound: nearly 1/f
    BOOST_CHECK_GT(slope[knee], -0.2);      // bandwidth-bound: nearly flat
    BOOST_CHECK_GE(change, 0.5);            // a knee by the sweep's threshold
    // with the board timing off the same sweep has no knee: 1/f throughout
    MachineConfig off = small(16);
    off.set("ext_mb_s", "0");
    auto a = run(src, off);
    off.set("clock_mhz", "480");
    auto b = run(src, off);
    BOOST_CHECK_EQUAL(a->cycles(), b->cycles());
}
