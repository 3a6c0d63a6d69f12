// Executor semantics per instruction class on small machines, with
// hand-computed expectations; cycle accounting; faults.
#define BOOST_TEST_MODULE isa_machine
#include <boost/test/unit_test.hpp>

#include "helpers.hpp"

using namespace isatest;
using V = std::vector<int>;

namespace {
void set24(Machine& m, int pe, int r0, uint32_t v) {
    m.set_reg(pe, r0, static_cast<uint8_t>(v));
    m.set_reg(pe, r0 + 1, static_cast<uint8_t>(v >> 8));
    m.set_reg(pe, r0 + 2, static_cast<uint8_t>(v >> 16));
}
uint32_t get24(const Machine& m, int pe, int r0) {
    return m.reg(pe, r0) | m.reg(pe, r0 + 1) << 8 | m.reg(pe, r0 + 2) << 16;
}
}  // namespace

BOOST_AUTO_TEST_CASE(add_24bit_carry_chain) {
    const uint32_t A[] = {0x00FFFF, 0x123456, 0xFFFFFF, 0x0000FF};
    const uint32_t B[] = {0x000001, 0x654321, 0x000001, 0x000001};
    auto m = run(R"(
        add r0, r0, r3
        adc r1, r1, r4
        adc r2, r2, r5
        setc r6
        halt)",
                 small(4), [&](Machine& m) {
                     for (int p = 0; p < 4; ++p) {
                         set24(m, p, 0, A[p]);
                         set24(m, p, 3, B[p]);
                     }
                 });
    const uint32_t S[] = {0x010000, 0x777777, 0x000000, 0x000100};
    for (int p = 0; p < 4; ++p) BOOST_CHECK_EQUAL(get24(*m, p, 0), S[p]);
    BOOST_CHECK(lanes(*m, 6) == (V{0, 0, 1, 0}));
    BOOST_CHECK_EQUAL(m->cycles(), 5u);
}

BOOST_AUTO_TEST_CASE(sub_24bit_borrow_chain_and_immediates) {
    const uint32_t A[] = {0x010000, 0x000000, 0x123456, 5};
    const uint32_t B[] = {1, 1, 0x123456, 6};
    auto m = run(R"(
        sub r0, r0, r3
        sbc r1, r1, r4
        sbc r2, r2, r5
        setc r6
        ; 16-bit r8:r7 = 0x0100 - 1 with immediates
        li r7, #0
        li r8, #1
        subi r7, r7, #1
        sbci r8, r8, #0
        ; 0x00FF + 1 with addi/adci
        li r9, #0xFF
        li r10, #0
        addi r9, r9, #1
        adci r10, r10, #0
        halt)",
                 small(4), [&](Machine& m) {
                     for (int p = 0; p < 4; ++p) {
                         set24(m, p, 0, A[p]);
                         set24(m, p, 3, B[p]);
                     }
                 });
    const uint32_t D[] = {0x00FFFF, 0xFFFFFF, 0, 0xFFFFFF};
    for (int p = 0; p < 4; ++p) BOOST_CHECK_EQUAL(get24(*m, p, 0), D[p]);
    BOOST_CHECK(lanes(*m, 6) == (V{0, 1, 0, 1}));
    BOOST_CHECK(lanes(*m, 7) == (V{255, 255, 255, 255}));
    BOOST_CHECK(lanes(*m, 8) == (V{0, 0, 0, 0}));
    BOOST_CHECK(lanes(*m, 9) == (V{0, 0, 0, 0}));
    BOOST_CHECK(lanes(*m, 10) == (V{1, 1, 1, 1}));
}

BOOST_AUTO_TEST_CASE(logic_min_max_moves) {
    auto m = run(R"(
        pidx r0, #0          ; 0 1 2 3
        li r1, #2
        min r2, r0, r1       ; 0 1 2 2
        max r3, r0, r1       ; 2 2 2 3
        mini r4, r0, #1      ; 0 1 1 1
        maxi r5, r0, #250    ; 250...
        and r6, r0, r1       ; 0 0 2 2
        ori r7, r0, #0x10    ; 16 17 18 19
        xori r8, r0, #3      ; 3 2 1 0
        mov r9, r8
        halt)");
    BOOST_CHECK(lanes(*m, 2) == (V{0, 1, 2, 2}));
    BOOST_CHECK(lanes(*m, 3) == (V{2, 2, 2, 3}));
    BOOST_CHECK(lanes(*m, 4) == (V{0, 1, 1, 1}));
    BOOST_CHECK(lanes(*m, 5) == (V{250, 250, 250, 250}));
    BOOST_CHECK(lanes(*m, 6) == (V{0, 0, 2, 2}));
    BOOST_CHECK(lanes(*m, 7) == (V{16, 17, 18, 19}));
    BOOST_CHECK(lanes(*m, 9) == (V{3, 2, 1, 0}));
}

