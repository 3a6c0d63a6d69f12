// Issue 32 items 1 and 2: every GTKWave view imapsim writes is loaded in
// GTKWave itself (headless, under Xvfb), and every signal the view names
// must be displayed: GTKWave drops a line it cannot resolve (a signal the
// trace does not hold, an alias it does not parse) without an error, so
// grepping the files cannot tell. The views: the instruction-level VCD
// (core), the RTL's VCD (8 PEs) and FST (256 PEs), and the lockstep's
// divergence waves.
#define BOOST_TEST_MODULE waves_gtkwave_views
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>
#include <string>

#include "cli_test_util.hpp"

namespace fs = std::filesystem;

namespace {

fs::path tmpdir() {
    fs::path d = fs::temp_directory_path() / ("imapsim-gtkwave-" + std::to_string(::getpid()));
    fs::create_directories(d);
    return d;
}

// The signals a .gtkw names: every line that is not a comment ('*'), an
// option ('['), a format ('@') or a group marker ('-'); an alias prefix
// "+{name} " is not part of the signal. A combined vector "#{name} (n)SIG
// ..." names the bits of its sources, which GTKWave lists bit by bit
// (SIG's base name followed by "[bit]"): each source counts as "SIG[*".
std::set<std::string> named_signals(const fs::path& gtkw) {
    std::set<std::string> out;
    std::ifstream in(gtkw);
    for (std::string line; std::getline(in, line);) {
        if (line.empty() || std::string("[*@-").find(line[0]) != std::string::npos) continue;
        if (line[0] == '+') {
            const size_t close = line.find("} ");
            if (close == std::string::npos) continue;
            line = line.substr(close + 2);
        }
        if (line[0] == '#') {
            std::istringstream parts(line.substr(line.find("} ") + 2));
            for (std::string bit; parts >> bit;) {
                const size_t name = bit.find(')') + 1, bracket = bit.find('[', name);
                out.insert(bit.substr(name, bracket - name) + "[*");
            }
            continue;
        }
        out.insert(line);
    }
    return out;
}

// Whether GTKWave's list holds `name` (a "BASE[*" entry: any bit of BASE).
bool shown_in(const std::set<std::string>& shown, const std::string& name) {
    if (name.size() < 2 || name.compare(name.size() - 2, 2, "[*") != 0)
        return shown.count(name) > 0;
    const std::string base = name.substr(0, name.size() - 1);
    const auto it = shown.lower_bound(base);
    return it != shown.end() && it->compare(0, base.size(), base) == 0;
}

// The signals GTKWave displays for `gtkw`, from its Tcl interface.
std::set<std::string> displayed_signals(const fs::path& dir, const fs::path& gtkw) {
    const fs::path tcl = dir / "list.tcl", shown = dir / "shown.txt";
    fs::remove(shown);
    std::ofstream(tcl) << "set f [open \"" << shown.string() << "\" w]\n"
                       << "foreach s [gtkwave::getDisplayedSignals] { puts $f $s }\n"
                       << "close $f\ngtkwave::/File/Quit\n";
    const std::string cmd = "cd '" + gtkw.parent_path().string() + "' && timeout 120 '" + XVFB_RUN +
                            "' -a '" + GTKWAVE + "' -S '" + tcl.string() + "' '" +
                            gtkw.filename().string() + "' > '" + (dir / "gtkwave.log").string() +
                            "' 2>&1";
    BOOST_TEST_REQUIRE(std::system(cmd.c_str()) == 0, "gtkwave failed: " << cmd);
    std::set<std::string> out;
    std::ifstream in(shown);
    for (std::string line; std::getline(in, line);)
        if (!line.empty()) out.insert(line);
    return out;
}

void check_view(const fs::path& dir, const fs::path& gtkw) {
    BOOST_TEST_CONTEXT(gtkw.filename().string()) {
        BOOST_TEST_REQUIRE(fs::exists(gtkw));
        const std::set<std::string> named = named_signals(gtkw);
        const std::set<std::string> shown = displayed_signals(dir, gtkw);
        BOOST_TEST(named.size() > 10u);
        std::string missing;
        for (const std::string& s : named)
            if (!shown_in(shown, s)) missing += "\n  " + s;
        BOOST_TEST(missing.empty(), "named in the view but not displayed by GTKWave:" << missing);
    }
}

// Runs `args` in a fresh folder `sub` (exit `code`) and checks the view
// `gtkw` it wrote there.
void check_run_view(const std::string& sub, const std::string& args, const std::string& gtkw,
                    int code = 0) {
    const fs::path d = tmpdir() / sub;
    fs::create_directories(d);
    const clitest::Result r = clitest::run(args, d.string());
    BOOST_TEST_INFO(r.out);
    BOOST_TEST_REQUIRE(r.code == code);
    check_view(d, d / gtkw);
}

}  // namespace

BOOST_AUTO_TEST_CASE(instruction_level_view) {
    check_run_view("core",
                   "run --model core --size 32x12 --D 6 --vcd core.vcd --trace-window 0:2000",
                   "core.gtkw");
}

BOOST_AUTO_TEST_CASE(rtl_vcd_view_8_pes) {
    check_run_view("rtl8",
                   "run --model rtl --pes 8 --size 32x12 --D 6 --vcd r.vcd --trace-pes 0:1 "
                   "--trace-window 0:800",
                   "r.gtkw");
}

BOOST_AUTO_TEST_CASE(rtl_fst_view_256_pes) {
    check_run_view("rtl256",
                   "run --model rtl --pes 256 --size 32x12 --D 6 --vcd r.fst --trace-pes 4:7 "
                   "--trace-window 0:800",
                   "r.gtkw");
}

BOOST_AUTO_TEST_CASE(lockstep_divergence_view) {
    // the divergence's exit code 1, and its waves' view
    check_run_view("lockstep",
                   "run --model lockstep --pes 8 --size 32x12 --D 6 --inject-fault 20:3:r5:0x24",
                   "rtl_divergence.gtkw", 1);
    fs::remove_all(tmpdir());
}
