// Helpers shared by the RTL tests: the TLM tests' every-class program and
// reference (tests/tlm/tlm_test_util.hpp) and a small DP firmware frame.
#pragma once

#include <boost/test/unit_test.hpp>
#include <random>
#include <vector>

#include "imap/firmware/plan.hpp"
#include "imap/firmware/run.hpp"
#include "imap/golden/stereo.hpp"
#include "imap/rtl/lockstep.hpp"
#include "imap/rtl/system.hpp"
#include "tlm_test_util.hpp"

namespace rtltest {

namespace g = imap::golden;
namespace fw = imap::firmware;
namespace rtl = imap::rtl;
using namespace tlmtest;

// A random stereo frame whose left image is the right one shifted by a
// per-line disparity plus noise.
struct Frame {
    int W = 0, H = 0;
    std::vector<uint8_t> L, R;
    g::ImageView left() const { return {L.data(), W, H, W}; }
    g::ImageView right() const { return {R.data(), W, H, W}; }
};
inline Frame random_frame(unsigned seed, int W, int H, int D) {
    std::mt19937 rng(seed);
    Frame f;
    f.W = W;
    f.H = H;
    f.L.resize(size_t(W) * size_t(H));
    f.R.resize(f.L.size());
    std::uniform_int_distribution<int> pix(0, 255), noise(-4, 4), disp(0, D - 1);
    for (int y = 0; y < H; ++y) {
        const int d = disp(rng);
        for (int x = 0; x < W; ++x) f.R[size_t(y * W + x)] = uint8_t(pix(rng));
        for (int x = 0; x < W; ++x) {
            const int xs = std::min(W - 1, x + d);
            f.L[size_t(y * W + x)] =
                uint8_t(std::clamp(f.R[size_t(y * W + xs)] + noise(rng), 0, 255));
        }
    }
    return f;
}

// The TLM tests' configuration (tests/tlm) with the memory sizes of the
// RTL configurations this build has (1024 B local, 64 KB external).
inline isa::MachineConfig rtl_config(int pes) {
    isa::MachineConfig cfg = config(pes);
    cfg.mem_bytes = 1024;
    cfg.ext_bytes = 65536;
    return cfg;
}

struct FirmwareCase {
    g::Params p;
    g::Roi roi;
    fw::FramePlan plan;
    isa::Program prog;
    Frame frame;
};
inline FirmwareCase firmware_case(int P, unsigned seed, int D, bool vote, g::Mode mode) {
    FirmwareCase c;
    c.p.D = D;
    c.p.vote = vote;
    c.p.mode = mode;
    c.frame = random_frame(seed, 24, 8, D);
    c.roi = g::Roi{2, 1, 20, 6};
    isa::MachineConfig cfg;
    cfg.pes = P;
    c.plan = fw::plan_frame(c.p, c.roi, cfg);
    c.prog = fw::assemble_frame(c.p, c.plan);
    return c;
}

}  // namespace rtltest