BOOST_AUTO_TEST_CASE(shifts_through_carry_multibyte) {
    // 16-bit values r1:r0 shifted left by one, then right by one, via C.
    auto m = run(R"(
        li r0, #0xC1
        li r1, #0x80
        shli r0, r0, #1      ; C = 1 (bit 7 of 0xC1)
        rolc r1, r1          ; 0x80 << 1 | 1 = 0x01, C = 1
        setc r2
        li r3, #0x81
        li r4, #0x01
        shri r4, r4, #1      ; C = 1
        rorc r3, r3          ; 0x81 >> 1 | 0x80 = 0xC0, C = 1
        setc r5
        li r6, #0x96
        shli r7, r6, #3      ; 0xB0, C = bit 5 of 0x96 = 0
        setc r8
        shri r9, r6, #2      ; 0x25, C = bit 1 = 1
        setc r10
        pidx r11, #0
        shlv r12, r6, r11    ; per PE: 0x96 << p
        shrv r13, r6, r11
        halt)");
    BOOST_CHECK(lanes(*m, 0) == (V{0x82, 0x82, 0x82, 0x82}));
    BOOST_CHECK(lanes(*m, 1) == (V{0x01, 0x01, 0x01, 0x01}));
    BOOST_CHECK(lanes(*m, 2) == (V{1, 1, 1, 1}));
    BOOST_CHECK(lanes(*m, 4) == (V{0, 0, 0, 0}));
    BOOST_CHECK(lanes(*m, 3) == (V{0xC0, 0xC0, 0xC0, 0xC0}));
    BOOST_CHECK(lanes(*m, 5) == (V{1, 1, 1, 1}));
    BOOST_CHECK(lanes(*m, 7) == (V{0xB0, 0xB0, 0xB0, 0xB0}));
    BOOST_CHECK(lanes(*m, 8) == (V{0, 0, 0, 0}));
    BOOST_CHECK(lanes(*m, 9) == (V{0x25, 0x25, 0x25, 0x25}));
    BOOST_CHECK(lanes(*m, 10) == (V{1, 1, 1, 1}));
    BOOST_CHECK(lanes(*m, 12) == (V{0x96, 0x2C, 0x58, 0xB0}));
    BOOST_CHECK(lanes(*m, 13) == (V{0x96, 0x4B, 0x25, 0x12}));
    // PE 3: 0x96 >> 3, last bit out = bit 2 = 1.
    BOOST_CHECK_EQUAL(m->carry_lanes()[3], 1);
}

BOOST_AUTO_TEST_CASE(compare_test_flag_and_selects) {
    auto m = run(R"(
        pidx r0, #0          ; 0 1 2 3
        li r1, #2
        cltu r0, r1          ; T = 1 1 0 0
        sett r2
        tsel r3, r0, r1      ; 0 1 2 2
        tnot
        sett r4              ; 0 0 1 1
        cgeui r0, #1         ; T = 0 1 1 1
        sett r5
        ceq r0, r1
        sett r6              ; 0 0 1 0
        cne r0, r1
        sett r7
        cleu r0, r1
        sett r8              ; 1 1 1 0
        cgtu r0, r1
        sett r9              ; 0 0 0 1
        ceqi r0, #3
        sett r10
        subi r11, r0, #2     ; C = borrow: 1 1 0 0
        csel r12, r1, r0     ; C ? 2 : p -> 2 2 2 3
        tc
        sett r13             ; 1 1 0 0
        halt)");
    BOOST_CHECK(lanes(*m, 2) == (V{1, 1, 0, 0}));
    BOOST_CHECK(lanes(*m, 3) == (V{0, 1, 2, 2}));
    BOOST_CHECK(lanes(*m, 4) == (V{0, 0, 1, 1}));
    BOOST_CHECK(lanes(*m, 5) == (V{0, 1, 1, 1}));
    BOOST_CHECK(lanes(*m, 6) == (V{0, 0, 1, 0}));
    BOOST_CHECK(lanes(*m, 7) == (V{1, 1, 0, 1}));
    BOOST_CHECK(lanes(*m, 8) == (V{1, 1, 1, 0}));
    BOOST_CHECK(lanes(*m, 9) == (V{0, 0, 0, 1}));
    BOOST_CHECK(lanes(*m, 10) == (V{0, 0, 0, 1}));
    BOOST_CHECK(lanes(*m, 12) == (V{2, 2, 2, 3}));
    BOOST_CHECK(lanes(*m, 13) == (V{1, 1, 0, 0}));
}

BOOST_AUTO_TEST_CASE(broadcast_constants_and_pe_index) {
    MachineConfig cfg = small(300);
    auto m = run(R"(
        cli c5, #0x11223344
        lc r0, c5
        lcb r1, c5, #2
        lcb r2, c5, #3
        pidx r3, #0
        pidx r4, #1
        pidx r5, #2
        halt)",
                 cfg);
    BOOST_CHECK_EQUAL(m->reg(7, 0), 0x44);
    BOOST_CHECK_EQUAL(m->reg(7, 1), 0x22);
    BOOST_CHECK_EQUAL(m->reg(7, 2), 0x11);
    BOOST_CHECK_EQUAL(m->reg(299, 3), 299 & 255);
    BOOST_CHECK_EQUAL(m->reg(299, 4), 1);
    BOOST_CHECK_EQUAL(m->reg(255, 4), 0);
    BOOST_CHECK_EQUAL(m->reg(256, 4), 1);
    BOOST_CHECK_EQUAL(m->reg(299, 5), 0);
}

