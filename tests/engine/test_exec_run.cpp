// engine.exec_run: a user's program through the library (exec.hpp) on the
// core model: a sum whose result, cycles and instructions are computed by
// hand (docs/isa.md costs), the PEs' registers and memory at the end, the
// report, a program that does not fit the machine, and source detection.
#define BOOST_TEST_MODULE engine_exec_run
#include <boost/test/unit_test.hpp>

#include "engine_test_util.hpp"
#include "imap/engine/error.hpp"
#include "imap/engine/exec.hpp"
#include "imap/engine/exec_request.hpp"
#include "imap/isa/assembler.hpp"

namespace e = imap::engine;
namespace ex = imap::engine::exec;
namespace isa = imap::isa;
using enginetest::Cleanup;
using enginetest::tmpdir;
BOOST_TEST_GLOBAL_FIXTURE(Cleanup);

namespace {

isa::MachineConfig pes(int n) {
    isa::MachineConfig cfg;
    cfg.set("pes", std::to_string(n));
    cfg.validate();
    return cfg;
}

// c1 = N + (N-1) + ... + 1 in phase "sum".
std::string sum_source(int n) {
    return ".phase sum\n"
           "        cli c0, #" +
           std::to_string(n) +
           "\n"
           "        cli c1, #0\n"
           "s:      cadd c1, c1, c0\n"
           "        loop c0, s\n"
           "        halt\n";
}

}  // namespace

BOOST_AUTO_TEST_CASE(the_sum_of_one_to_n) {
    for (const int n : {10, 37}) {
        const isa::Program prog = isa::assemble_string(sum_source(n), "sum.s");
        const isa::MachineConfig cfg = pes(8);
        std::unique_ptr<isa::Machine> m = ex::load_machine(cfg, prog, "sum.s");
        ex::Inputs in;
        in.name = "sum.s";
        const ex::Result r = ex::run("core", m, prog, in);
        // cli 1 each, cadd 1, loop 1 (+1 taken, N-1 times), halt 1.
        const uint64_t cycles = 2 + n + (2 * n - 1) + 1;
        BOOST_TEST(r.cycles == cycles);
        BOOST_TEST(r.cp[1] == static_cast<uint32_t>(n * (n + 1) / 2));
        BOOST_TEST(r.cp[0] == 0u);
        BOOST_TEST(r.stats.instructions == static_cast<uint64_t>(2 * n + 4));
        BOOST_TEST(r.modeled_ms == static_cast<double>(cycles) / 40e3);
        uint64_t in_sum = 0;
        for (const auto& [name, c] : r.phases)
            if (name == "sum") in_sum = c;
        BOOST_TEST(in_sum == cycles);
        const nlohmann::json j =
            ex::report("sum.s", "core", cfg, in, r, nlohmann::json::array(), "", "");
        BOOST_TEST(j.at("cycles").get<uint64_t>() == cycles);
        BOOST_TEST(j.at("cp").at(1).get<long long>() == n * (n + 1) / 2);
        BOOST_TEST(j.at("phases").at("sum").get<uint64_t>() == cycles);
        BOOST_TEST(j.at("params").at("machine").at("pes").get<int>() == 8);
        BOOST_TEST(!j.contains("pes"));
    }
}

