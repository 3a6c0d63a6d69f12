// imapsim run --vcd end to end: the same run twice gives identical bytes, the
// TLM model gives the same waves as the core, the RTL model writes per-cycle waves
// (identical bytes twice), the VCD is well formed and the .gtkw view names
// signals of the VCD; bad options and paths are clear errors.
#define BOOST_TEST_MODULE waves_cli
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <cstdio>
#include <filesystem>
#include <string>

#include "cli_test_util.hpp"
#include "vcd_check.hpp"

namespace fs = std::filesystem;

namespace {

using clitest::Result;
using clitest::run;

fs::path tmpdir() {
    fs::path d = fs::temp_directory_path() / ("imapsim-waves-cli-" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}

const char* kTrace = " --trace-pes 0:3 --trace-window 0:20000";

}  // namespace

BOOST_AUTO_TEST_CASE(core_twice_and_tlm_give_identical_well_formed_waves) {
    const fs::path d = tmpdir();
    const std::string a = (d / "A.vcd").string(), b = (d / "B.vcd").string(),
                      t = (d / "T.vcd").string();
    const Result ra = run("run --model core --vcd " + a + kTrace);
    BOOST_TEST_INFO(ra.out);
    BOOST_REQUIRE(ra.code == 0);
    BOOST_TEST(ra.out.find("waves -> " + a) != std::string::npos);
    const Result rb = run("run --model core --vcd " + b + kTrace);
    BOOST_REQUIRE(rb.code == 0);
    const std::string va = vcdcheck::read_all(a), vb = vcdcheck::read_all(b);
    BOOST_TEST(va.size() > 10000u);
    BOOST_TEST((va == vb));
    BOOST_TEST((vcdcheck::read_all((d / "A.gtkw").string()).size() > 100u));

    const Result rt = run("run --model tlm --vcd " + t + kTrace);
    BOOST_TEST_INFO(rt.out);
    if (rt.out.find("invalid value 'tlm' for --model") == std::string::npos) {
        BOOST_REQUIRE(rt.code == 0);
        BOOST_TEST((vcdcheck::read_all(t) == va));  // same machine, same waves
    }

    // Well formed: declared identifiers, increasing time, inside the window.
    vcdcheck::Parsed p = vcdcheck::parse(va);
    BOOST_TEST(p.error == "");
    BOOST_TEST(p.timescale == "1ns");
    BOOST_REQUIRE(!p.times.empty());
    BOOST_TEST(p.times.back() <= 20100u * 25u);  // the last instruction may end after t1
    BOOST_TEST(p.full_names.count("top.cp.instr[255:0]") == 1u);
    BOOST_TEST(p.full_names.count("top.pe003.r15[7:0]") == 1u);
    BOOST_TEST(p.full_names.count("top.pe004.r15[7:0]") == 0u);
    size_t pc_changes = 0;  // the PC's width follows the program size
    for (const auto& [name, n] : p.changes_by_name)
        if (name.rfind("top.cp.pc[", 0) == 0) pc_changes = n;
    BOOST_TEST(pc_changes > 1000u);
    BOOST_TEST(p.changes_by_name["top.pe000.mem_we"] > 10u);

    // The view names only signals of the VCD, and has the groups.
    const std::string g = vcdcheck::read_all((d / "A.gtkw").string());
    BOOST_TEST(g.find("[dumpfile] \"A.vcd\"") != std::string::npos);
    BOOST_TEST(g.find("-PE 3") != std::string::npos);
    const auto names = vcdcheck::gtkw_signals(g);
    BOOST_TEST(names.size() > 20u);
    for (const std::string& n : names) BOOST_TEST(p.full_names.count(n) == 1u, n);
    BOOST_TEST(!fs::exists(a + ".part"));
}

BOOST_AUTO_TEST_CASE(signal_groups_and_limit) {
    const fs::path d = tmpdir();
    const std::string v = (d / "m.vcd").string();
    Result r = run("run --model core --vcd " + v +
                   " --trace-pes 5,9 --trace-window 100000:100500 --trace-signals mem,mask");
    BOOST_REQUIRE(r.code == 0);
    vcdcheck::Parsed p = vcdcheck::parse(vcdcheck::read_all(v));
    BOOST_TEST(p.error == "");
    BOOST_TEST(p.full_names.count("top.pe005.mem_addr[9:0]") == 1u);
    BOOST_TEST(p.full_names.count("top.pe009.M") == 1u);
    BOOST_TEST(p.full_names.count("top.pe009.r0[7:0]") == 0u);
    BOOST_TEST(p.full_names.count("top.cp.pc[10:0]") == 0u);
    BOOST_TEST(p.times.front() >= 100000u * 25u);

    // A tiny limit: warned, stopped, still a valid file.
    r = run("run --model core --vcd " + v + " --trace-pes 0:7 --trace-limit-mb 0.05");
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE(r.code == 0);
    BOOST_TEST(r.out.find("warning:") != std::string::npos);
    BOOST_TEST(r.out.find("stopped at --trace-limit-mb") != std::string::npos);
    BOOST_TEST(fs::file_size(v) < 60000u);
    p = vcdcheck::parse(vcdcheck::read_all(v));
    BOOST_TEST(p.error == "");
}

BOOST_AUTO_TEST_CASE(errors_are_clear_and_leave_nothing) {
    const fs::path d = tmpdir();
    const std::string bad = (d / "no-such-dir" / "x.vcd").string();
    Result r = run("run --model core --vcd " + bad);
    BOOST_TEST(r.code != 0);
    BOOST_TEST(r.out.find("cannot create") != std::string::npos);
    BOOST_TEST(!fs::exists(bad));
    BOOST_TEST(!fs::exists(bad + ".part"));
    r = run("run --model core --vcd " + (d / "e.vcd").string() + " --trace-pes 300");
    BOOST_TEST(r.code == 2);
    BOOST_TEST(r.out.find("invalid value '300' for --trace-pes") != std::string::npos);
    r = run("run --model core --vcd " + (d / "e.vcd").string() + " --trace-window 9:3");
    BOOST_TEST(r.code == 2);
    BOOST_TEST(r.out.find("for --trace-window") != std::string::npos);
    BOOST_TEST(!fs::exists(d / "e.vcd"));
}

BOOST_AUTO_TEST_CASE(vcd_on_a_model_without_tracing_is_an_input_error) {
    const fs::path d = tmpdir();
    const std::string vcd = (d / "lockstep.vcd").string();
    const Result r = run("run --model lockstep --pes 8 --size 32x16 --D 8 --vcd " + vcd);
    if (r.out.find("invalid value 'lockstep' for --model") != std::string::npos) return;  // no RTL
    BOOST_TEST_INFO(r.out);
    BOOST_TEST(r.code == 2);
    BOOST_TEST(r.out.find("--vcd") != std::string::npos);
    BOOST_TEST(!fs::exists(vcd));
    fs::remove_all(d);
}

// --model rtl: the verilated design's own signals (Verilator's VCD writer,
// docs/rtl.md "Waves"): two runs give identical files; the selected PEs'
// scopes only; the .gtkw names signals of the VCD.
BOOST_AUTO_TEST_CASE(rtl_design_waves_are_identical_and_selected) {
    const fs::path d = tmpdir();
    const std::string a = (d / "R1.vcd").string(), b = (d / "R2.vcd").string();
    const std::string args = " --pes 8 --size 32x16 --D 8 --trace-pes 0:3";
    const Result ra = run("run --model rtl --vcd " + a + args);
    if (ra.out.find("invalid value 'rtl' for --model") != std::string::npos) return;  // no RTL
    BOOST_TEST_INFO(ra.out);
    BOOST_REQUIRE(ra.code == 0);
    BOOST_TEST(ra.out.find("waves -> " + a) != std::string::npos);
    BOOST_TEST(ra.out.find("the design's signals") != std::string::npos);
    const Result rb = run("run --model rtl --vcd " + b + args);
    BOOST_REQUIRE(rb.code == 0);
    const std::string va = vcdcheck::read_all(a), vb = vcdcheck::read_all(b);
    BOOST_TEST(va.size() > 10000u);
    BOOST_TEST((va == vb));
    BOOST_TEST(!fs::exists(a + ".part"));
    BOOST_TEST(va.find("$timescale 1ps $end") != std::string::npos);
    BOOST_TEST(va.find("$scope module u_cp $end") != std::string::npos);
    BOOST_TEST(va.find(" mcycle ") != std::string::npos);
    BOOST_TEST(va.find("$scope module g_pe[3] $end") != std::string::npos);
    BOOST_TEST(va.find("$scope module g_pe[4] $end") == std::string::npos);  // not selected

    const std::string g = vcdcheck::read_all((d / "R1.gtkw").string());
    BOOST_TEST(g.find("[dumpfile] \"R1.vcd\"") != std::string::npos);
    BOOST_TEST(g.find("dut.imap_tb.u_chip.u_cp.mcycle[63:0]") != std::string::npos);
    BOOST_TEST(g.find("dut.imap_tb.u_chip.u_array.g_pe[3].u_pe.regs[0][7:0]") != std::string::npos);
    fs::remove_all(d);
}

// Issue 13 item 7: the cycle number as a signal (time / period), the
// mnemonic and the operands as signals of their own, and the firmware's
// multi-byte costs as combined decimal vectors in the view.
BOOST_AUTO_TEST_CASE(cycle_counter_split_instruction_and_combined_costs) {
    const fs::path d = tmpdir();
    const std::string v = (d / "c.vcd").string();
    // Inside the forward pass of the default run (DP nodes and the pointer
    // transfers to external memory, several hundred cycles each).
    const Result r =
        run("run --model core --vcd " + v + " --trace-pes 94:95 --trace-window 100000:102000");
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE(r.code == 0);
    const std::string text = vcdcheck::read_all(v);
    const vcdcheck::Parsed p = vcdcheck::parse(text);
    BOOST_TEST(p.error == "");
    const std::string cycle = "top.cp.cycle[30:0]";  // bits for the default watchdog 2e9
    BOOST_REQUIRE(p.history.count(cycle) == 1u);
    const auto& h = p.history.at(cycle);
    BOOST_TEST(h.size() >= 300u);                           // one value per cycle of the window
    for (const auto& [t, c] : h) BOOST_TEST(t == c * 25u);  // 40 MHz: 25 ns per cycle
    for (size_t i = 1; i < h.size(); ++i) BOOST_TEST(h[i].second == h[i - 1].second + 1);
    BOOST_TEST(p.full_names.count("top.cp.op[63:0]") == 1u);
    BOOST_TEST(p.full_names.count("top.cp.args[191:0]") == 1u);
    BOOST_TEST(p.changes_by_name.at("top.cp.op[63:0]") > 50u);

    const std::string g = vcdcheck::read_all((d / "c.gtkw").string());
    const auto vectors = vcdcheck::gtkw_vectors(g);
    const std::string cost = "top.pe094.fwd_run[15:0]";  // firmware::wave_groups(): r5:r6
    bool found = false;
    for (const auto& vec : vectors) {
        if (vec.name != cost) continue;
        found = true;
        // r6 (the high byte) first, bit 7 of each register first.
        BOOST_REQUIRE(vec.bits.size() == 16u);
        const char* regs[2] = {"top.pe094.r6[7:0]", "top.pe094.r5[7:0]"};
        for (int i = 0; i < 16; ++i) {
            BOOST_TEST(vec.bits[static_cast<size_t>(i)].first == i % 8);
            BOOST_TEST(vec.bits[static_cast<size_t>(i)].second == regs[i / 8]);
        }
    }
    BOOST_TEST(found, cost << " in the view");
    // Shown as decimal: the flags line before it is @24 (or with the collapsed bit).
    const size_t at = g.find("#{" + cost + "}");
    BOOST_REQUIRE(at != std::string::npos);
    const size_t prev = g.rfind("\n@", at);
    BOOST_REQUIRE(prev != std::string::npos);
    BOOST_TEST(g.substr(prev + 2, 2) == "24");
    for (const std::string& n : vcdcheck::gtkw_signals(g))
        BOOST_TEST(p.full_names.count(n) == 1u, n);
    fs::remove_all(d);
}

// Issue 13 item 7: a window past the end of the run warns (the trace is empty).
BOOST_AUTO_TEST_CASE(trace_window_past_the_end_warns) {
    const fs::path d = tmpdir();
    const std::string v = (d / "late.vcd").string();
    const Result r =
        run("run --model core --size 64x32 --D 16 --vcd " + v + " --trace-window 50000000:");
    BOOST_TEST_INFO(r.out);
    BOOST_TEST(r.code == 0);
    BOOST_TEST(r.out.find("warning: --trace-window 50000000: starts at cycle 50000000, after the "
                          "end of the run") != std::string::npos);
    BOOST_TEST(fs::exists(v));  // written, valid and empty, as the warning says
    fs::remove_all(d);
}

// Issue 32 items 4 and 5: the RTL behaves as the other models. A window
// past the end gives a valid trace and the same warning, never a "->" line
// for a file that does not exist; --trace-limit-mb stops the RTL's trace
// too; and machine cycle c lies at the same time in both models' waves
// (the RTL's axis starts when the reset is released, not at the program
// load before it).
BOOST_AUTO_TEST_CASE(rtl_waves_follow_the_same_rules_as_the_other_models) {
    const fs::path d = tmpdir();
    const std::string late = (d / "late_rtl.vcd").string();
    const std::string args = " --pes 8 --size 32x16 --D 8 --trace-pes 0:1";
    const Result r = run("run --model rtl --vcd " + late + args + " --trace-window 50000000:");
    if (r.out.find("invalid value 'rtl' for --model") != std::string::npos) return;  // no RTL
    BOOST_TEST_INFO(r.out);
    BOOST_TEST(r.code == 0);
    BOOST_TEST(r.out.find("warning: --trace-window 50000000: starts at cycle 50000000, after the "
                          "end of the run") != std::string::npos);
    BOOST_REQUIRE(fs::exists(late));
    BOOST_TEST(r.out.find("waves -> " + late) != std::string::npos);
    BOOST_TEST(vcdcheck::read_all(late).find("$enddefinitions") != std::string::npos);

    // The size limit: a whole-run trace of every PE stops early (the
    // writer buffers, so at about the limit), well short of the full trace.
    const std::string big = (d / "big_rtl.vcd").string(), full = (d / "full_rtl.vcd").string();
    const std::string all = " --pes 8 --size 32x16 --D 8";
    const Result l = run("run --model rtl --vcd " + big + all + " --trace-limit-mb 0.01");
    BOOST_TEST_INFO(l.out);
    BOOST_TEST(l.code == 0);
    BOOST_TEST(l.out.find("stopped at --trace-limit-mb") != std::string::npos);
    const Result f = run("run --model rtl --vcd " + full + all);
    BOOST_REQUIRE(f.code == 0);
    BOOST_TEST(f.out.find("stopped at --trace-limit-mb") == std::string::npos);
    BOOST_TEST(fs::file_size(big) * 2 < fs::file_size(full),
               fs::file_size(big) << " B vs " << fs::file_size(full) << " B");
    BOOST_TEST(vcdcheck::read_all(big).find("$enddefinitions") != std::string::npos);

    // The same window on both models starts at the same time: VCD times
    // in ps (RTL) and ns (ISA tracer), 25 ns per cycle at 40 MHz. The RTL's
    // clock also ticks in zero-cost slots (phase markers), so it may lie a
    // little later; before, it lay 215 us (the program load) later.
    const std::string rv = (d / "w_rtl.vcd").string(), tv = (d / "w_tlm.vcd").string();
    const std::string win = args + " --trace-window 1000:3000";
    BOOST_REQUIRE(run("run --model rtl --vcd " + rv + win).code == 0);
    BOOST_REQUIRE(run("run --model tlm --vcd " + tv + win).code == 0);
    auto first_time_ps = [](const std::string& text, uint64_t unit_ps) {
        const size_t e = text.find("$enddefinitions");
        const size_t h = text.find("\n#", e);
        return h == std::string::npos ? UINT64_MAX : std::stoull(text.substr(h + 2, 24)) * unit_ps;
    };
    const uint64_t t_rtl = first_time_ps(vcdcheck::read_all(rv), 1);
    const uint64_t t_tlm = first_time_ps(vcdcheck::read_all(tv), 1000);
    BOOST_TEST(t_tlm >= 1000u * 25000u);  // the first instruction issued in the window
    BOOST_TEST(t_tlm <= 1010u * 25000u);
    BOOST_TEST(t_rtl + 2 * 25000u >= t_tlm, t_rtl << " ps vs " << t_tlm << " ps");
    BOOST_TEST(t_rtl <= t_tlm + 200u * 25000u, t_rtl << " ps vs " << t_tlm << " ps");
    fs::remove_all(d);
}

// Issue 13 item 2: a .gtkw that cannot be written stops the run before it
// starts (not after, throwing the VCD away).
BOOST_AUTO_TEST_CASE(unwritable_gtkw_is_refused_before_the_run) {
    const fs::path d = tmpdir();
    fs::create_directories(d / "g.gtkw");  // a folder where the view would go
    const std::string v = (d / "g.vcd").string();
    const Result r = run("run --model core --vcd " + v);
    BOOST_TEST_INFO(r.out);
    BOOST_TEST(r.code == 2);
    BOOST_TEST(r.out.find("g.gtkw': is a folder") != std::string::npos);
    BOOST_TEST(r.out.find("bit-exact") == std::string::npos);  // nothing ran
    BOOST_TEST(!fs::exists(v));
    BOOST_TEST(!fs::exists(v + ".part"));
    fs::remove_all(d);
}