BOOST_AUTO_TEST_CASE(nested_mif_melse_mend) {
    auto m = run(R"(
        pidx r0, #0
        li r1, #0
        cltui r0, #4         ; T = p < 4
        mif
          li r1, #1
          cltui r0, #2
          mif                ; p < 2
            li r1, #2
          melse              ; p = 2, 3
            li r1, #3
          mend
        melse                ; p >= 4
          li r1, #4
          ceqi r0, #6
          mif
            li r1, #6
          mend
        mend
        li r2, #9
        halt)",
                 small(8));
    BOOST_CHECK(lanes(*m, 1) == (V{2, 2, 3, 3, 4, 4, 6, 4}));
    BOOST_CHECK(lanes(*m, 2) == (V{9, 9, 9, 9, 9, 9, 9, 9}));
    BOOST_CHECK_EQUAL(m->mask_stack_size(), 0);
    BOOST_CHECK_EQUAL(m->active_pes(), 8);
}

BOOST_AUTO_TEST_CASE(masked_lanes_keep_flags_and_mall_clears_the_stack) {
    auto m = run(R"(
        pidx r0, #0
        ceqi r0, #1          ; T = 0 1 0 0
        mif                  ; only PE 1
          li r1, #7
          addi r2, r1, #250  ; 257: C = 1 on PE 1 only
          cltui r0, #9       ; T = 1 on PE 1 only (others keep 0)
          ceqi r0, #1
          mif
          mall               ; everything on, stack emptied
        setc r3
        sett r4
        li r5, #1
        halt)");
    BOOST_CHECK(lanes(*m, 1) == (V{0, 7, 0, 0}));
    BOOST_CHECK(lanes(*m, 3) == (V{0, 1, 0, 0}));
    BOOST_CHECK(lanes(*m, 4) == (V{0, 1, 0, 0}));
    BOOST_CHECK(lanes(*m, 5) == (V{1, 1, 1, 1}));
    BOOST_CHECK_EQUAL(m->mask_stack_size(), 0);
}

BOOST_AUTO_TEST_CASE(ring_wraps_both_ways_multi_hop) {
    MachineConfig cfg = small(5);
    auto setup = [](Machine& m) {
        for (int p = 0; p < 5; ++p) m.set_reg(p, 0, static_cast<uint8_t>(p * 10));
    };
    auto m = run(R"(
        rxl r1, r0, #1
        rxl r2, r0, #2
        rxr r3, r0, #1
        rxr r4, r0, #3
        rxl r5, r0, #7       ; 7 mod 5 = 2 hops around, 7 cycles
        rxr r6, r0, #5       ; full circle
        halt)",
                 cfg, setup);
    BOOST_CHECK(lanes(*m, 1) == (V{40, 0, 10, 20, 30}));
    BOOST_CHECK(lanes(*m, 2) == (V{30, 40, 0, 10, 20}));
    BOOST_CHECK(lanes(*m, 3) == (V{10, 20, 30, 40, 0}));
    BOOST_CHECK(lanes(*m, 4) == (V{30, 40, 0, 10, 20}));
    BOOST_CHECK(lanes(*m, 5) == (V{30, 40, 0, 10, 20}));
    BOOST_CHECK(lanes(*m, 6) == (V{0, 10, 20, 30, 40}));
    BOOST_CHECK_EQUAL(m->cycles(), 1u + 2 + 1 + 3 + 7 + 5 + 1);
    BOOST_CHECK_EQUAL(m->stats().class_cycles[static_cast<int>(CostClass::Ring)], 19u);

    // Masked PEs still drive the ring; only their write is suppressed.
    auto m2 = run(R"(
        pidx r9, #0
        cnei r9, #2
        mif
          rxl r0, r0, #1
        mend
        halt)",
                  cfg, setup);
    BOOST_CHECK(lanes(*m2, 0) == (V{40, 0, 20, 20, 30}));

    cfg.costs.ring_hop = 3;
    auto m3 = run("rxr r1, r0, #2\nhalt", cfg, setup);
    BOOST_CHECK_EQUAL(m3->cycles(), 6u + 1);
}

