// Every SIMD path of the executor (machine.hpp, SimdPath) gives the same
// state as the baseline path, and the run loop's straight-line runs give the
// same state, cycles and statistics as single steps and as runs cut by cycle
// limits. Random programs use every PE opcode, masked and unmasked (mif /
// melse / mend / mall around them, host-written masks), the ring, ldx / stx,
// xld / xst, branches, calls and phases, on array sizes with and without a
// partial 64-lane chunk. Paths this CPU cannot run are reported and skipped
// (the baseline always runs), so the outcome does not depend on the CPU.
#define BOOST_TEST_MODULE isa_simd_paths
#include <boost/test/unit_test.hpp>
#include <random>

#include "helpers.hpp"

using namespace isatest;

namespace {

// The complete architectural state plus the counters.
struct Snapshot {
    std::vector<uint8_t> lanes, mem, ext;
    std::vector<uint32_t> cp, params;
    std::vector<uint64_t> phase_cycles;
    uint64_t cycles = 0;
    uint32_t pc = 0;
    bool halted = false;
    int msp = 0, active = 0, csp = 0;
    Stats stats;
    std::string fault;

    bool operator==(const Snapshot& o) const {
        return lanes == o.lanes && mem == o.mem && ext == o.ext && cp == o.cp &&
               params == o.params && phase_cycles == o.phase_cycles && cycles == o.cycles &&
               pc == o.pc && halted == o.halted && msp == o.msp && active == o.active &&
               csp == o.csp && fault == o.fault && stats.instructions == o.stats.instructions &&
               stats.class_cycles == o.stats.class_cycles && stats.op_counts == o.stats.op_counts &&
               stats.pe_cycles == o.stats.pe_cycles &&
               stats.active_lane_cycles == o.stats.active_lane_cycles;
    }
};

Snapshot snap(const Machine& m, const std::string& fault = "") {
    Snapshot s;
    const int P = m.pes();
    const MachineConfig& c = m.config();
    auto put = [&](const uint8_t* p) { s.lanes.insert(s.lanes.end(), p, p + P); };
    for (int r = 0; r < c.pe_regs; ++r) put(m.reg_lanes(r));
    put(m.carry_lanes());
    put(m.test_lanes());
    put(m.mask_lanes());
    for (int l = 0; l < m.mask_stack_size(); ++l) put(m.mask_stack_lanes(l));
    s.mem.assign(m.mem_data(), m.mem_data() + size_t{c.mem_bytes} * P);
    s.ext.assign(m.ext_data(), m.ext_data() + size_t{c.ext_bytes} * P);
    for (int i = 0; i < kCpRegs; ++i) s.cp.push_back(m.cp(i));
    s.params.assign(m.params().begin(), m.params().end());
    s.phase_cycles = m.phase_cycles();
    s.cycles = m.cycles();
    s.pc = m.pc();
    s.halted = m.halted();
    s.msp = m.mask_stack_size();
    s.active = m.active_pes();
    s.csp = m.call_stack_size();
    s.stats = m.stats();
    s.fault = fault;
    return s;
}

Word w(Op op, int rd = 0, int ra = 0, int rb = 0, uint32_t imm = 0) {
    Word x;
    x.op = static_cast<uint8_t>(op);
    x.rd = static_cast<uint8_t>(rd);
    x.ra = static_cast<uint8_t>(ra);
    x.rb = static_cast<uint8_t>(rb);
    x.imm = imm;
    return x;
}

// A random program over every PE opcode. Registers r0..r11 are written at
// random; r12 holds 0/1 (high byte of ldx / stx offsets), c2 = 5 (ldx CP
// base). Local memory 1024 bytes, external 256.
Program random_program(std::mt19937& rng, bool with_fault) {
    auto R = [&](int n) { return static_cast<int>(rng() % static_cast<unsigned>(n)); };
    auto reg = [&]() { return R(12); };
    std::vector<Word> code;
    auto emit = [&](Word x) { code.push_back(x); };
    emit(w(Op::CLI, 1, 0, 0, 3));  // outer loop count
    emit(w(Op::CLI, 2, 0, 0, 5));
    emit(w(Op::CLI, 3, 0, 0, 0x01020304));
    const uint32_t loop_top = static_cast<uint32_t>(code.size());
    emit(w(Op::PHASE, 0, 0, 0, 1));
    std::vector<int> fixups;  // call sites
    int depth = 0;
    const int body = 260;
    for (int i = 0; i < body; ++i) {
        const int k = R(40);
        if (k < 10) {  // register-register ALU, shifts, selects
            static const Op ops[] = {Op::ADD,  Op::ADC,  Op::SUB, Op::SBC, Op::AND,
                                     Op::OR,   Op::XOR,  Op::MIN, Op::MAX, Op::SHLV,
                                     Op::SHRV, Op::CSEL, Op::TSEL};
            emit(w(ops[R(13)], reg(), reg(), reg()));
        } else if (k < 16) {  // immediates and fixed shifts
            static const Op ops[] = {Op::ADDI, Op::ADCI, Op::SUBI, Op::SBCI, Op::ANDI, Op::ORI,
                                     Op::XORI, Op::MINI, Op::MAXI, Op::SHLI, Op::SHRI};
            const Op o = ops[R(11)];
            const bool sh = o == Op::SHLI || o == Op::SHRI;
            emit(w(o, reg(), reg(), 0, static_cast<uint32_t>(sh ? R(8) : R(256))));
        } else if (k < 19) {  // compares
            static const Op rr[] = {Op::CEQ, Op::CNE, Op::CLTU, Op::CLEU, Op::CGTU, Op::CGEU};
            static const Op ri[] = {Op::CEQI, Op::CNEI, Op::CLTUI, Op::CLEUI, Op::CGTUI, Op::CGEUI};
            if (R(2))
                emit(w(rr[R(6)], 0, reg(), reg()));
            else
                emit(w(ri[R(6)], 0, reg(), 0, static_cast<uint32_t>(R(256))));
        } else if (k < 22) {  // moves and flags
            switch (R(10)) {
                case 0:
                    emit(w(Op::MOV, reg(), reg()));
                    break;
                case 1:
                    emit(w(Op::LI, reg(), 0, 0, static_cast<uint32_t>(R(256))));
                    break;
                case 2:
                    emit(w(Op::LC, reg(), 3));
                    break;
                case 3:
                    emit(w(Op::LCB, reg(), 3, 0, static_cast<uint32_t>(R(4))));
                    break;
                case 4:
                    emit(w(Op::PIDX, reg(), 0, 0, static_cast<uint32_t>(R(4))));
                    break;
                case 5:
                    emit(w(Op::SETC, reg()));
                    break;
                case 6:
                    emit(w(Op::SETT, reg()));
                    break;
                case 7:
                    emit(w(Op::TC));
                    break;
                case 8:
                    emit(w(Op::TNOT));
                    break;
                default:
                    emit(w(R(2) ? Op::ROLC : Op::RORC, reg(), reg()));
            }
        } else if (k < 25) {  // broadcast memory
            emit(w(R(2) ? Op::LD : Op::ST, reg(), 0, kNoBase, static_cast<uint32_t>(R(1024))));
        } else if (k < 28) {  // per-PE memory: offsets 0..511 (+ 5 with c2)
            const Op o = R(2) ? Op::LDX : Op::STX;
            switch (R(3)) {
                case 0:
                    emit(w(o, reg(), reg(), 12, static_cast<uint32_t>(R(500))));
                    break;
                case 1:
                    emit(w(o, reg(), reg(), 0, kLdxNoHigh | static_cast<uint32_t>(R(700))));
                    break;
                default:
                    emit(w(o, reg(), reg(), 12,
                           kLdxUseCp | (2u << kLdxCpShift) | static_cast<uint32_t>(R(500))));
            }
        } else if (k < 29) {  // external memory: c4 = ext address, c5 = length
            emit(w(Op::CLI, 4, 0, 0, static_cast<uint32_t>(R(250))));
            emit(w(Op::CLI, 5, 0, 0, static_cast<uint32_t>(R(6))));
            emit(w(R(2) ? Op::XLD : Op::XST, 5, 4, kNoBase, static_cast<uint32_t>(R(1000))));
        } else if (k < 31) {  // ring
            emit(w(R(2) ? Op::RXL : Op::RXR, reg(), reg(), 0, static_cast<uint32_t>(1 + R(300))));
        } else if (k < 35) {  // mask
            const int c = R(4);
            if (c == 0 && depth < 6) {
                emit(w(Op::MIF));
                ++depth;
            } else if (c == 1 && depth > 0) {
                emit(w(Op::MELSE));
            } else if (c == 2 && depth > 0) {
                emit(w(Op::MEND));
                --depth;
            } else if (depth == 0) {
                emit(w(Op::MALL));
            } else {
                emit(w(Op::MEND));
                --depth;
            }
        } else if (k < 37) {  // status, CP arithmetic, a branch to the next instruction
            emit(w(R(2) ? Op::RANY : Op::RALL, 6));
            emit(w(Op::CADDI, 7, 7, 0, static_cast<uint32_t>(R(1000))));
            const uint32_t next = static_cast<uint32_t>(code.size() + 1);
            emit(w(R(2) ? Op::BZ : Op::BNZ, 0, 6, 0, next));
        } else if (k < 38) {
            fixups.push_back(static_cast<int>(code.size()));
            emit(w(Op::CALL));
        } else {
            emit(w(Op::PHASE, 0, 0, 0, static_cast<uint32_t>(R(3))));
        }
    }
    while (depth-- > 0) emit(w(Op::MEND));
    if (with_fault) {
        // every PE active, offsets 1000 + PE index: PEs 24 and up leave memory
        emit(w(Op::MALL));
        emit(w(Op::PIDX, 0));
        emit(w(Op::LDX, 1, 0, 0, kLdxNoHigh | 1000u));
    }
    emit(w(Op::LOOP, 0, 1, 0, loop_top));
    emit(w(Op::HALT));
    const uint32_t sub = static_cast<uint32_t>(code.size());
    emit(w(Op::ADD, 0, 0, 1));
    emit(w(Op::SHLI, 1, 1, 0, 3));
    emit(w(Op::RET));
    for (int f : fixups) code[static_cast<size_t>(f)].imm = sub;
    Program p;
    for (const Word& x : code) p.code.push_back(x.encode());
    p.phases = {"a", "b", "c"};
    return p;
}

// Random registers, flags, memories; r12 = 0/1; M random or all 1.
void seed_state(Machine& m, std::mt19937& rng, bool partial_mask) {
    const int P = m.pes();
    for (int p = 0; p < P; ++p) {
        for (int r = 0; r < 12; ++r) m.set_reg(p, r, static_cast<uint8_t>(rng()));
        m.set_reg(p, 12, static_cast<uint8_t>(rng() & 1));
        m.carry_lanes()[p] = rng() & 1;
        m.test_lanes()[p] = rng() & 1;
        m.mask_lanes()[p] = partial_mask ? (rng() % 4 != 0) : 1;
    }
    for (uint32_t a = 0; a < m.config().mem_bytes; a += 7)
        m.mem_write(rng() % static_cast<unsigned>(P), a, static_cast<uint8_t>(rng()));
    for (uint32_t a = 0; a < m.config().ext_bytes; a += 5)
        m.ext_write(rng() % static_cast<unsigned>(P), a, static_cast<uint8_t>(rng()));
}

enum class How { Run, Steps, Chunks };

Snapshot execute(const MachineConfig& cfg, const Program& prog, SimdPath path, unsigned seed,
                 bool partial_mask, How how) {
    Machine m(cfg);
    m.set_simd_path(path);
    m.load(prog);
    std::mt19937 rng(seed);
    seed_state(m, rng, partial_mask);
    try {
        if (how == How::Run) {
            m.run();
        } else if (how == How::Steps) {
            while (!m.halted()) m.step();
        } else {
            uint64_t limit = 0;
            while (!m.halted()) m.run(limit += 1 + rng() % 37);
        }
    } catch (const Fault& f) {
        return snap(m, f.what());
    }
    return snap(m);
}

}  // namespace

