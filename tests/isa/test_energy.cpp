// The energy model (docs/energy.md): event counts against hand-counted
// programs, energy against the events x energies recomputed here, static
// energy against cycles x PEs, and the table's ranges.
#define BOOST_TEST_MODULE isa_energy
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <sstream>

#include "helpers.hpp"
#include "imap/isa/energy.hpp"

using namespace isatest;

namespace {

// Five PE instructions under a mask that leaves PE 3 off (P = 4), plus
// unmasked ones around it. Counted by hand:
//   pidx, cltui          ALU     4 + 4 active lanes
//   mif / mend           mask    2 x 4 PE ops
//   addi                 ALU     3 active, 1 masked
//   max                  minmax  3 active, 1 masked
//   shli                 shift   3 active, 1 masked
//   st                   store   3 active, 1 masked
//   rxl #2               ring    2 hops x 4 PEs (every ring register moves)
//   ld                   load    4 active
//   halt                 CP      1
const char* kMasked = R"(
        pidx r0, #0
        cltui r0, #3
        mif
          addi r1, r1, #1
          max r2, r1, r0
          shli r5, r1, #1
          st r1, [#5]
          rxl r3, r1, #2
        mend
        ld r4, [#5]
        halt)";

void check_hand_counts(const EnergyEvents& e) {
    BOOST_TEST(e.alu_lanes == 4u + 4u + 3u);
    BOOST_TEST(e.minmax_lanes == 3u);
    BOOST_TEST(e.shift_lanes == 3u);
    BOOST_TEST(e.store_lanes == 3u);
    BOOST_TEST(e.load_lanes == 4u);
    BOOST_TEST(e.masked_lanes == 4u);  // addi, max, shli, st on PE 3
    BOOST_TEST(e.ring_pe_hops == 8u);
    BOOST_TEST(e.mask_pe_ops == 8u);
    BOOST_TEST(e.cp_instructions == 1u);
    BOOST_TEST(e.instructions == 11u);
    BOOST_TEST(e.ext_bytes == 0u);
    BOOST_TEST(e.ext_transfers == 0u);
    BOOST_TEST(e.video_bytes == 0u);
    BOOST_TEST(e.pes == 4u);
}

}  // namespace

BOOST_AUTO_TEST_CASE(events_of_a_masked_program_counted_by_hand) {
    auto m = run(kMasked, small(4));
    BOOST_REQUIRE(m->halted());
    check_hand_counts(energy_events(m->stats(), 4, m->cycles()));
    BOOST_TEST(m->stats().op_lanes[static_cast<size_t>(Op::ADDI)] == 3u);
    BOOST_TEST(m->stats().ring_hops == 2u);
}

BOOST_AUTO_TEST_CASE(single_steps_and_cycle_limits_count_the_same) {
    // exec_one (single steps) and partial runs (a cycle limit mid-run) book
    // the active lanes as the straight-line runs do.
    Machine a(small(4));
    a.load(assemble_string(kMasked, "t.s"));
    while (!a.halted()) a.step();
    check_hand_counts(energy_events(a.stats(), 4, a.cycles()));
    Machine b(small(4));
    b.load(assemble_string(kMasked, "t.s"));
    for (uint64_t lim = 1; !b.halted(); ++lim) b.run(lim);
    check_hand_counts(energy_events(b.stats(), 4, b.cycles()));
}

BOOST_AUTO_TEST_CASE(external_bytes_are_len_times_active_pes) {
    MachineConfig cfg = small(4);
    cfg.ext_bytes = 64;
    auto m = run(R"(
        cli c1, #10
        cli c2, #4
        cli c3, #20
        pidx r0, #0
        ceqi r0, #0
        xld [c3 + 1], ext[c1], c2     ; 4 bytes x 4 PEs
        mif                           ; PE 0 only
          xst [c3 + 1], ext[c1], c2   ; 4 bytes x 1 PE
        mend
        halt)",
                 cfg);
    BOOST_REQUIRE(m->halted());
    const EnergyEvents e = energy_events(m->stats(), 4, m->cycles());
    BOOST_TEST(e.ext_bytes == 16u + 4u);
    BOOST_TEST(e.ext_transfers == 2u);
}