BOOST_AUTO_TEST_CASE(broadcast_load_store_masked) {
    auto m = run(R"(
        cli c1, #2
        pidx r0, #0
        addi r0, r0, #100
        st r0, [c1 + 3]      ; row 5 = 100 101 102 103
        ceqi r0, #102
        mif
          li r1, #77
          st r1, [c1 + 3]    ; only PE 2 overwritten
          st r1, [#9]
        mend
        ld r2, [c1 + 3]
        ld r3, [#5]
        ld r4, [c1 - 2]      ; row 0 (never written) = 0
        halt)");
    for (int p = 0; p < 4; ++p) BOOST_CHECK_EQUAL(m->mem_read(p, 5), p == 2 ? 77 : 100 + p);
    BOOST_CHECK(lanes(*m, 2) == (V{100, 101, 77, 103}));
    BOOST_CHECK(lanes(*m, 3) == (V{100, 101, 77, 103}));
    BOOST_CHECK(lanes(*m, 4) == (V{0, 0, 0, 0}));
    BOOST_CHECK_EQUAL(m->mem_read(2, 9), 77);
    BOOST_CHECK_EQUAL(m->mem_read(1, 9), 0);
    // Address-major layout: row 5 is one contiguous P-byte run.
    BOOST_CHECK_EQUAL(m->mem_data()[5 * 4 + 3], 103);
}

BOOST_AUTO_TEST_CASE(indirect_load_store_per_pe) {
    auto setup = [](Machine& m) {
        for (int p = 0; p < 4; ++p)
            m.mem_write(p, static_cast<uint32_t>(100 + 3 * p), static_cast<uint8_t>(50 + p));
    };
    auto m = run(R"(
        pidx r0, #0
        add r1, r0, r0
        add r1, r1, r0       ; 3p
        cli c2, #100
        ldx r2, [r1 + c2]    ; mem[100 + 3p] = 50 + p
        li r3, #1
        stx r2, [r1:r3 + 4]  ; mem[256 + 3p + 4]
        ldx r4, [r1:r3 + c2 - 96]
        ceqi r0, #0
        mif
          li r5, #200
          stx r5, [r5 + 7]   ; only PE 0 stores (207)
        mend
        halt)",
                 small(4), setup);
    BOOST_CHECK(lanes(*m, 2) == (V{50, 51, 52, 53}));
    for (int p = 0; p < 4; ++p) BOOST_CHECK_EQUAL(m->mem_read(p, 260 + 3 * p), 50 + p);
    BOOST_CHECK(lanes(*m, 4) == (V{50, 51, 52, 53}));
    BOOST_CHECK_EQUAL(m->mem_read(0, 207), 200);
    BOOST_CHECK_EQUAL(m->mem_read(1, 207), 0);
    // ldx / stx cost mem + indirect_extra = 2 each.
    BOOST_CHECK_EQUAL(m->stats().class_cycles[static_cast<int>(CostClass::Indirect)], 8u);
}

BOOST_AUTO_TEST_CASE(indirect_faults_name_the_pe_and_masked_lanes_do_not_fault) {
    MachineConfig cfg = small(4);
    cfg.mem_bytes = 64;
    Machine m(cfg);
    m.load(assemble_string(R"(
        pidx r0, #0
        li r1, #0
        ceqi r0, #3
        tnot
        mif                  ; PE 3 masked off
          shli r1, r0, #5    ; 0 32 64 96 (PE 3 keeps 0)
          li r2, #60
          ldx r3, [r2]       ; fine
          ceqi r0, #2
          mif                ; PE 2: 64 + 0 -> out of range
            ldx r3, [r1 + 0]
          mend
        mend
        halt)",
                           "ind.s"));
    try {
        m.run();
        BOOST_FAIL("expected a fault");
    } catch (const Fault& f) {
        BOOST_CHECK_EQUAL(f.pc(), 10u);
        BOOST_CHECK_EQUAL(f.pe(), 2);
        BOOST_CHECK_EQUAL(f.address(), 64);
        const std::string w = f.what();
        BOOST_CHECK_MESSAGE(w.find("ind.s:12") != std::string::npos, w);
        BOOST_CHECK_MESSAGE(w.find("PE 2") != std::string::npos, w);
        BOOST_CHECK_MESSAGE(w.find("64 bytes") != std::string::npos, w);
    }
    BOOST_CHECK_EQUAL(m.pc(), 10u);

    cfg.indirect = false;
    Machine off(cfg);
    try {
        off.load(assemble_string("nop\nldx r1, [r2]\nhalt", "x.s"));
        BOOST_FAIL("expected a load error");
    } catch (const LoadError& e) {
        BOOST_CHECK_EQUAL(e.pc(), 1u);
        BOOST_CHECK_MESSAGE(std::string(e.what()).find("indirect = off") != std::string::npos,
                            e.what());
    }
}

BOOST_AUTO_TEST_CASE(status_over_the_mask_bus) {
    auto m = run(R"(
        pidx r0, #0
        ceqi r0, #2
        rany c1              ; 1
        rall c2              ; 0
        mif
          rall c3            ; only PE 2 active, T = 1 -> 1
        mend
        ceqi r0, #9          ; T = 0 everywhere
        rany c4              ; 0
        mif                  ; nobody active
          rall c5            ; 1 (empty AND)
          rany c6            ; 0
        mend
        cgeui r0, #0
        rall c7              ; 1
        halt)");
    BOOST_CHECK_EQUAL(m->cp(1), 1u);
    BOOST_CHECK_EQUAL(m->cp(2), 0u);
    BOOST_CHECK_EQUAL(m->cp(3), 1u);
    BOOST_CHECK_EQUAL(m->cp(4), 0u);
    BOOST_CHECK_EQUAL(m->cp(5), 1u);
    BOOST_CHECK_EQUAL(m->cp(6), 0u);
    BOOST_CHECK_EQUAL(m->cp(7), 1u);
}

