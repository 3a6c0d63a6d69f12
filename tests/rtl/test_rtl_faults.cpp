// Machine faults of the RTL design: a program that faults stops the design
// in the faulting instruction's first cycle, and run_rtl reports it as an
// isa::Fault with the PC, cycle, PE and address of the instruction-set
// model's fault. Each case is one simulation, in a forked child.
#define BOOST_TEST_MODULE rtl_faults
#include <sys/wait.h>
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <cstdio>
#include <fstream>

#include "rtl_test_util.hpp"

using namespace rtltest;

namespace {
struct Outcome {
    bool fault = false;
    uint32_t pc = 0;
    int64_t pe = -2, address = -2;
    uint64_t cycle = 0;
    std::string what;
};

// The fault of `src` on the core and (in a child process) on the RTL.
std::pair<Outcome, Outcome> both(const std::string& src, isa::MachineConfig cfg) {
    const isa::Program prog = isa::assemble_string(src, "f.s");
    Outcome core, rtl_out;
    try {
        isa::Machine m(cfg);
        m.load(prog);
        m.run();
    } catch (const isa::Fault& f) {
        core = {true, f.pc(), f.pe(), f.address(), f.cycle(), f.what()};
    }
    char tmpl[] = "/tmp/rtl-fault-XXXXXX";
    const int fd = mkstemp(tmpl);
    close(fd);
    const pid_t pid = fork();
    if (pid == 0) {
        std::ofstream o(tmpl);
        try {
            rtl::run_rtl(cfg, prog, {}, rtl::ImageInput{}, rtl::ImageInput{}, 0, 0, nullptr);
            o << "0\n";
        } catch (const isa::Fault& f) {
            o << "1 " << f.pc() << " " << f.pe() << " " << f.address() << " " << f.cycle() << "\n"
              << f.what() << "\n";
        } catch (const std::exception& e) {
            o << "2\n" << e.what() << "\n";
        }
        o.close();
        _exit(0);
    }
    int st = 0;
    waitpid(pid, &st, 0);
    std::ifstream in(tmpl);
    int kind = -1;
    in >> kind;
    if (kind == 1) {
        rtl_out.fault = true;
        in >> rtl_out.pc >> rtl_out.pe >> rtl_out.address >> rtl_out.cycle;
    }
    std::getline(in, rtl_out.what);
    std::getline(in, rtl_out.what);
    std::remove(tmpl);
    return {core, rtl_out};
}

void same_fault(const std::string& src, isa::MachineConfig cfg = rtl_config(8)) {
    const auto [c, r] = both(src, cfg);
    BOOST_TEST_CONTEXT(src << "\ncore: " << c.what << " (pe " << c.pe << ", address " << c.address
                           << ")\nrtl: " << r.what) {
        BOOST_REQUIRE(c.fault);
        BOOST_REQUIRE(r.fault);
        BOOST_CHECK_EQUAL(r.pc, c.pc);
        BOOST_CHECK_EQUAL(r.cycle, c.cycle);
        BOOST_CHECK_EQUAL(r.pe, c.pe);
        if (c.address != isa::Fault::kNone) BOOST_CHECK_EQUAL(r.address, c.address);
        BOOST_CHECK(r.what.find("fault at pc " + std::to_string(c.pc)) != std::string::npos);
    }
}
}  // namespace

BOOST_AUTO_TEST_CASE(broadcast_address) {
    same_fault("cli c1, #1000\n ld r1, [c1 + 30]\n halt\n");
}
BOOST_AUTO_TEST_CASE(per_pe_address) {
    same_fault("pidx r1, #0\n shli r1, r1, #7\n ldx r2, [r1 + 900]\n halt\n");
}
BOOST_AUTO_TEST_CASE(mask_stack) {
    same_fault("mif\nmif\nmif\nmif\nmif\nmif\nmif\nmif\nmif\nhalt\n");
    same_fault("mend\nhalt\n");
}
BOOST_AUTO_TEST_CASE(return_stack) {
    same_fault("ret\nhalt\n");
    // overflow: a subroutine that calls itself, call_depth 3 (found by the
    // design's code coverage: the overflow arm was never taken)
    isa::MachineConfig cfg = rtl_config(8);
    cfg.call_depth = 3;
    same_fault("call s\n halt\ns: add r1, r1, r2\n call s\n ret\n", cfg);
}
BOOST_AUTO_TEST_CASE(param_block) {
    same_fault("cli c2, #200\n cld c1, [c2 + 56]\n halt\n");
}
BOOST_AUTO_TEST_CASE(transfers) {
    same_fault("cli c1, #-1\n cli c2, #0\n xld [#0], ext[c2], c1\n halt\n");
    same_fault("cli c1, #30\n cli c2, #0\n xst [#1000], ext[c2], c1\n halt\n");
    same_fault("cli c1, #30\n cli c2, #65530\n xld [#0], ext[c2], c1\n halt\n");
    same_fault("cli c1, #30\n cli c2, #65530\n xld [#1000], ext[c2], c1\n halt\n");
}
// a video row outside local memory (1024 bytes): refused in decode (found by
// the design's code coverage)
BOOST_AUTO_TEST_CASE(video_row) {
    same_fault("cli c1, #0\n vin #0, [#1100], c1, c1\n halt\n");
    same_fault("cli c1, #0\n cli c2, #1020\n vout #1, [c2 + 4], c1, c1\n halt\n");
}
BOOST_AUTO_TEST_CASE(video_port_missing) {
    same_fault("cli c1, #0\n vin #0, [#0], c1, c1\n halt\n");
}
BOOST_AUTO_TEST_CASE(watchdog) {
    isa::MachineConfig cfg = rtl_config(8);
    cfg.watchdog_cycles = 500;
    same_fault("lp: add r1, r1, r2\n jmp lp\n", cfg);
    const auto [c, r] = both("lp: add r1, r1, r2\n jmp lp\n", cfg);
    BOOST_CHECK(r.what.find("watchdog_cycles = 500") != std::string::npos);
}
// The boundary: an instruction that starts at cycle watchdog_cycles faults
// (the run would be longer). The loop's instructions start at 3k (add) and
// 3k + 1 (jmp): 499 = 3 * 166 + 1 is a start, so an RTL that fired only
// after the limit (mcycle > watchdog_cycles) would fault at 501 instead.
BOOST_AUTO_TEST_CASE(watchdog_boundary) {
    isa::MachineConfig cfg = rtl_config(8);
    cfg.watchdog_cycles = 499;
    same_fault("lp: add r1, r1, r2\n jmp lp\n", cfg);
}
BOOST_AUTO_TEST_CASE(pc_past_the_end) {
    same_fault("nop\nnop\n");
}
