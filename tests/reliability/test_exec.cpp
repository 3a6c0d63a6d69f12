// imapsim exec from the outside: a user's program (source or IMAPFW01 file)
// on the core and TLM models. Expectations come from the program text and
// the cost table of docs/isa.md, or from OpenCV, never from a previous run.
#define BOOST_TEST_MODULE reliability_exec
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <string>

#include "cli_test_util.hpp"

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct Dir {
    fs::path path;
    Dir() {
        path = fs::temp_directory_path() / ("imapsim-exec-" + std::to_string(::getpid()));
        fs::remove_all(path);
        fs::create_directories(path);
    }
    ~Dir() { fs::remove_all(path); }
    std::string operator/(const std::string& f) const { return (path / f).string(); }
};

void write_file(const std::string& p, const std::string& text) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out << text;
    BOOST_REQUIRE(out.good());
}

json read_json(const std::string& p) {
    std::ifstream in(p);
    BOOST_REQUIRE_MESSAGE(in.good(), "cannot read " << p);
    return json::parse(in);
}

// c1 = 1 + 2 + ... + N (docs/isa.md §6).
const char* const kSum =
    "; c1 = 1 + 2 + ... + N\n"
    ".ifndef N\n"
    ".equ N 10\n"
    ".endif\n"
    ".phase sum\n"
    "        cli c0, #N\n"
    "        cli c1, #0\n"
    "loop_:  cadd c1, c1, c0\n"
    "        loop c0, loop_\n"
    "        halt\n";

// out(x, y) = 255 - in(x, y) on video port 0, P pixels per segment;
// param 0 = lines, param 1 = width.
const char* const kInvert =
    ".ifndef P\n"
    ".equ P 256\n"
    ".endif\n"
    ".phase invert\n"
    "        cld c1, [#0]\n"
    "        cld c4, [#1]\n"
    "        cli c2, #0\n"
    "row:    cli c3, #0\n"
    "seg:    vin #0, [#0], c2, c3\n"
    "        ld r0, [#0]\n"
    "        xori r0, r0, #255\n"
    "        st r0, [#0]\n"
    "        vout #0, [#0], c2, c3\n"
    "        caddi c3, c3, #P\n"
    "        blt c3, c4, seg\n"
    "        caddi c2, c2, #1\n"
    "        bne c2, c1, row\n"
    "        halt\n";

}  // namespace

BOOST_AUTO_TEST_CASE(sum_program_cycles_and_registers) {
    Dir d;
    write_file(d / "sum.s", kSum);
    for (const long long n : {10LL, 100LL}) {
        // Default costs: cli 1 each, cadd 1, loop 1 (+1 taken), halt 1, phase 0:
        // 2 + N + (2N - 1) + 1 cycles; instructions phase + 2 cli + 2N + halt.
        const long long cycles = 3 * n + 2, instructions = 2 * n + 4, sum = n * (n + 1) / 2;
        json rep[2];
        int k = 0;
        for (const char* model : {"core", "tlm"}) {
            const std::string r = d / (std::string("sum-") + model + ".json");
            const clitest::Result res =
                clitest::run("exec " + (d / "sum.s") + " -D N=" + std::to_string(n) + " --model " +
                             model + " --report " + r);
            BOOST_TEST_CONTEXT(model << " N=" << n << "\n" << res.out) {
                BOOST_REQUIRE(res.code == 0);
                BOOST_TEST(res.out.find("halted: yes") != std::string::npos);
                rep[k] = read_json(r);
                BOOST_TEST(rep[k].at("halted").get<bool>());
                BOOST_TEST(rep[k].at("cycles").get<long long>() == cycles);
                BOOST_TEST(rep[k].at("instructions").get<long long>() == instructions);
                BOOST_TEST(rep[k].at("cp").at(1).get<long long>() == sum);
                BOOST_TEST(rep[k].at("phases").at("sum").get<long long>() == cycles);
                BOOST_TEST(
                    rep[k].at("modeled_ms").get<double>() == static_cast<double>(cycles) / 40e3,
                    boost::test_tools::tolerance(1e-9));
            }
            ++k;
        }
    }
}