BOOST_AUTO_TEST_CASE(cp_alu_branches_loop_and_cycle_count) {
    auto m = run(R"(
        cli c0, #10
        cli c1, #0
    sum:
        cadd c1, c1, c0
        loop c0, sum
        halt)");
    BOOST_CHECK_EQUAL(m->cp(1), 55u);
    BOOST_CHECK_EQUAL(m->cp(0), 0u);
    // 2 cli + 10 cadd + 10 loop (9 taken: +1 each) + halt
    BOOST_CHECK_EQUAL(m->cycles(), 2u + 10 + 10 + 9 + 1);
    BOOST_CHECK_EQUAL(m->stats().instructions, 23u);

    auto b = run(R"(
        cli c0, #-1
        cli c1, #1
        cli c9, #0
        blt c0, c1, a        ; signed: taken
        ori_fail: cori c9, c9, #1
    a:  bge c0, c1, fail     ; not taken
        bge c1, c0, b2       ; taken
        jmp fail
    b2: beq c0, c0, b3
        jmp fail
    b3: bne c0, c1, b4
        jmp fail
    b4: bz c9, b5
        jmp fail
    b5: bnz c0, b6
        jmp fail
    b6: cli c2, #0x80000010
        csrai c3, c2, #4     ; 0xF8000001
        cshri c4, c2, #4     ; 0x08000001
        cshli c5, c2, #1     ; 0x00000020
        csubi c6, c1, #3     ; -2
        cxori c7, c6, #-1    ; 1
        candi c8, c2, #0xFF  ; 0x10
        cmov c10, c8
        csub c11, c1, c0     ; 2
        cxor c12, c11, c1    ; 3
        cor c13, c12, c8     ; 0x13
        cand c14, c13, c12   ; 3
        caddi c15, c14, #100
        call sub
        call sub
        halt
    sub:
        caddi c9, c9, #10
        ret
    fail:
        cli c9, #999
        halt)");
    BOOST_CHECK_EQUAL(b->cp(3), 0xF8000001u);
    BOOST_CHECK_EQUAL(b->cp(4), 0x08000001u);
    BOOST_CHECK_EQUAL(b->cp(5), 0x20u);
    BOOST_CHECK_EQUAL(b->cp(6), 0xFFFFFFFEu);
    BOOST_CHECK_EQUAL(b->cp(7), 1u);
    BOOST_CHECK_EQUAL(b->cp(8), 0x10u);
    BOOST_CHECK_EQUAL(b->cp(10), 0x10u);
    BOOST_CHECK_EQUAL(b->cp(11), 2u);
    BOOST_CHECK_EQUAL(b->cp(12), 3u);
    BOOST_CHECK_EQUAL(b->cp(13), 0x13u);
    BOOST_CHECK_EQUAL(b->cp(14), 3u);
    BOOST_CHECK_EQUAL(b->cp(15), 103u);
    BOOST_CHECK_EQUAL(b->cp(9), 20u);
    BOOST_CHECK_EQUAL(b->call_stack_size(), 0);
}

BOOST_AUTO_TEST_CASE(param_block) {
    auto m = run(R"(
        cld c3, [#5]
        cli c4, #1
        cst c3, [c4 + 7]
        cld c5, [c4 + 7]
        halt)",
                 small(), [](Machine& m) { m.set_param(5, 1234); });
    BOOST_CHECK_EQUAL(m->cp(3), 1234u);
    BOOST_CHECK_EQUAL(m->param(8), 1234u);
    BOOST_CHECK_EQUAL(m->cp(5), 1234u);
    // reset keeps the param block (written by the host before the run).
    m->reset();
    BOOST_CHECK_EQUAL(m->param(5), 1234u);
    BOOST_CHECK_EQUAL(m->cp(3), 0u);
}

// The variable-cost classes: shifter width, min/max select, shared external path.
BOOST_AUTO_TEST_CASE(shifter_minmax_and_transfer_costs) {
    auto cycles_of = [](const std::string& instr, MachineConfig cfg) {
        cfg.ext_bytes = 64;
        auto m = run("cli c2, #5\n" + instr + "\nhalt", cfg);
        return m->cycles() - 2 * cfg.costs.cp;  // less the cli and the halt
    };
    MachineConfig barrel = small(4);
    BOOST_CHECK_EQUAL(cycles_of("shli r1, r2, #5", barrel), 1u);
    BOOST_CHECK_EQUAL(cycles_of("shrv r1, r2, r3", barrel), 1u);
    MachineConfig serial = small(4);
    serial.costs.shift_bits = 1;
    BOOST_CHECK_EQUAL(cycles_of("shli r1, r2, #5", serial), 5u);
    BOOST_CHECK_EQUAL(cycles_of("shri r1, r2, #0", serial), 1u);
    BOOST_CHECK_EQUAL(cycles_of("shlv r1, r2, r3", serial), 7u);  // worst lane
    BOOST_CHECK_EQUAL(cycles_of("rolc r1, r2", serial), 1u);      // one bit: the ALU
    MachineConfig two = small(4);
    two.costs.shift_bits = 2;
    two.costs.alu = 3;
    BOOST_CHECK_EQUAL(cycles_of("shli r1, r2, #5", two), 3u + 2u);  // alu + ceil(5/2) - 1
    MachineConfig mm = small(4);
    mm.costs.minmax_extra = 1;
    BOOST_CHECK_EQUAL(cycles_of("min r1, r2, r3", mm), 2u);
    BOOST_CHECK_EQUAL(cycles_of("maxi r1, r2, #7", mm), 2u);
    BOOST_CHECK_EQUAL(cycles_of("add r1, r2, r3", mm), 1u);
    MachineConfig x = small(4);
    x.costs.ext_bytes_per_cycle = 3;
    // 4 PEs x 5 bytes = 20 bytes at 3 per cycle = 7 cycles after the 8-cycle setup
    BOOST_CHECK_EQUAL(cycles_of("xld [#0], ext[c2], c2", x), 8u + 7u);
    x.costs.ext_bytes_per_cycle = 1000;
    BOOST_CHECK_EQUAL(cycles_of("xst [#0], ext[c2], c2", x), 8u + 1u);
}