BOOST_AUTO_TEST_CASE(path_names_round_trip_and_the_baseline_is_always_there) {
    const std::vector<SimdPath> paths = supported_simd_paths();
    BOOST_REQUIRE(!paths.empty());
    BOOST_CHECK(paths.front() == SimdPath::Generic);
    for (SimdPath p : {SimdPath::Generic, SimdPath::Avx2, SimdPath::Avx512})
        BOOST_CHECK(simd_path_from_string(to_string(p)) == p);
    BOOST_CHECK_THROW(simd_path_from_string("sse9"), std::invalid_argument);
    Machine m(small(8));
    for (SimdPath p : {SimdPath::Generic, SimdPath::Avx2, SimdPath::Avx512}) {
        const bool ok = std::find(paths.begin(), paths.end(), p) != paths.end();
        if (ok) {
            m.set_simd_path(p);
            BOOST_CHECK(m.simd_path() == p);
        } else {
            BOOST_CHECK_THROW(m.set_simd_path(p), std::invalid_argument);
        }
    }
}

BOOST_AUTO_TEST_CASE(every_path_and_every_run_shape_give_the_baseline_state) {
    const std::vector<SimdPath> paths = supported_simd_paths();
    for (SimdPath p : {SimdPath::Avx2, SimdPath::Avx512})
        if (std::find(paths.begin(), paths.end(), p) == paths.end())
            BOOST_TEST_MESSAGE("SIMD path " << to_string(p) << " not supported here: skipped");
    std::mt19937 rng(2024);
    int compared = 0;
    for (int P : {37, 64, 100, 256}) {
        MachineConfig cfg = small(P);
        for (int rep = 0; rep < 3; ++rep) {
            const bool with_fault = rep == 2;
            const Program prog = random_program(rng, with_fault);
            for (bool partial : {false, true}) {
                const unsigned seed = static_cast<unsigned>(rng());
                const Snapshot base =
                    execute(cfg, prog, SimdPath::Generic, seed, partial, How::Steps);
                BOOST_CHECK(base.stats.instructions > 200);
                if (with_fault)
                    BOOST_CHECK_MESSAGE(
                        base.fault.find("ldx: PE 24 address 1024") != std::string::npos,
                        "expected an ldx fault, got '" << base.fault << "'");
                else
                    BOOST_CHECK(base.halted && base.fault.empty());
                for (SimdPath path : paths)
                    for (How how : {How::Run, How::Steps, How::Chunks}) {
                        const Snapshot s = execute(cfg, prog, path, seed, partial, how);
                        BOOST_CHECK_MESSAGE(s == base, "P=" << P << " rep " << rep << " path "
                                                            << to_string(path) << " shape "
                                                            << static_cast<int>(how)
                                                            << (partial ? " partial mask" : ""));
                        if (!(s == base) && s.fault != base.fault)
                            BOOST_TEST_MESSAGE("  fault '" << s.fault << "' vs '" << base.fault
                                                           << "'");
                        ++compared;
                    }
            }
        }
    }
    BOOST_TEST_MESSAGE(compared << " runs compared with the baseline");
}

// The external memory is cleared by reset() whether the machine wrote it
// (xst), the host wrote a cell (ext_write) or the host held a writable
// pointer.
BOOST_AUTO_TEST_CASE(reset_clears_every_external_write) {
    Machine m(small(8));
    m.load(
        assemble_string("cli c1, #4\ncli c2, #10\nli r1, #7\nst r1, [#3]\n"
                        "xst [#0], ext[c2], c1\nhalt\n",
                        "t.s"));
    m.run();
    BOOST_CHECK_EQUAL(m.ext_read(3, 13), 7);
    m.ext_write(5, 200, 9);
    m.reset();
    const Machine& cm = m;
    for (uint32_t a = 0; a < 256; ++a)
        for (int p = 0; p < 8; ++p) BOOST_REQUIRE_EQUAL(cm.ext_read(p, a), 0);
    m.ext_data()[8 * 100 + 1] = 5;  // a writable pointer: cleared too
    m.reset();
    BOOST_CHECK_EQUAL(cm.ext_read(1, 100), 0);
    m.ext_data()[8 * 101 + 2] = 6;  // and on every later reset
    m.reset();
    BOOST_CHECK_EQUAL(cm.ext_read(2, 101), 0);
}
