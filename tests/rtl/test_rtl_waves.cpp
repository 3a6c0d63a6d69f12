// Waves of the design's own signals (Verilator tracing of the traced
// variants of the 8-PE configuration): VCD and FST, the PE selection and the
// window, a GTKWave view of the design's hierarchy, byte-identical files for
// identical runs. Each run is one simulation, in a forked child.
#define BOOST_TEST_MODULE rtl_waves
#include <sys/wait.h>
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "rtl_test_util.hpp"

using namespace rtltest;
namespace fs = std::filesystem;

namespace {
std::string slurp(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
}

// Runs the every-class program on the RTL with waves into `path`; the exit
// code of the child (0 ok).
int traced_run(const std::string& path, std::vector<int> pes, uint64_t t0, uint64_t t1) {
    const pid_t pid = fork();
    if (pid == 0) {
        try {
            const isa::MachineConfig cfg = rtl_config(8);
            const isa::Program prog = isa::assemble_string(kProgram, "equiv.s");
            rtl::RtlConfig rc;
            rc.waves.path = path;
            rc.waves.pes = std::move(pes);
            rc.waves.t0 = t0;
            rc.waves.t1 = t1;
            rtl::OutputImages out;
            const auto r = rtl::run_rtl(cfg, prog, kParams, image(10, 3, 1), image(10, 3, 90),
                                        kOutW, kOutH, &out, rc);
            _exit(r.waves_written ? 0 : 3);
        } catch (const std::exception& e) {
            std::fprintf(stderr, "%s\n", e.what());
            _exit(2);
        }
    }
    int st = 0;
    waitpid(pid, &st, 0);
    return WIFEXITED(st) ? WEXITSTATUS(st) : 99;
}
}  // namespace

BOOST_AUTO_TEST_CASE(vcd_and_fst_of_the_design) {
    const fs::path d = fs::temp_directory_path() / ("rtl-waves-" + std::to_string(::getpid()));
    fs::create_directories(d);
    const std::string a = (d / "a.vcd").string(), b = (d / "b.vcd").string();
    BOOST_REQUIRE_EQUAL(traced_run(a, {1, 2}, 0, UINT64_MAX), 0);
    BOOST_REQUIRE_EQUAL(traced_run(b, {1, 2}, 0, UINT64_MAX), 0);
    const std::string va = slurp(a);
    BOOST_CHECK(va == slurp(b));  // identical runs, identical files
    BOOST_CHECK(va.find("$timescale") != std::string::npos);
    BOOST_CHECK(va.find("$scope module u_cp $end") != std::string::npos);
    // the control word (Verilator 5.006 writes a packed struct as a scope of kind struct)
    BOOST_CHECK(va.find("$scope struct cw $end") != std::string::npos);
    BOOST_CHECK(va.find(" mcycle ") != std::string::npos);
    BOOST_CHECK(va.find(" clk ") != std::string::npos);
    BOOST_CHECK(va.find("$scope module g_pe[1] $end") != std::string::npos);
    BOOST_CHECK(va.find("$scope module g_pe[2] $end") != std::string::npos);
    BOOST_CHECK(va.find("$scope module g_pe[0] $end") == std::string::npos);  // not selected
    BOOST_CHECK(va.find("imap_pkg") == std::string::npos);
    const std::string gtkw = slurp(d / "a.gtkw");
    BOOST_CHECK(gtkw.find("[dumpfile] \"a.vcd\"") != std::string::npos);
    BOOST_CHECK(gtkw.find("dut.imap_tb.u_chip.u_cp.mcycle[63:0]") != std::string::npos);
    BOOST_CHECK(gtkw.find("dut.imap_tb.u_chip.u_array.g_pe[1].u_pe.regs[0][7:0]") !=
                std::string::npos);
    // a window of machine cycles: a smaller file
    const std::string w = (d / "w.vcd").string();
    BOOST_REQUIRE_EQUAL(traced_run(w, {1}, 20, 30), 0);
    BOOST_CHECK_LT(fs::file_size(w), fs::file_size(a));
    // FST, twice
    const std::string f1 = (d / "f1.fst").string(), f2 = (d / "f2.fst").string();
    BOOST_REQUIRE_EQUAL(traced_run(f1, {}, 0, UINT64_MAX), 0);
    BOOST_REQUIRE_EQUAL(traced_run(f2, {}, 0, UINT64_MAX), 0);
    BOOST_CHECK_GT(fs::file_size(f1), 1000u);
    BOOST_CHECK(slurp(f1) == slurp(f2));
    BOOST_CHECK(fs::exists(d / "f1.gtkw"));
    fs::remove_all(d);
}
