// Helpers shared by the TLM tests: a program that touches every part of the
// machine, its inputs, a reference run on a bare isa::Machine, and a
// comparison of the architectural state of two machines.
#pragma once

#include <boost/test/unit_test.hpp>
#include <string>
#include <utility>
#include <vector>

#include "imap/isa/isa.hpp"
#include "imap/tlm/tlm.hpp"

namespace tlmtest {

namespace isa = imap::isa;
namespace itlm = imap::tlm;

// ALU (carry chain), memory (broadcast and per-PE), the ring with wrap
// (k < P, k > P, both directions), the mask (nested mif / melse), the status
// reduction (rany / rall, inside and outside the mask), external memory,
// video in (two ports, wider image) and out, phases and a loop.
inline const char* kProgram = R"(
        .phase load
        cli c1, #0              ; line
        cli c2, #0              ; column
        vin #0, [#0], c1, c2    ; left line 0 -> row 0
        vin #1, [#1], c1, c2    ; right line 0 -> row 1
        cli c1, #2
        cli c3, #2
        vin #0, [c3 + 0], c1, c2  ; left line 2 -> row 2
        .phase compute
        ld r0, [#0]
        ld r1, [#1]
        add r2, r0, r1
        adc r3, r0, r2
        sub r4, r0, r1
        rxl r5, r2, #3          ; wraps
        rxr r6, r3, #11         ; k > P
        pidx r7, #0
        cltui r7, #5
        mif
          addi r8, r5, #100
          rany c4
          rall c5
          cgeui r7, #2
          mif
            rxl r9, r8, #1      ; masked PEs still drive the ring
            rall c6
          mend
        melse
          xori r8, r6, #0x55
          rxr r9, r8, #2
          rany c7
        mend
        ceq r0, r1
        rall c8
        rany c9
        cli c10, #6
loop1:  adc r10, r10, r2
        shli r11, r10, #1
        max r12, r11, r9
        loop c10, loop1
        st r2, [#3]
        st r8, [#4]
        st r12, [#5]
        pidx r13, #0
        stx r9, [r13 + 10]      ; per-PE address 10 + p
        ldx r14, [r13 + 9]
        cli c11, #4
        cli c12, #0
        xst [#2], ext[c12], c11
        xld [#20], ext[c12], c11
        cld c13, [#0]
        cadd c13, c13, c4
        cst c13, [#1]
        .phase out
        cli c1, #0
        vout #0, [#4], c1, c2
        cli c1, #1
        vout #1, [#3], c1, c2
        vout #0, [#5], c1, c2
        halt
)";

inline isa::MachineConfig config(int pes) {
    isa::MachineConfig c;
    c.pes = pes;
    c.mem_bytes = 64;
    c.ext_bytes = 32;
    c.watchdog_cycles = 1000000;
    return c;
}

inline itlm::ImageInput image(int w, int h, int seed) {
    itlm::ImageInput im;
    im.width = w;
    im.height = h;
    for (int i = 0; i < w * h; ++i) im.pixels.push_back(static_cast<uint8_t>(seed + 37 * i));
    return im;
}

inline const std::vector<std::pair<int, uint32_t>> kParams = {{0, 1000}, {7, 7}};
constexpr int kOutW = 8, kOutH = 2;

// The reference: the same program on a bare machine (built-in ring, status
// and video row copy).
struct Reference {
    std::unique_ptr<isa::Machine> m;
    isa::ImageVideoPort video;
};
inline std::unique_ptr<Reference> run_reference(const isa::MachineConfig& cfg,
                                                const isa::Program& prog,
                                                const itlm::ImageInput& left,
                                                const itlm::ImageInput& right) {
    auto r = std::make_unique<Reference>();
    r->m = std::make_unique<isa::Machine>(cfg);
    r->m->load(prog);
    for (const auto& [i, v] : kParams) r->m->set_param(i, v);
    r->video.input[0] = left;
    r->video.input[1] = right;
    r->video.make_output(0, kOutW, kOutH);
    r->video.make_output(1, kOutW, kOutH);
    r->m->set_video(&r->video);
    r->m->run();
    return r;
}

// Every piece of architectural state and accounting.
inline void check_same_state(const isa::Machine& a, const isa::Machine& b) {
    const int P = a.pes();
    BOOST_REQUIRE_EQUAL(P, b.pes());
    const auto lanes = [P](const uint8_t* p) { return std::vector<int>(p, p + P); };
    for (int r = 0; r < a.config().pe_regs; ++r) {
        BOOST_TEST_CONTEXT("r" << r) {
            BOOST_CHECK(lanes(a.reg_lanes(r)) == lanes(b.reg_lanes(r)));
        }
    }
    BOOST_CHECK(lanes(a.carry_lanes()) == lanes(b.carry_lanes()));
    BOOST_CHECK(lanes(a.test_lanes()) == lanes(b.test_lanes()));
    BOOST_CHECK(lanes(a.mask_lanes()) == lanes(b.mask_lanes()));
    BOOST_CHECK_EQUAL(a.mask_stack_size(), b.mask_stack_size());
    BOOST_CHECK_EQUAL(a.active_pes(), b.active_pes());
    const size_t mem = size_t{a.config().mem_bytes} * static_cast<size_t>(P);
    const size_t ext = size_t{a.config().ext_bytes} * static_cast<size_t>(P);
    BOOST_CHECK(std::vector<uint8_t>(a.mem_data(), a.mem_data() + mem) ==
                std::vector<uint8_t>(b.mem_data(), b.mem_data() + mem));
    BOOST_CHECK(std::vector<uint8_t>(a.ext_data(), a.ext_data() + ext) ==
                std::vector<uint8_t>(b.ext_data(), b.ext_data() + ext));
    for (int i = 0; i < isa::kCpRegs; ++i) BOOST_CHECK_EQUAL(a.cp(i), b.cp(i));
    BOOST_CHECK(a.params() == b.params());
    BOOST_CHECK_EQUAL(a.pc(), b.pc());
    BOOST_CHECK_EQUAL(a.halted(), b.halted());
    BOOST_CHECK_EQUAL(a.cycles(), b.cycles());
    BOOST_CHECK(a.phase_cycles() == b.phase_cycles());
    BOOST_CHECK_EQUAL(a.stats().instructions, b.stats().instructions);
    BOOST_CHECK(a.stats().class_cycles == b.stats().class_cycles);
    BOOST_CHECK(a.stats().op_counts == b.stats().op_counts);
    BOOST_CHECK_EQUAL(a.stats().pe_cycles, b.stats().pe_cycles);
    BOOST_CHECK_EQUAL(a.stats().active_lane_cycles, b.stats().active_lane_cycles);
}

inline uint64_t count(const isa::Stats& s, isa::Op o) {
    return s.op_counts[static_cast<uint8_t>(o)];
}

}  // namespace tlmtest