BOOST_AUTO_TEST_CASE(external_memory_block_transfer) {
    MachineConfig cfg = small(4);
    cfg.ext_bytes = 64;
    auto m = run(R"(
        cli c1, #10          ; ext address
        cli c2, #4           ; length
        cli c3, #20          ; local base
        pidx r0, #0
        ceqi r0, #0
        xld [c3 + 1], ext[c1], c2
        cli c1, #40
        xst [c3 + 1], ext[c1], c2
        mif                  ; PE 0 only: the other PEs keep their bytes
          cli c1, #50
          xst [c3 + 1], ext[c1], c2
          cli c1, #10
          xld [c3 + 30], ext[c1], c2
        mend
        halt)",
                 cfg, [](Machine& m) {
                     for (int p = 0; p < 4; ++p)
                         for (int i = 0; i < 4; ++i)
                             m.ext_write(p, static_cast<uint32_t>(10 + i),
                                         static_cast<uint8_t>(p * 16 + i));
                 });
    for (int p = 0; p < 4; ++p)
        for (int i = 0; i < 4; ++i) {
            BOOST_CHECK_EQUAL(m->mem_read(p, static_cast<uint32_t>(21 + i)), p * 16 + i);
            BOOST_CHECK_EQUAL(m->ext_read(p, static_cast<uint32_t>(40 + i)), p * 16 + i);
            BOOST_CHECK_EQUAL(m->ext_read(p, static_cast<uint32_t>(50 + i)), p == 0 ? i : 0);
            BOOST_CHECK_EQUAL(m->mem_read(p, static_cast<uint32_t>(50 + i)), p == 0 ? i : 0);
        }
    // all 4 PEs x 4 bytes = 16 bytes over the shared 8-byte/cycle path: 2 cycles after
    // the setup; PE 0 alone: 4 bytes, 1 cycle
    BOOST_CHECK_EQUAL(m->stats().class_cycles[static_cast<int>(CostClass::Xfer)],
                      2u * (8 + 2) + 2u * (8 + 1));

    auto fault_text = [&](const std::string& src, MachineConfig c) {
        try {
            run(src, c);
        } catch (const Fault& f) {
            return std::string(f.what());
        }
        return std::string("no fault");
    };
    const std::string big =
        fault_text("cli c2, #60\ncli c1, #10\nxld [#0], ext[c1], c2\nhalt", cfg);
    BOOST_CHECK_MESSAGE(big.find("external range 10..69") != std::string::npos, big);
    const std::string neg = fault_text("cli c2, #-1\nxld [#0], ext[c1], c2\nhalt", cfg);
    BOOST_CHECK_MESSAGE(neg.find("negative length") != std::string::npos, neg);
    cfg.ext_bytes = 0;
    const std::string off = fault_text("xst [#0], ext[c1], c2\nhalt", cfg);
    BOOST_CHECK_MESSAGE(off.find("external memory disabled") != std::string::npos, off);
}