BOOST_AUTO_TEST_CASE(energy_is_events_times_energies) {
    MachineConfig cfg = small(4);
    cfg.mem_bytes = 4096;  // local-memory energy x (4096 / 1024)^0.5 = 2
    EnergyTable& t = cfg.energy;
    // distinct values, so that a count charged to the wrong class shows
    t.e_alu_pj = 1;
    t.e_minmax_pj = 3;
    t.e_shift_pj = 5;
    t.e_rf_pj = 7;
    t.e_masked_pj = 11;
    t.e_load_pj = 13;
    t.e_store_pj = 17;
    t.mem_size_exp = 0.5;
    t.e_ring_hop_pj = 19;
    t.e_mask_pj = 23;
    t.e_cp_pj = 29;
    t.e_issue_pj = 31;
    t.e_ext_byte_pj = 37;
    t.e_ext_xfer_pj = 41;
    t.e_video_byte_pj = 43;
    t.s_pe_clock_pj = 47;
    t.s_cp_clock_pj = 53;
    t.s_pe_leak_uw = 59;
    t.s_cp_leak_uw = 61;
    t.energy_scale = 2;
    auto m = run(kMasked, cfg);
    const uint64_t cyc = m->cycles();
    const EnergyReport r = energy_of(m->stats(), cyc, cfg);
    // From the hand counts above, not from energy_events.
    const double k = 2;
    const double dyn = k * (11 * 1 + 3 * 3 + 3 * 5 + (11 + 3 + 3) * 7 + 4 * 11 + 4 * 13 * 2.0 +
                            3 * 17 * 2.0 + 8 * 19 + 8 * 23 + 1 * 29 + 11 * 31);
    const double sec = static_cast<double>(cyc) / 40e6;
    const double stat = 4.0 * (static_cast<double>(cyc) * 47 * k + sec * 59e6) +
                        (static_cast<double>(cyc) * 53 * k + sec * 61e6);
    const auto tol = boost::test_tools::tolerance(1e-12);
    BOOST_TEST(r.dynamic_pj == dyn, tol);
    BOOST_TEST(r.static_pj == stat, tol);
    BOOST_TEST(r.total_pj == dyn + stat, tol);
    BOOST_TEST(r.power_mw == (dyn + stat) * 1e-12 / sec * 1e3, tol);
    BOOST_TEST(r.by_class_pj[size_t(EnergyClass::Load)] == 4 * 13 * 2.0 * k, tol);
    BOOST_TEST(r.by_class_pj[size_t(EnergyClass::Masked)] == 4 * 11 * k, tol);
    double sum = 0;
    for (double x : r.by_class_pj) sum += x;
    BOOST_TEST(sum == r.total_pj, tol);
}

// Phases (issue 29 item 3): the executor splits the counts at the phase
// markers. Counted by hand, per phase (P = 4, PE 3 masked off in phase a):
//   default  pidx (ALU 4), halt (CP 1)                         2 instructions
//   a        cltui (ALU 4), mif / mend (mask 2 x 4), addi (ALU 3, 1 masked),
//            later max (min-max 4)                             5 instructions
//   b        rxl #2 (ring 2 hops x 4), ld (load 4)             2 instructions
// Phase a is entered twice: the counts follow the phase, not the PC.
const char* kPhased = R"(
        pidx r0, #0
        .phase a
        cltui r0, #3
        mif
          addi r1, r1, #1
        mend
        .phase b
        rxl r3, r1, #2
        ld r4, [#5]
        .phase a
        max r2, r1, r0
        .phase default
        halt)";