BOOST_AUTO_TEST_CASE(pe_state_and_param_block) {
    // r1 = pe + 3 + param 0, r2 = 2 r1, stored at 0x10; 0x5a at 0x11.
    const std::string src =
        ".phase work\n"
        "        cld c1, [#0]\n"
        "        pidx r1, #0\n"
        "        addi r1, r1, #3\n"
        "        add r2, r1, r1\n"
        "        st r2, [#0x10]\n"
        "        li r3, #0x5a\n"
        "        st r3, [#0x11]\n"
        "        halt\n";
    const isa::Program prog = isa::assemble_string(src, "pes.s");
    const isa::MachineConfig cfg = pes(8);
    std::unique_ptr<isa::Machine> m = ex::load_machine(cfg, prog, "pes.s");
    ex::Inputs in;
    in.params = {{0, 7}};
    const ex::Result r = ex::run("core", m, prog, in);
    BOOST_TEST(r.cp[1] == 7u);
    const nlohmann::json s = ex::pe_state(*m, {2, 5}, true, {0x10, 0x11});
    BOOST_REQUIRE(s.size() == 2u);
    for (size_t k = 0; k < 2; ++k) {
        const int pe = k == 0 ? 2 : 5;
        BOOST_TEST(s[k].at("pe").get<int>() == pe);
        BOOST_TEST(s[k].at("regs").at(0).get<int>() == 0);
        BOOST_TEST(s[k].at("regs").at(1).get<int>() == pe + 3);
        BOOST_TEST(s[k].at("regs").at(2).get<int>() == 2 * (pe + 3));
        BOOST_TEST(s[k].at("regs").at(3).get<int>() == 0x5a);
        BOOST_TEST(s[k].at("mem").at("first").get<int>() == 0x10);
        BOOST_TEST(s[k].at("mem").at("bytes") == nlohmann::json({2 * (pe + 3), 0x5a}));
    }
    const nlohmann::json j = ex::report("pes.s", "core", cfg, in, r, s, "", "");
    BOOST_TEST(j.at("params").at("param_block").at("0").get<int>() == 7);
    BOOST_TEST(j.at("pes").size() == 2u);
}

BOOST_AUTO_TEST_CASE(models_and_sources) {
    BOOST_CHECK_NO_THROW(ex::check_model("core"));
    BOOST_CHECK_THROW(ex::check_model("lockstep"), e::Error);
    BOOST_TEST(ex::is_source("x.s"));
    BOOST_TEST(ex::is_source("X.ASM"));
    const std::string bin = (tmpdir() / "prog.bin").string();
    const isa::Program prog = isa::assemble_string(sum_source(3), "sum.s");
    isa::save_program(prog, bin);
    BOOST_TEST(!ex::is_source(bin));
    std::unique_ptr<isa::Machine> m = ex::load_machine(pes(8), isa::load_program(bin), bin);
    ex::Inputs in;
    BOOST_TEST(ex::run("core", m, prog, in).cp[1] == 6u);
}

namespace {

// exec's checks before the run (exec_request.hpp), with imapsim's messages.

std::string check_error(const ex::Request& r) {
    try {
        ex::check(r, [] {});
    } catch (const e::Error& e) {
        BOOST_TEST(e.code() == e::kExitInput);
        return e.what();
    }
    return "";
}

ex::Request core() {
    ex::Request r;
    r.program = "p.s";
    r.model = "core";
    return r;
}

}  // namespace

BOOST_AUTO_TEST_CASE(check_refusals) {
    ex::Request r = core();
    r.dump_mem = "0:15";
    BOOST_TEST(check_error(r) == "--dump-mem needs --dump-pes (whose memory to print)");
    r = core();
    r.out_size = "0x5";
    BOOST_TEST(check_error(r) ==
               "invalid value '0x5' for --out-size: expected WxH with W and H in 1..65536");
    r = core();
    r.out_left = "o.png";
    BOOST_TEST(check_error(r) ==
               "--out-left needs an input image (--left or --right) or --out-size: the output "
               "image has the size of the inputs");
}

BOOST_AUTO_TEST_CASE(check_fills_the_inputs) {
    ex::Request r = core();
    r.out_size = "32x16";
    r.dump_pes = "0,3";
    r.dump_mem = "0:15";
    r.params = {"1=5"};
    const ex::Checked c = ex::check(r, [] {});
    BOOST_TEST((c.in.out_w == 32 && c.in.out_h == 16));
    BOOST_TEST((c.dump_pes == std::vector<int>{0, 3}));
    BOOST_TEST(c.mem_range.first == 0u);
    BOOST_TEST(c.mem_range.second == 15u);
    BOOST_TEST(c.in.params.size() == 1u);
    BOOST_TEST(c.in.name == "p.s");
}