BOOST_AUTO_TEST_CASE(invert_image_source_and_binary_on_both_models) {
    Dir d;
    write_file(d / "invert.s", kInvert);
    // 300 pixels wide: two segments of 256 PEs
    cv::Mat img(20, 300, CV_8UC1);
    cv::RNG rng(7);
    rng.fill(img, cv::RNG::UNIFORM, 0, 256);
    BOOST_REQUIRE(cv::imwrite(d / "in.png", img));
    cv::Mat want(img.size(), CV_8UC1);
    for (int y = 0; y < img.rows; ++y)
        for (int x = 0; x < img.cols; ++x) want.at<uint8_t>(y, x) = 255 - img.at<uint8_t>(y, x);

    const clitest::Result as = clitest::run("asm " + (d / "invert.s") + " -o " + (d / "inv.bin"));
    BOOST_TEST_INFO(as.out);
    BOOST_REQUIRE(as.code == 0);
    for (const char* prog : {"invert.s", "inv.bin"})
        for (const char* model : {"core", "tlm"}) {
            const std::string out = d / (std::string(prog) + "-" + model + ".png");
            const clitest::Result r =
                clitest::run("exec " + (d / prog) + " --model " + model + " --left " +
                             (d / "in.png") + " --param 0=20 --param 1=300 --out-left " + out);
            BOOST_TEST_CONTEXT(prog << " on " << model << "\n" << r.out) {
                BOOST_REQUIRE(r.code == 0);
                const cv::Mat got = cv::imread(out, cv::IMREAD_UNCHANGED);
                BOOST_REQUIRE(!got.empty());
                BOOST_TEST(got.type() == CV_8UC1);
                BOOST_REQUIRE(got.size() == want.size());
                BOOST_TEST(cv::countNonZero(got != want) == 0);
            }
        }
}

BOOST_AUTO_TEST_CASE(param_words_are_32_bit) {
    Dir d;
    write_file(d / "p.s", "cld c1, [#5]\ncld c2, [#255]\nhalt\n");
    const clitest::Result r = clitest::run("exec " + (d / "p.s") +
                                           " --model core --param 5=-1 --param 255=4000000000 "
                                           "--report " +
                                           (d / "r.json"));
    BOOST_TEST_INFO(r.out);
    BOOST_REQUIRE(r.code == 0);
    const json j = read_json(d / "r.json");
    BOOST_TEST(j.at("cp").at(1).get<uint64_t>() == 4294967295u);  // -1 as a 32-bit word
    BOOST_TEST(j.at("cp").at(2).get<uint64_t>() == 4000000000u);
}

// Issue 13 item 8: exec writes waves (--vcd, as run) and prints the PE
// registers, flags and local memory at the end (--dump-pes / --dump-mem),
// also in the report. Expected values come from the program text.
BOOST_AUTO_TEST_CASE(waves_and_pe_dump) {
    const Dir d;
    // PE p: r1 = p + 3, r2 = 2 (p + 3), mem[0x10] = r2, mem[0x11] = 0x5a.
    write_file(d / "pes.s",
               ".phase work\n"
               "        pidx r1, #0\n"
               "        addi r1, r1, #3\n"
               "        add r2, r1, r1\n"
               "        st r2, [#0x10]\n"
               "        li r3, #0x5a\n"
               "        st r3, [#0x11]\n"
               "        halt\n");
    for (const char* model : {"core", "tlm"}) {
        BOOST_TEST_CONTEXT(model) {
            const std::string vcd = d / (std::string(model) + ".vcd");
            const std::string rep = d / (std::string(model) + ".json");
            const clitest::Result r = clitest::run(
                "exec " + (d / "pes.s") + " --model " + model + " --pes 8 --vcd " + vcd +
                " --trace-pes 0:1 --dump-pes 2,5 --dump-mem 0x10:0x11" + " --report " + rep);
            BOOST_TEST_INFO(r.out);
            BOOST_REQUIRE(r.code == 0);
            BOOST_TEST(r.out.find("waves -> " + vcd) != std::string::npos);
            BOOST_TEST(fs::is_regular_file(vcd));
            BOOST_TEST(fs::is_regular_file(d / (std::string(model) + ".gtkw")));
            BOOST_TEST(r.out.find("    pe 2: 00 05 0a 5a") != std::string::npos);
            BOOST_TEST(r.out.find("    pe 5: 00 08 10 5a") != std::string::npos);
            BOOST_TEST(r.out.find("    pe 5 @0x0010: 10 5a") != std::string::npos);
            const json j = read_json(rep);
            BOOST_REQUIRE(j.at("pes").size() == 2u);
            BOOST_TEST(j["pes"][1]["pe"] == 5);
            BOOST_TEST(j["pes"][1]["regs"][1] == 8);
            BOOST_TEST(j["pes"][1]["regs"][2] == 16);
            BOOST_TEST(j["pes"][1]["mem"]["first"] == 16);
            BOOST_TEST(j["pes"][1]["mem"]["bytes"][0] == 16);
            BOOST_TEST(j["pes"][1]["mem"]["bytes"][1] == 0x5a);
            BOOST_TEST(j["pes"][1]["M"] == 1);
            BOOST_TEST(j.at("params").at("machine").at("pes") == 8);
        }
    }
    // Bad selections are refused before the run.
    const std::string src = d / "pes.s";
    for (const char* bad : {"--dump-pes 8 --pes 8", "--dump-pes 3:1", "--dump-mem 0:3",
                            "--dump-pes 0 --dump-mem 0:1024", "--dump-pes 0 --dump-mem 5:2"}) {
        const clitest::Result r = clitest::run("exec " + src + " " + bad);
        BOOST_TEST_CONTEXT(bad << "\n" << r.out) {
            BOOST_TEST(r.code == 2);
            BOOST_TEST(r.out.find("halted") == std::string::npos);
        }
    }
}