void check_phase_counts(const Machine& m) {
    const Stats& s = m.stats();
    const Program& p = m.program();
    BOOST_REQUIRE_EQUAL(p.phases.size(), 3u);
    BOOST_REQUIRE_EQUAL(s.by_phase.size(), 3u);
    BOOST_REQUIRE(p.phases[1] == "a");
    BOOST_REQUIRE(p.phases[2] == "b");
    const EnergyEvents d = energy_events(s.by_phase[0], 4, 0);
    const EnergyEvents a = energy_events(s.by_phase[1], 4, 0);
    const EnergyEvents b = energy_events(s.by_phase[2], 4, 0);
    BOOST_TEST(d.alu_lanes == 4u);
    BOOST_TEST(d.cp_instructions == 1u);
    BOOST_TEST(d.instructions == 2u);
    BOOST_TEST(d.masked_lanes + d.minmax_lanes + d.load_lanes + d.ring_pe_hops + d.mask_pe_ops ==
               0u);
    BOOST_TEST(a.alu_lanes == 4u + 3u);
    BOOST_TEST(a.masked_lanes == 1u);
    BOOST_TEST(a.mask_pe_ops == 8u);
    BOOST_TEST(a.minmax_lanes == 4u);
    BOOST_TEST(a.instructions == 5u);
    BOOST_TEST(a.load_lanes + a.ring_pe_hops + a.cp_instructions == 0u);
    BOOST_TEST(b.ring_pe_hops == 8u);
    BOOST_TEST(b.load_lanes == 4u);
    BOOST_TEST(b.instructions == 2u);
    BOOST_TEST(b.alu_lanes + b.masked_lanes + b.mask_pe_ops + b.cp_instructions == 0u);
    // The phases add up to the totals, opcode by opcode.
    for (size_t o = 0; o < 256; ++o) {
        uint64_t n = 0, l = 0;
        for (const Stats& x : s.by_phase) n += x.op_counts[o], l += x.op_lanes[o];
        BOOST_TEST_INFO("opcode " << o);
        BOOST_TEST(n == s.op_counts[o]);
        BOOST_TEST(l == s.op_lanes[o]);
    }
    uint64_t cyc = 0;
    for (const Stats& x : s.by_phase) {
        BOOST_TEST(x.by_phase.empty());
        for (uint64_t c : x.class_cycles) cyc += c;
    }
    BOOST_TEST(cyc == m.cycles());
}

BOOST_AUTO_TEST_CASE(phase_counts_split_at_the_markers_counted_by_hand) {
    auto m = run(kPhased, small(4));
    BOOST_REQUIRE(m->halted());
    check_phase_counts(*m);
    // single steps (exec_one) and cycle limits (partial runs) split the same
    Machine a(small(4));
    a.load(assemble_string(kPhased, "t.s"));
    while (!a.halted()) a.step();
    check_phase_counts(a);
    Machine b(small(4));
    b.load(assemble_string(kPhased, "t.s"));
    for (uint64_t lim = 1; !b.halted(); ++lim) b.run(lim);
    check_phase_counts(b);
    // reset clears them
    b.reset();
    BOOST_TEST(b.stats().by_phase.size() == 3u);
    for (const Stats& x : b.stats().by_phase) BOOST_TEST(x.instructions == 0u);
}

BOOST_AUTO_TEST_CASE(phase_energies_are_their_events_times_energies_and_add_up) {
    MachineConfig cfg = small(4);
    cfg.mem_bytes = 4096;  // local-memory energy x 2
    EnergyTable& t = cfg.energy;
    t.e_alu_pj = 1;
    t.e_minmax_pj = 3;
    t.e_shift_pj = 5;
    t.e_rf_pj = 7;
    t.e_masked_pj = 11;
    t.e_load_pj = 13;
    t.e_store_pj = 17;
    t.e_ring_hop_pj = 19;
    t.e_mask_pj = 23;
    t.e_cp_pj = 29;
    t.e_issue_pj = 31;
    t.s_pe_clock_pj = 47;
    t.s_cp_clock_pj = 53;
    t.s_pe_leak_uw = 59;
    t.s_cp_leak_uw = 61;
    t.energy_scale = 2;
    auto m = run(kPhased, cfg);
    const std::vector<uint64_t>& pc = m->phase_cycles();
    BOOST_REQUIRE_EQUAL(pc.size(), 3u);
    const std::vector<EnergyReport> e = energy_by_phase(m->stats(), pc, cfg);
    BOOST_REQUIRE_EQUAL(e.size(), 3u);
    // Dynamic energy of each phase from the hand counts above (k = 2).
    const double k = 2;
    const double dyn[3] = {k * (4 * 1 + 4 * 7 + 1 * 29 + 2 * 31),                         // default
                           k * (7 * 1 + 4 * 3 + (7 + 4) * 7 + 1 * 11 + 8 * 23 + 5 * 31),  // a
                           k * (4 * 13 * 2.0 + 8 * 19 + 2 * 31)};                         // b
    const auto tol = boost::test_tools::tolerance(1e-12);
    double sum = 0;
    for (size_t i = 0; i < 3; ++i) {
        BOOST_TEST_INFO("phase " << i);
        const double c = static_cast<double>(pc[i]), sec = c / 40e6;
        const double stat = 4.0 * (c * 47 * k + sec * 59e6) + (c * 53 * k + sec * 61e6);
        BOOST_TEST(e[i].dynamic_pj == dyn[i], tol);
        BOOST_TEST(e[i].static_pj == stat, tol);
        sum += e[i].total_pj;
    }
    const EnergyReport whole = energy_of(m->stats(), m->cycles(), cfg);
    BOOST_TEST(sum == whole.total_pj, tol);
}

