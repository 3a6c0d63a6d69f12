// The VCD writer and the GTKWave save file: header, scopes, value changes
// only, identical bytes for identical input, text signals, the size limit,
// atomic output, and the trace options.
#define BOOST_TEST_MODULE waves_vcd
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <sstream>
#include <string>

#include "imap/isa/assembler.hpp"
#include "imap/waves/gtkw.hpp"
#include "imap/waves/isa_trace.hpp"
#include "imap/waves/vcd.hpp"
#include "vcd_check.hpp"

namespace fs = std::filesystem;
namespace w = imap::waves;

namespace {

fs::path tmpdir() {
    fs::path d = fs::temp_directory_path() / ("imap-waves-vcd-" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}

struct Ids {
    w::SignalId clk, bus, txt, wide;
};

// A small fixed design: top.clk, top.u.bus[7:0], top.u.txt (8 chars),
// top.u.v.wide[63:0]; 10 cycles of changes.
Ids declare(w::VcdWriter& v) {
    Ids i{};
    v.push_scope("top");
    i.clk = v.add_wire("clk", 1);
    v.push_scope("u");
    i.bus = v.add_wire("bus", 8);
    i.txt = v.add_text("txt", 8);
    v.push_scope("v");
    i.wide = v.add_wire("wide", 64);
    v.pop_scope();
    v.pop_scope();
    v.pop_scope();
    return i;
}

void drive(w::VcdWriter& v, const Ids& i) {
    v.begin();
    for (uint64_t t = 0; t < 10; ++t) {
        v.set_time(t * 5);
        v.change(i.clk, t & 1);
        v.change(i.bus, t < 5 ? 7 : 0x1F3);  // masked to 8 bits: 0xF3
        v.change_text(i.txt, t < 3 ? "nop" : "add r1");
        v.change(i.wide, t == 9 ? ~uint64_t{0} : 1);
    }
    v.finish(50);
}

std::string write_design(const fs::path& p) {
    w::VcdWriter v(p.string());
    drive(v, declare(v));
    return vcdcheck::read_all(p.string());
}

}  // namespace

BOOST_AUTO_TEST_CASE(header_scopes_and_names) {
    const fs::path p = tmpdir() / "h.vcd";
    w::VcdWriter v(p.string());
    const Ids i = declare(v);
    BOOST_TEST(v.full_name(i.clk) == "top.clk");
    BOOST_TEST(v.full_name(i.bus) == "top.u.bus[7:0]");
    BOOST_TEST(v.full_name(i.txt) == "top.u.txt[63:0]");
    BOOST_TEST(v.full_name(i.wide) == "top.u.v.wide[63:0]");
    drive(v, i);
    const std::string s = vcdcheck::read_all(p.string());
    BOOST_TEST(s.find("$timescale 1ns $end") != std::string::npos);
    BOOST_TEST(s.find("$scope module top $end") != std::string::npos);
    BOOST_TEST(s.find("$var wire 8 \" bus [7:0] $end") != std::string::npos);
    BOOST_TEST(s.find("$enddefinitions $end") != std::string::npos);
    // No date or version of the host anywhere.
    BOOST_TEST(s.find("$date") == std::string::npos);
    const vcdcheck::Parsed r = vcdcheck::parse(s);
    BOOST_TEST(r.error == "");
    BOOST_TEST(r.vars.size() == 4u);
    BOOST_TEST(r.full_names.count("top.u.v.wide[63:0]") == 1u);
    BOOST_TEST(!fs::exists(p.string() + ".part"));
}

BOOST_AUTO_TEST_CASE(value_changes_only) {
    const fs::path p = tmpdir() / "c.vcd";
    const vcdcheck::Parsed r = vcdcheck::parse(write_design(p));
    BOOST_REQUIRE(r.error == "");
    // clk toggles every step: 10 values; bus: dump + one change; txt: dump +
    // one change; wide: dump + one change.
    BOOST_TEST(r.changes_by_name.at("top.clk") == 10u);
    BOOST_TEST(r.changes_by_name.at("top.u.bus[7:0]") == 2u);
    BOOST_TEST(r.changes_by_name.at("top.u.txt[63:0]") == 2u);
    BOOST_TEST(r.changes_by_name.at("top.u.v.wide[63:0]") == 2u);
    // Time stamps 0..45 and the final 50.
    BOOST_TEST(r.times.size() == 11u);
    BOOST_TEST(r.times.back() == 50u);
    const std::string s = vcdcheck::read_all(p.string());
    BOOST_TEST(s.find("b11110011 \"") != std::string::npos);  // 0x1F3 masked to 8 bits
}

BOOST_AUTO_TEST_CASE(same_time_keeps_the_last_value_and_drops_no_changes) {
    const fs::path p = tmpdir() / "s.vcd";
    w::VcdWriter v(p.string());
    v.push_scope("top");
    const w::SignalId a = v.add_wire("a", 4);
    v.pop_scope();
    v.begin();
    v.set_time(0);
    v.change(a, 1);
    v.set_time(10);
    v.change(a, 3);
    v.change(a, 1);  // back to the old value at the same time: no change
    v.set_time(20);
    v.change(a, 2);
    v.change(a, 5);
    v.finish(20);
    const std::string s = vcdcheck::read_all(p.string());
    BOOST_TEST(s.find("#10") == std::string::npos);
    BOOST_TEST(s.find("#20\nb101 !\n") != std::string::npos);
    BOOST_TEST(s.find("b10 !") == std::string::npos);
    BOOST_TEST(vcdcheck::parse(s).error == "");
}

BOOST_AUTO_TEST_CASE(identical_input_identical_bytes) {
    const fs::path d = tmpdir();
    const std::string a = write_design(d / "a.vcd");
    const std::string b = write_design(d / "b.vcd");
    BOOST_TEST(!a.empty());
    BOOST_TEST(a == b);
}

BOOST_AUTO_TEST_CASE(text_is_ascii_right_justified) {
    const fs::path p = tmpdir() / "t.vcd";
    w::VcdWriter v(p.string());
    const w::SignalId t = v.add_text("t", 4);
    v.begin();
    v.set_time(0);
    v.change_text(t, "AB");  // 0x41 0x42 in the low bytes
    v.set_time(1);
    v.change_text(t, "ABCDEFG");  // truncated to 4 characters
    v.finish(2);
    const std::string s = vcdcheck::read_all(p.string());
    BOOST_TEST(s.find("b100000101000010 !") != std::string::npos);
    BOOST_TEST(s.find("b1000001010000100100001101000100 !") != std::string::npos);
}

BOOST_AUTO_TEST_CASE(time_never_goes_back_and_widths_are_checked) {
    const fs::path p = tmpdir() / "b.vcd";
    w::VcdWriter v(p.string());
    BOOST_CHECK_THROW(v.add_wire("x", 0), w::WaveError);
    BOOST_CHECK_THROW(v.add_wire("x", 65), w::WaveError);
    BOOST_CHECK_THROW(v.add_wire("has space", 1), w::WaveError);
    const w::SignalId x = v.add_wire("x", 1);
    v.begin();
    BOOST_CHECK_THROW(v.add_wire("late", 1), w::WaveError);
    v.set_time(10);
    v.change(x, 1);
    BOOST_CHECK_THROW(v.set_time(9), w::WaveError);
    v.finish(10);
    BOOST_TEST(fs::exists(p));
}

BOOST_AUTO_TEST_CASE(unwritable_path_is_a_clear_error_and_leaves_nothing) {
    const fs::path p = tmpdir() / "no-such-dir" / "x.vcd";
    w::VcdWriter v(p.string());
    v.add_wire("x", 1);
    try {
        v.begin();
        BOOST_FAIL("begin() should have thrown");
    } catch (const w::WaveError& e) {
        const std::string m = e.what();
        BOOST_TEST(m.find("cannot create") != std::string::npos);
        BOOST_TEST(m.find("x.vcd") != std::string::npos);
    }
    BOOST_TEST(!fs::exists(p));
    BOOST_TEST(!fs::exists(p.string() + ".part"));
    BOOST_CHECK_THROW(w::write_text_atomic(p.string(), "x"), w::WaveError);
    BOOST_TEST(!fs::exists(p.string() + ".part"));
}

BOOST_AUTO_TEST_CASE(abandoned_writer_leaves_nothing) {
    const fs::path p = tmpdir() / "abandoned.vcd";
    {
        w::VcdWriter v(p.string());
        const w::SignalId x = v.add_wire("x", 1);
        v.begin();
        v.set_time(0);
        v.change(x, 1);
        BOOST_TEST(fs::exists(p.string() + ".part"));
    }  // destroyed without finish(), e.g. by an exception
    BOOST_TEST(!fs::exists(p));
    BOOST_TEST(!fs::exists(p.string() + ".part"));
}

BOOST_AUTO_TEST_CASE(size_limit_stops_cleanly_with_a_warning) {
    const fs::path p = tmpdir() / "limit.vcd";
    std::ostringstream warn;
    w::VcdOptions o;
    o.limit_bytes = 2000;
    o.limit_name = "--trace-limit-mb 0.002";
    o.warn = &warn;
    w::VcdWriter v(p.string(), o);
    const w::SignalId x = v.add_wire("x", 32);
    v.begin();
    for (uint64_t t = 0; t < 10000; ++t) {
        v.set_time(t);
        v.change(x, t * 2654435761u);
    }
    v.finish(10000);
    BOOST_TEST(v.limit_reached());
    BOOST_TEST(fs::file_size(p) < 2200u);
    BOOST_TEST(warn.str().find("--trace-limit-mb 0.002") != std::string::npos);
    const std::string s = vcdcheck::read_all(p.string());
    BOOST_TEST(s.find("trace stopped") != std::string::npos);
    BOOST_TEST(vcdcheck::parse(s).error == "");
}

BOOST_AUTO_TEST_CASE(gtkw_references_declared_signals) {
    const fs::path d = tmpdir();
    w::VcdWriter v((d / "g.vcd").string());
    const Ids i = declare(v);
    w::GtkwSave g("g.vcd");
    g.begin_group("U");
    g.add_signal(v.full_name(i.bus), w::Format::Hex);
    g.add_signal(v.full_name(i.txt), w::Format::Ascii);
    g.begin_group("closed", true);
    g.add_signal(v.full_name(i.wide), w::Format::Dec);
    g.end_group();
    g.end_group();
    g.add_signal(v.full_name(i.clk), w::Format::Bin);
    g.add_marker(25, "half");
    g.set_view(0, 50);
    drive(v, i);
    g.write((d / "g.gtkw").string());
    const std::string t = vcdcheck::read_all((d / "g.gtkw").string());
    BOOST_TEST(t.find("[dumpfile] \"g.vcd\"") != std::string::npos);
    BOOST_TEST(t.find("@820\ntop.u.txt[63:0]") != std::string::npos);  // ASCII format
    BOOST_TEST(t.find("@800200\n-U") != std::string::npos);
    BOOST_TEST(t.find("@c00200\n-closed") != std::string::npos);
    BOOST_TEST(t.find("[markername] Ahalf") != std::string::npos);
    const vcdcheck::Parsed r = vcdcheck::parse(vcdcheck::read_all((d / "g.vcd").string()));
    const auto names = vcdcheck::gtkw_signals(t);
    BOOST_TEST(names.size() == 4u);
    for (const std::string& n : names) BOOST_TEST(r.full_names.count(n) == 1u, n);
    BOOST_TEST(names == g.signals());
}

BOOST_AUTO_TEST_CASE(clock_scale_and_trace_options) {
    BOOST_TEST(w::clock_scale(40).timescale == "1ns");
    BOOST_TEST(w::clock_scale(40).period == 25u);
    BOOST_TEST(w::clock_scale(1000).period == 1u);
    BOOST_TEST(w::clock_scale(33).timescale == "1ps");
    BOOST_TEST(w::clock_scale(33).period == 30303u);
    BOOST_CHECK_THROW(w::clock_scale(0), w::WaveError);

    imap::isa::MachineConfig cfg;  // 256 PEs at 40 MHz
    w::TraceSelection s = w::parse_trace_selection("", "", "", 200, cfg);
    BOOST_TEST((s.pes == std::vector<int>{0, 1, 2, 3}));
    BOOST_TEST(s.t0 == 0u);
    BOOST_TEST(s.t1 == UINT64_MAX);
    BOOST_TEST((s.cp && s.ring && s.mask && s.mem && s.regs));
    BOOST_TEST(s.limit_bytes == 200u << 20);
    s = w::parse_trace_selection("9,1:2,5", "100:200", "cp,mem", 1.5, cfg);
    BOOST_TEST((s.pes == std::vector<int>{1, 2, 5, 9}));
    BOOST_TEST(s.t0 == 100u);
    BOOST_TEST(s.t1 == 200u);
    BOOST_TEST((s.cp && s.mem && !s.ring && !s.mask && !s.regs));
    s = w::parse_trace_selection("0", "2.5us:3us", "all", 200, cfg);
    BOOST_TEST(s.t0 == 100u);  // 2.5 us at 40 MHz
    BOOST_TEST(s.t1 == 120u);
    s = w::parse_trace_selection("0", "1000ns:", "", 200, cfg);
    BOOST_TEST(s.t0 == 40u);
    BOOST_TEST(s.t1 == UINT64_MAX);
    auto err = [&](const char* pes, const char* win, const char* sig, double mb) {
        try {
            w::parse_trace_selection(pes, win, sig, mb, cfg);
        } catch (const w::WaveError& e) {
            return std::string(e.what());
        }
        return std::string();
    };
    BOOST_TEST(err("256", "", "", 200).find("invalid value '256' for --trace-pes") == 0u);
    BOOST_TEST(err("3:1", "", "", 200).find("--trace-pes") != std::string::npos);
    BOOST_TEST(err("", "5:5", "", 200).find("invalid value '5:5' for --trace-window") == 0u);
    BOOST_TEST(err("", "1x:5", "", 200).find("--trace-window") != std::string::npos);
    BOOST_TEST(err("", "", "cp,bogus", 200).find("--trace-signals") != std::string::npos);
    BOOST_TEST(err("", "", "", 0).find("--trace-limit-mb") != std::string::npos);
}

// Issue 13 item 2: a finished trace is kept when its companion .gtkw cannot
// be written (here a folder took its name after the checks); finish() says why.
BOOST_AUTO_TEST_CASE(vcd_is_kept_when_the_view_cannot_be_written) {
    namespace isa = imap::isa;
    const fs::path d = tmpdir();
    const std::string vcd = (d / "k.vcd").string();
    isa::MachineConfig cfg;
    cfg.pes = 4;
    const isa::Program prog = isa::assemble_string("li r1, #5\naddi r2, r1, #1\nhalt\n");
    w::TraceSelection sel = w::parse_trace_selection("0:1", "", "", 200, cfg);
    sel.groups = {{"pair", {1, 2}}};
    w::IsaTracer tracer(vcd, cfg, prog, sel);
    isa::Machine m(cfg);
    m.load(prog);
    m.set_observer(&tracer);
    m.run();
    fs::create_directories(d / "k.gtkw");
    BOOST_CHECK_NO_THROW(tracer.finish(m.cycles()));
    BOOST_TEST(fs::is_regular_file(vcd));
    BOOST_TEST(!tracer.gtkw_error().empty());
    BOOST_TEST(vcdcheck::parse(vcdcheck::read_all(vcd)).error == "");
    fs::remove_all(d);
}

// The combined vectors of a register group: GTKWave's "#{name} (bit)parent"
// lines, most significant register and bit first.
BOOST_AUTO_TEST_CASE(register_groups_become_combined_vectors) {
    namespace isa = imap::isa;
    const fs::path d = tmpdir();
    const std::string vcd = (d / "v.vcd").string();
    isa::MachineConfig cfg;
    cfg.pes = 4;
    const isa::Program prog = isa::assemble_string("li r1, #5\nhalt\n");
    w::TraceSelection sel = w::parse_trace_selection("2", "", "", 200, cfg);
    sel.groups = {{"cost", {3, 4, 5}}};
    {
        w::IsaTracer tracer(vcd, cfg, prog, sel);
        isa::Machine m(cfg);
        m.load(prog);
        m.set_observer(&tracer);
        m.run();
        tracer.finish(m.cycles());
        BOOST_TEST(tracer.gtkw_error() == "");
    }
    const std::string g = vcdcheck::read_all((d / "v.gtkw").string());
    std::string want = "#{top.pe2.cost[23:0]}";
    for (const int r : {5, 4, 3})
        for (int b = 0; b < 8; ++b)
            want += " (" + std::to_string(b) + ")top.pe2.r" + std::to_string(r) + "[7:0]";
    BOOST_TEST(g.find("@24\n" + want + "\n") != std::string::npos, g);
    // A group naming a register that is not traced is refused.
    sel.groups = {{"bad", {3, 40}}};
    BOOST_CHECK_THROW(w::IsaTracer((d / "x.vcd").string(), cfg, prog, sel), w::WaveError);
    BOOST_TEST(!fs::exists(d / "x.vcd"));
    fs::remove_all(d);
}
