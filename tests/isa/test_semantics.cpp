// Lane semantics against wide-integer references, exhaustively, and the
// vectorised lane loops of the executor against the scalar semantics.
#define BOOST_TEST_MODULE isa_semantics
#include <boost/test/unit_test.hpp>
#include <random>

#include "helpers.hpp"

using namespace isatest;

BOOST_AUTO_TEST_CASE(alu_exhaustive_against_wide_arithmetic) {
    for (int a = 0; a < 256; ++a)
        for (int b = 0; b < 256; ++b)
            for (int c = 0; c < 2; ++c) {
                const auto A = static_cast<uint8_t>(a), B = static_cast<uint8_t>(b),
                           C = static_cast<uint8_t>(c);
                auto chk = [&](Op o, int r, int co) {
                    const sem::LaneOut x = sem::alu_lane(o, A, B, C);
                    if (x.r != r || x.c != co)
                        BOOST_FAIL(std::string(op_info(o)->mnemonic) + " a=" + std::to_string(a) +
                                   " b=" + std::to_string(b) + " c=" + std::to_string(c));
                };
                chk(Op::ADD, (a + b) & 255, (a + b) >> 8);
                chk(Op::ADDI, (a + b) & 255, (a + b) >> 8);
                chk(Op::ADC, (a + b + c) & 255, (a + b + c) >> 8);
                chk(Op::ADCI, (a + b + c) & 255, (a + b + c) >> 8);
                chk(Op::SUB, (a - b) & 255, a < b);
                chk(Op::SUBI, (a - b) & 255, a < b);
                chk(Op::SBC, (a - b - c) & 255, a - b - c < 0);
                chk(Op::SBCI, (a - b - c) & 255, a - b - c < 0);
                chk(Op::AND, a & b, c);
                chk(Op::OR, a | b, c);
                chk(Op::XOR, a ^ b, c);
                chk(Op::MIN, std::min(a, b), c);
                chk(Op::MAX, std::max(a, b), c);
                chk(Op::MINI, std::min(a, b), c);
                chk(Op::MAXI, std::max(a, b), c);
                const int n = b & 7;
                const int wl = a << n;
                chk(Op::SHLV, wl & 255, n ? (wl >> 8) & 1 : c);
                chk(Op::SHRV, a >> n, n ? (a >> (n - 1)) & 1 : c);
                if (b < 8) {
                    chk(Op::SHLI, wl & 255, n ? (wl >> 8) & 1 : c);
                    chk(Op::SHRI, a >> n, n ? (a >> (n - 1)) & 1 : c);
                }
                chk(Op::ROLC, ((a << 1) | c) & 255, a >> 7);
                chk(Op::RORC, (a >> 1) | (c << 7), a & 1);
                BOOST_REQUIRE(sem::compare_lane(Op::CEQ, A, B) == (a == b));
                BOOST_REQUIRE(sem::compare_lane(Op::CNE, A, B) == (a != b));
                BOOST_REQUIRE(sem::compare_lane(Op::CLTU, A, B) == (a < b));
                BOOST_REQUIRE(sem::compare_lane(Op::CLEU, A, B) == (a <= b));
                BOOST_REQUIRE(sem::compare_lane(Op::CGTU, A, B) == (a > b));
                BOOST_REQUIRE(sem::compare_lane(Op::CGEUI, A, B) == (a >= b));
            }
}

BOOST_AUTO_TEST_CASE(carry_writers_are_exactly_the_arithmetic_and_shift_ops) {
    for (const OpInfo& i : all_ops()) {
        const bool expect = i.op == Op::ADD || i.op == Op::ADC || i.op == Op::SUB ||
                            i.op == Op::SBC || i.op == Op::ADDI || i.op == Op::ADCI ||
                            i.op == Op::SUBI || i.op == Op::SBCI || i.op == Op::SHLI ||
                            i.op == Op::SHRI || i.op == Op::ROLC || i.op == Op::RORC ||
                            i.op == Op::SHLV || i.op == Op::SHRV;
        BOOST_CHECK_MESSAGE(sem::writes_carry(i.op) == expect, i.mnemonic);
    }
}