BOOST_AUTO_TEST_CASE(static_energy_scales_with_cycles_times_pes) {
    // The same program at P and 2P (same cycles: no P-dependent cost), and
    // a longer program (more cycles); the CP's static part subtracted.
    auto stat_pe = [](int pes, const std::string& src) {
        MachineConfig cfg = small(pes);
        auto m = run(src, cfg);
        const EnergyReport r = energy_of(m->stats(), m->cycles(), cfg);
        return std::make_pair(r.by_class_pj[size_t(EnergyClass::StaticPe)], m->cycles());
    };
    const auto [e4, c4] = stat_pe(4, kMasked);
    const auto [e8, c8] = stat_pe(8, kMasked);
    BOOST_REQUIRE(c4 == c8);
    BOOST_TEST(e4 > 0);
    BOOST_TEST(e8 / e4 == 2.0, boost::test_tools::tolerance(1e-12));
    const std::string longer = std::string(kMasked).insert(1, "nop\nnop\nnop\nnop\nnop\n");
    const auto [l4, lc4] = stat_pe(4, longer);
    BOOST_REQUIRE(lc4 == c4 + 5);
    BOOST_TEST(l4 / e4 == static_cast<double>(lc4) / static_cast<double>(c4),
               boost::test_tools::tolerance(1e-12));
    // per PE-cycle: clock tree + leakage per cycle at 40 MHz
    const EnergyTable t;
    BOOST_TEST(e4 / (4.0 * static_cast<double>(c4)) == t.s_pe_clock_pj + t.s_pe_leak_uw / 40.0,
               boost::test_tools::tolerance(1e-12));
}

// Issue 29 item 3: the average power at the camera's rate, worked out here
// from the report's energy, static energy and time: the frame, then idle at
// the static power until the next frame; a frame slower than the camera's
// period cannot keep up and reports the frame-time power.
BOOST_AUTO_TEST_CASE(power_at_the_camera_rate) {
    MachineConfig cfg = small(4);
    cfg.energy.frame_rate_hz = 25;
    auto m = run(kMasked, cfg);
    const EnergyReport r = energy_of(m->stats(), m->cycles(), cfg);
    const double sec = static_cast<double>(m->cycles()) / 40e6;
    const double static_w = r.static_pj * 1e-12 / sec;
    const double want_w = (r.total_pj * 1e-12 + static_w * (1.0 / 25 - sec)) * 25;
    const auto tol = boost::test_tools::tolerance(1e-12);
    BOOST_TEST(r.keeps_up);
    BOOST_TEST(r.frame_rate_hz == 25.0);
    BOOST_TEST(r.period_s == 0.04, tol);
    BOOST_TEST(r.static_mw == static_w * 1e3, tol);
    BOOST_TEST(r.power_camera_mw == want_w * 1e3, tol);
    BOOST_TEST(r.power_camera_mw < r.power_mw);  // idle is cheaper than running
    // 1 MHz and a 1 us camera period: the frame's cycles take longer
    cfg.clock_mhz = 1;
    cfg.energy.frame_rate_hz = 1e6;
    const EnergyReport slow = energy_of(m->stats(), m->cycles(), cfg);
    BOOST_REQUIRE(m->cycles() > 1u);
    BOOST_TEST(!slow.keeps_up);
    BOOST_TEST(slow.power_camera_mw == slow.power_mw);
    // the rate only changes the camera-rate figure
    cfg.energy.frame_rate_hz = 30;
    BOOST_TEST(energy_of(m->stats(), m->cycles(), cfg).total_pj == slow.total_pj);
}

BOOST_AUTO_TEST_CASE(every_energy_parameter_is_range_checked_by_name) {
    for (const EnergyTable::Field& f : EnergyTable::fields()) {
        BOOST_TEST_INFO(f.name);
        MachineConfig c;
        BOOST_CHECK_NO_THROW(c.set(f.name, "0.5"));
        BOOST_TEST(c.energy.get(f.name) == 0.5);
        for (const double bad : {f.min - 1, f.max * 2}) {
            std::ostringstream v;
            v << bad;
            try {
                c.set(f.name, v.str());
                BOOST_ERROR("accepted " << v.str());
            } catch (const ConfigError& e) {
                const std::string w = e.what();
                BOOST_TEST(w.find(f.name) != std::string::npos, w);
                BOOST_TEST(w.find("allowed ") != std::string::npos, w);
            }
        }
        if (f.min_exclusive) BOOST_CHECK_THROW(c.set(f.name, "0"), ConfigError);
        BOOST_CHECK_THROW(c.set(f.name, "abc"), ConfigError);
        BOOST_CHECK_THROW(c.set(f.name, "nan"), ConfigError);
        c.energy.*f.ptr = f.max * 2;
        BOOST_CHECK_THROW(c.validate(), ConfigError);
    }
    MachineConfig c;
    BOOST_CHECK_THROW(c.set("e_nothing_pj", "1"), ConfigError);
}