BOOST_AUTO_TEST_CASE(video_line_io) {
    ImageVideoPort video;
    video.input[1].width = 6;
    video.input[1].height = 3;
    for (int i = 0; i < 18; ++i) video.input[1].pixels.push_back(static_cast<uint8_t>(i + 1));
    video.make_output(0, 6, 3);
    Machine m(small(4));
    m.set_video(&video);
    m.load(assemble_string(R"(
        cli c2, #1           ; line
        cli c3, #4           ; first column
        cli c4, #0
        vin #1, [c4 + 3], c2, c3     ; pixels 4, 5 then beyond the width: 0
        vin #1, [#4], c2, c4         ; pixels 0..3
        cli c5, #2
        vout #0, [#4], c5, c3        ; columns 4..7 of output line 2: 4, 5 kept
        halt)"));
    m.run();
    BOOST_CHECK(flags(m.mem_data() + 3 * 4, 4) == (V{11, 12, 0, 0}));
    BOOST_CHECK(flags(m.mem_data() + 4 * 4, 4) == (V{7, 8, 9, 10}));
    BOOST_CHECK(std::vector<int>(video.output[0].pixels.begin() + 12,
                                 video.output[0].pixels.end()) == (V{0, 0, 0, 0, 7, 8}));
    BOOST_CHECK_EQUAL(m.cycles(), 8u);

    Machine bad(small(4));
    bad.set_video(&video);
    bad.load(assemble_string("cli c2, #3\nvin #0, [#0], c2, c3\nhalt", "v.s"));
    BOOST_CHECK_EXCEPTION(bad.run(), Fault, [](const Fault& f) {
        return f.pc() == 1 &&
               std::string(f.what()).find("line outside input image 0") != std::string::npos;
    });
    Machine none(small(4));
    none.load(assemble_string("vout #0, [#0], c2, c3\nhalt"));
    BOOST_CHECK_EXCEPTION(none.run(), Fault, [](const Fault& f) {
        return std::string(f.what()).find("no video port") != std::string::npos;
    });
}

BOOST_AUTO_TEST_CASE(phase_accounting) {
    auto m = run(R"(
        nop                  ; default: 1
        .phase load
        nop
        nop                  ; load: 2
        .phase compute
        add r0, r0, r0
        rxl r1, r0, #3       ; compute: 4
        .phase load
        nop                  ; load: 3
        .phase default
        halt                 ; default: 2
    )");
    const Program& p = m->program();
    BOOST_REQUIRE_EQUAL(p.phases.size(), 3u);
    BOOST_CHECK_EQUAL(p.phases[1], "load");
    BOOST_CHECK_EQUAL(p.phases[2], "compute");
    BOOST_CHECK(m->phase_cycles() == (std::vector<uint64_t>{2, 3, 4}));
    BOOST_CHECK_EQUAL(m->cycles(), 9u);
    BOOST_CHECK_EQUAL(m->stats().class_cycles[static_cast<int>(CostClass::Phase)], 0u);
}

BOOST_AUTO_TEST_CASE(cost_table_changes_the_cycle_count) {
    const std::string src = R"(
        cli c0, #3
    l:  add r0, r0, r1
        ld r2, [#1]
        ldx r3, [r2]
        mif
        mend
        rany c1
        loop c0, l
        halt)";
    auto base = run(src);
    // cli 1 + 3 x (alu 1 + mem 1 + ldx 2 + mask 2 + status 1 + loop 1) + 2 taken + halt 1
    BOOST_CHECK_EQUAL(base->cycles(), 1u + 3 * 8 + 2 + 1);
    MachineConfig cfg = small();
    cfg.costs.set("alu", 2);
    cfg.costs.set("mem", 3);
    cfg.costs.set("indirect_extra", 4);
    cfg.costs.set("mask", 5);
    cfg.costs.set("status", 6);
    cfg.costs.set("cp", 7);
    cfg.costs.set("branch_taken", 0);
    auto m = run(src, cfg);
    // cli 7 + 3 x (2 + 3 + 7 + 10 + 6 + 7) + halt 7
    BOOST_CHECK_EQUAL(m->cycles(), 7u + 3 * 35 + 7);
    uint64_t sum = 0;
    for (uint64_t c : m->stats().class_cycles) sum += c;
    BOOST_CHECK_EQUAL(sum, m->cycles());
}

BOOST_AUTO_TEST_CASE(utilisation_counts_active_lanes) {
    auto m = run(R"(
        pidx r0, #0          ; 4 active x 1
        cltui r0, #2         ; 4 x 1
        mif
          add r1, r1, r1     ; 2 active x 1
        mend
        halt)");
    BOOST_CHECK_EQUAL(m->stats().pe_cycles, 3u);
    BOOST_CHECK_EQUAL(m->stats().active_lane_cycles, 10u);
}

namespace {
std::string fault_of(const std::string& src, MachineConfig cfg = small()) {
    Machine m(cfg);
    m.load(assemble_string(src, "f.s"));
    try {
        m.run();
    } catch (const Fault& f) {
        return f.what();
    }
    return "no fault";
}
std::string load_error_of(const std::string& src, MachineConfig cfg = small()) {
    Machine m(cfg);
    try {
        m.load(assemble_string(src, "l.s"));
    } catch (const LoadError& e) {
        return e.what();
    }
    return "loaded";
}
bool has(const std::string& s, const std::string& part) {
    if (s.find(part) != std::string::npos) return true;
    BOOST_TEST_MESSAGE("'" << s << "' lacks '" << part << "'");
    return false;
}
}  // namespace

BOOST_AUTO_TEST_CASE(bad_address_fault_is_precise) {
    Machine m(small());
    m.load(assemble_string("li r1, #5\nld r1, [#1024]\nhalt", "f.s"));
    try {
        m.run();
        BOOST_FAIL("no fault");
    } catch (const Fault& f) {
        BOOST_CHECK_EQUAL(f.pc(), 1u);
        BOOST_CHECK_EQUAL(f.address(), 1024);
        BOOST_CHECK_EQUAL(f.pe(), Fault::kNone);
        BOOST_CHECK_EQUAL(f.cycle(), 1u);
        BOOST_CHECK(has(f.what(), "fault at pc 1 (f.s:2), cycle 1: ld: address 1024 out of range"));
        BOOST_CHECK(has(f.what(), "1024 bytes per PE"));
    }
    BOOST_CHECK(lanes(m, 1) == (V{5, 5, 5, 5}));  // state as before the faulting instruction
    BOOST_CHECK_EQUAL(m.cycles(), 1u);
    BOOST_CHECK(has(fault_of("cli c1, #-3\nst r0, [c1 + 1]\nhalt"), "st: address -2"));
    BOOST_CHECK(
        has(fault_of("cld c1, [#256]\nhalt"), "param block address 256 out of range 0..255"));
}

BOOST_AUTO_TEST_CASE(stack_faults) {
    BOOST_CHECK(has(fault_of("mend\nhalt"), "mend: mask stack underflow"));
    BOOST_CHECK(has(fault_of("melse\nhalt"), "melse: mask stack underflow"));
    MachineConfig c = small();
    c.mask_depth = 2;
    BOOST_CHECK(has(fault_of("mif\nmif\nmif\nhalt", c), "fault at pc 2 (f.s:3)"));
    BOOST_CHECK(has(fault_of("mif\nmif\nmif\nhalt", c), "mask stack overflow (mask_depth = 2)"));
    BOOST_CHECK(has(fault_of("ret\nhalt"), "ret: return stack underflow"));
    c.call_depth = 3;
    BOOST_CHECK(has(fault_of("f: call f\nhalt", c), "return stack overflow (call_depth = 3)"));
}

BOOST_AUTO_TEST_CASE(runaway_and_end_of_program) {
    MachineConfig c = small();
    c.watchdog_cycles = 1000;
    const std::string w = fault_of("spin: jmp spin", c);
    BOOST_CHECK(has(w, "watchdog: no halt after 1000 cycles (watchdog_cycles = 1000)"));
    BOOST_CHECK(has(fault_of("nop\nnop"), "ran past the end of the program (2 instructions)"));

    Machine m(c);
    m.load(assemble_string("spin: jmp spin"));
    const RunResult r = m.run(100);
    BOOST_CHECK(r.status == RunStatus::CycleLimit);
    BOOST_CHECK_EQUAL(r.cycles, 100u);
    BOOST_CHECK_THROW(m.run(), Fault);
}

BOOST_AUTO_TEST_CASE(load_errors_name_the_pc) {
    BOOST_CHECK(has(load_error_of("nop\n.word 0xFF\nhalt"), "pc 1 (l.s:2)"));
    BOOST_CHECK(has(load_error_of("nop\n.word 0xFF\nhalt"), "unknown opcode 0xff"));
    BOOST_CHECK(has(load_error_of("add r1, r2, r20\nhalt"),
                    "add: register r20 (field rb) does not exist on this machine (pe_regs = 16)"));
    BOOST_CHECK(has(load_error_of("jmp 7\nhalt"), "jmp: target 7 outside the program (0..1)"));
    BOOST_CHECK(has(load_error_of("phase #3\nhalt"), "phase id 3 has no name"));
    // A reserved field that is not zero: add with an immediate.
    BOOST_CHECK(
        has(load_error_of(".word 0x0000000503020140\nhalt"), "add: unused field imm must be 0"));
    MachineConfig c = small();
    c.pe_regs = 64;
    BOOST_CHECK_EQUAL(load_error_of("add r63, r62, r61\nhalt", c), "loaded");
}

BOOST_AUTO_TEST_CASE(step_and_observer) {
    struct Rec : Observer {
        std::vector<uint32_t> pcs;
        uint64_t cycles = 0;
        void on_instruction(const Machine&, const TraceEvent& e) override {
            pcs.push_back(e.pc);
            cycles += e.cycle_after - e.cycle_before;
        }
    } rec;
    Machine m(small());
    m.load(assemble_string("cli c0, #2\nl: rxl r0, r0, #2\nloop c0, l\nhalt"));
    const StepResult s = m.step();
    BOOST_CHECK_EQUAL(s.cycles, 1u);
    BOOST_CHECK_EQUAL(s.pc, 1u);
    m.set_observer(&rec);
    m.run();
    BOOST_CHECK(rec.pcs == (std::vector<uint32_t>{1, 2, 1, 2, 3}));
    BOOST_CHECK_EQUAL(rec.cycles, m.cycles() - 1);
    BOOST_CHECK(m.halted());
    BOOST_CHECK(m.step().halted);
}

BOOST_AUTO_TEST_CASE(debug_accessors_check_ranges) {
    Machine m(small());
    BOOST_CHECK_THROW(m.mem_read(4, 0), std::out_of_range);
    BOOST_CHECK_THROW(m.mem_read(0, 1024), std::out_of_range);
    BOOST_CHECK_THROW(m.ext_write(0, 256, 1), std::out_of_range);
    BOOST_CHECK_THROW(m.reg(0, 16), std::out_of_range);
    BOOST_CHECK_THROW(m.cp(16), std::out_of_range);
    BOOST_CHECK_THROW(m.set_param(256, 0), std::out_of_range);
}