// Every register-register / register-immediate ALU, shift and compare op,
// executed on an odd-sized array (loop remainders) with a random mask,
// against the scalar lane semantics and the blend rule.
BOOST_AUTO_TEST_CASE(lane_loops_match_scalar_semantics_under_random_masks) {
    std::mt19937 rng(7);
    const int P = 37;
    MachineConfig cfg = small(P);
    for (const OpInfo& info : all_ops()) {
        const Format f = info.format;
        const bool alu = f == Format::Rrr || f == Format::Rri8 || f == Format::Rsh ||
                         info.op == Op::ROLC || info.op == Op::RORC;
        const bool cmp = f == Format::Cmp || f == Format::Cmpi;
        if ((!alu && !cmp) || info.op == Op::CSEL || info.op == Op::TSEL) continue;
        for (int rep = 0; rep < 4; ++rep) {
            const int imm =
                f == Format::Rsh ? static_cast<int>(rng() % 8) : static_cast<int>(rng() % 256);
            // r1 = a, r2 = b; result into r3 (distinct) and r1 (aliasing rd == ra).
            for (int rd : {3, 1}) {
                Word w;
                w.op = static_cast<uint8_t>(info.op);
                if (cmp) {
                    w.ra = 1;
                    w.rb = f == Format::Cmp ? 2 : 0;
                    w.imm = f == Format::Cmpi ? static_cast<uint32_t>(imm) : 0;
                } else {
                    w.rd = static_cast<uint8_t>(rd);
                    w.ra = 1;
                    w.rb = f == Format::Rrr ? 2 : 0;
                    w.imm =
                        (f == Format::Rri8 || f == Format::Rsh) ? static_cast<uint32_t>(imm) : 0;
                }
                BOOST_REQUIRE_EQUAL(check_word(w.encode()), "");
                Program p;
                p.code = {w.encode(), Word{static_cast<uint8_t>(Op::HALT)}.encode()};
                Machine m(cfg);
                m.load(p);
                std::vector<uint8_t> a(P), b(P), c(P), t(P), mk(P), old(P);
                for (int i = 0; i < P; ++i) {
                    a[i] = static_cast<uint8_t>(rng());
                    b[i] = static_cast<uint8_t>(rng());
                    c[i] = rng() & 1;
                    t[i] = rng() & 1;
                    mk[i] = (rng() % 3) != 0;
                    old[i] = static_cast<uint8_t>(rng());
                    m.set_reg(i, 1, a[i]);
                    m.set_reg(i, 2, b[i]);
                    m.set_reg(i, 3, old[i]);
                    m.carry_lanes()[i] = c[i];
                    m.test_lanes()[i] = t[i];
                    m.mask_lanes()[i] = mk[i];
                }
                m.run();
                for (int i = 0; i < P; ++i) {
                    const uint8_t bb =
                        f == Format::Rrr || f == Format::Cmp ? b[i] : static_cast<uint8_t>(imm);
                    if (cmp) {
                        const uint8_t et = mk[i] ? sem::compare_lane(info.op, a[i], bb) : t[i];
                        BOOST_REQUIRE_MESSAGE(m.test_lanes()[i] == et,
                                              info.mnemonic << " PE " << i);
                        BOOST_REQUIRE(m.carry_lanes()[i] == c[i]);
                    } else {
                        const sem::LaneOut o = sem::alu_lane(info.op, a[i], bb, c[i]);
                        const uint8_t before = rd == 3 ? old[i] : a[i];
                        BOOST_REQUIRE_MESSAGE(m.reg(i, rd) == (mk[i] ? o.r : before),
                                              info.mnemonic << " PE " << i << " rd r" << rd);
                        BOOST_REQUIRE_MESSAGE(m.carry_lanes()[i] == (mk[i] ? o.c : c[i]),
                                              info.mnemonic << " carry PE " << i);
                        BOOST_REQUIRE(m.test_lanes()[i] == t[i]);
                    }
                }
            }
        }
    }
}