// Technology presets (docs/energy.md section 4): a preset sets what it names
// (the rule's factor worked out here), resets the rest to the 45 nm values,
// later settings override it, the camera rate stays, and an unknown name is
// refused with the list.
BOOST_AUTO_TEST_CASE(technology_presets) {
    MachineConfig c;
    BOOST_TEST(c.energy.tech == "45nm");
    c.set("e_alu_pj", "0.5");
    c.set("frame_rate_hz", "25");
    c.set("tech", "350nm");
    BOOST_TEST(c.energy.tech == "350nm");
    BOOST_TEST(std::fabs(c.energy.energy_scale - 350.0 / 45.0 * 3.3 * 3.3) < 0.5);
    BOOST_TEST(c.energy.s_pe_leak_uw == 0.0);
    BOOST_TEST(c.energy.e_ext_byte_pj == 2500.0);
    BOOST_TEST(c.energy.e_alu_pj == EnergyTable().e_alu_pj);  // reset to the 45 nm value
    BOOST_TEST(c.energy.frame_rate_hz == 25.0);               // not a technology figure
    c.set("energy_scale", "60");                              // overrides the preset
    BOOST_TEST(c.energy.energy_scale == 60.0);
    c.set("tech", "500nm");
    BOOST_TEST(std::fabs(c.energy.energy_scale - 500.0 / 45.0 * 3.3 * 3.3) < 0.5);
    c.set("tech", "45nm");
    BOOST_TEST(c.energy.energy_scale == 1.0);
    BOOST_TEST(c.energy.s_pe_leak_uw == EnergyTable().s_pe_leak_uw);
    try {
        c.set("tech", "7nm");
        BOOST_ERROR("accepted 7nm");
    } catch (const ConfigError& e) {
        BOOST_TEST(std::string(e.what()).find("allowed 45nm|350nm|500nm") != std::string::npos);
    }
    // the run's dynamic on-chip energy scales by the preset's factor
    auto m = run(kMasked, small(4));
    MachineConfig old = small(4);
    old.set("tech", "350nm");
    const EnergyReport a = energy_of(m->stats(), m->cycles(), small(4));
    const EnergyReport b = energy_of(m->stats(), m->cycles(), old);
    const size_t alu = static_cast<size_t>(EnergyClass::Alu);
    BOOST_TEST(std::fabs(b.by_class_pj[alu] / a.by_class_pj[alu] - 85.0) < 1e-9);
}

// The tornado: each parameter's energies at x0.5 and x2 move the total by
// what that parameter's events cost (the ALU's 11 lanes of kMasked, counted
// by hand above: (2 - 0.5) x 0.03 pJ x 11), sorted by spread, every energy
// parameter but the camera rate listed once.
BOOST_AUTO_TEST_CASE(tornado_moves_the_total_by_each_parameters_events) {
    auto m = run(kMasked, small(4));
    const MachineConfig c = small(4);
    const std::vector<EnergySensitivity> t = energy_tornado(m->stats(), m->cycles(), c);
    BOOST_TEST(t.size() == EnergyTable::fields().size() - 1);
    const double total = energy_of(m->stats(), m->cycles(), c).total_pj;
    for (size_t i = 0; i < t.size(); ++i) {
        BOOST_TEST_INFO(t[i].name);
        BOOST_TEST(t[i].name != "frame_rate_hz");
        BOOST_TEST(t[i].low_pj <= total + 1e-9);
        BOOST_TEST(t[i].high_pj >= total - 1e-9);
        if (i > 0) BOOST_TEST(t[i - 1].high_pj - t[i - 1].low_pj >= t[i].high_pj - t[i].low_pj);
        if (t[i].name == "e_alu_pj")
            BOOST_TEST(std::fabs(t[i].high_pj - t[i].low_pj - 1.5 * 0.03 * 11) < 1e-9);
    }
}
