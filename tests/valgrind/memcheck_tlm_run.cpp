// The program that valgrind memcheck runs (scripts/valgrind.sh, CTest
// valgrind.tlm_run): one frame of the DP firmware on the SystemC TLM model,
// compared bit for bit with the golden reference.
//
// It links only imap_golden, imap_isa, imap_firmware and imap_tlm (SystemC)
// and makes its own synthetic pair: no OpenCV, so none of the libraries
// OpenCV pulls in (libavcodec -> libjxl -> libhwy) is loaded. Their start-up
// code runs before main and may use instructions valgrind cannot decode on
// the CPU at hand (libhwy's TimerResolution uses RDTSCP, which valgrind 3.19
// stops on with SIGILL); scripts/valgrind.sh checks with ldd that none of
// them is linked (docs/testing.md, "Valgrind").
//
// The test case planted_memory_error (disabled unless named with
// --run_test) runs the same frame and then reads past a heap block, branches
// on an uninitialised value and leaks a block: memcheck must report it
// (scripts/valgrind.sh --expect-errors, CTest valgrind.planted_error).
#define BOOST_TEST_MODULE valgrind_tlm_run
#include <boost/test/unit_test.hpp>
#include <cstdint>
#include <cstdio>
#include <vector>

#include "imap/firmware/plan.hpp"
#include "imap/firmware/run.hpp"
#include "imap/golden/stereo.hpp"
#include "imap/tlm/system.hpp"

namespace g = imap::golden;
namespace fw = imap::firmware;
namespace isa = imap::isa;
namespace itlm = imap::tlm;

namespace {

constexpr int kW = 64, kH = 32, kD = 16;

uint64_t splitmix64(uint64_t& s) {
    uint64_t z = (s += 0x9E3779B97F4A7C15ull);
    z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
    z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
    return z ^ (z >> 31);
}

// A textured background at disparity 3 with a box at disparity 9 in front
// (SPEC A.1: left pixel x + d shows what right pixel x shows), plus a little
// noise on the left view. Integers only.
struct Pair {
    std::vector<uint8_t> left, right;
};
Pair make_pair() {
    uint64_t s = 13;
    std::vector<int> tex(static_cast<size_t>(kW) * kH);
    for (int& t : tex) t = 30 + static_cast<int>(splitmix64(s) % 180);
    Pair p;
    p.right.resize(tex.size());
    p.left.resize(tex.size());
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const int a = tex[static_cast<size_t>(y) * kW + x];
            const int b = tex[static_cast<size_t>(y) * kW + (x + 1) % kW];
            p.right[static_cast<size_t>(y) * kW + x] = static_cast<uint8_t>((a + b) / 2);
        }
    for (int y = 0; y < kH; ++y)
        for (int x = 0; x < kW; ++x) {
            const bool box = y >= 8 && y < 24 && x >= 28 && x < 48;
            const int d = box ? 9 : 3;
            const int xr = x - d < 0 ? 0 : x - d;
            const int noise = static_cast<int>(splitmix64(s) % 5) - 2;
            int v = p.right[static_cast<size_t>(y) * kW + xr] + noise;
            v = v < 0 ? 0 : v > 255 ? 255 : v;
            p.left[static_cast<size_t>(y) * kW + x] = static_cast<uint8_t>(v);
        }
    return p;
}

g::ImageView view(const std::vector<uint8_t>& img) {
    return {img.data(), kW, kH, kW};
}

struct Frame {
    g::DisparityMap want;
    std::vector<uint8_t> got;
    uint64_t cycles = 0;
};

// One frame of the DP firmware on the TLM model (SystemC elaborates once per
// process, so each test case below is run in its own process).
Frame run_frame() {
    const Pair pair = make_pair();
    g::Params p;
    p.D = kD;
    const g::Roi roi{0, 0, kW, kH};
    const isa::MachineConfig cfg;  // the board: 256 PEs, 1 KB each
    const fw::FramePlan plan = fw::plan_frame(p, roi, cfg);
    const isa::Program prog = fw::assemble_frame(p, plan);
    itlm::OutputImages out;
    const itlm::TlmRunResult r =
        itlm::run_tlm(cfg, prog, fw::param_block(plan), fw::to_video_image(view(pair.left)),
                      fw::to_video_image(view(pair.right)), kW, kH, &out);
    Frame f;
    f.want = g::compute(p, view(pair.left), view(pair.right), roi);
    f.got = out.image[0].pixels;
    f.cycles = r.cycles;
    BOOST_TEST(r.halted);
    return f;
}

}  // namespace

BOOST_AUTO_TEST_CASE(tlm_frame_is_bit_exact) {
    const Frame f = run_frame();
    BOOST_TEST_MESSAGE("TLM frame " << kW << "x" << kH << " D=" << kD << ": " << f.cycles
                                    << " cycles");
    BOOST_TEST(f.cycles > 0u);
    BOOST_TEST(f.got == f.want.data, boost::test_tools::per_element());
    // Not a blank map: the box and the background are both found.
    int box = 0, background = 0;
    for (const uint8_t d : f.want.data) {
        box += d == 9;
        background += d == 3;
    }
    BOOST_TEST(box > 100);
    BOOST_TEST(background > 500);
}

BOOST_AUTO_TEST_CASE(planted_memory_error, *boost::unit_test::disabled()) {
    const Frame f = run_frame();
    BOOST_TEST(f.got == f.want.data);
    // An invalid read one byte past a heap block, a branch on an
    // uninitialised byte, and a block that is never freed.
    uint8_t* copy = new uint8_t[f.got.size()];
    for (size_t i = 0; i < f.got.size(); ++i) copy[i] = f.got[i];
    volatile const uint8_t* past = copy;
    const int beyond = past[f.got.size()];
    uint8_t* fresh = new uint8_t[16];
    volatile const uint8_t* unset = fresh;
    if (unset[7] == 42) std::puts("uninitialised byte was 42");
    std::printf("planted: byte past the end %d\n", beyond);
    delete[] copy;
    uint8_t* volatile leak = new uint8_t[100];
    leak[0] = 1;
    leak = nullptr;  // the block is lost
    delete[] fresh;
}
