// The bad-input matrix of imapsim (docs/errors.md): one test case per row.
// Each row runs the imapsim binary with one bad input and checks
//   - the exit code (2 bad input, 3 machine fault),
//   - that the message is one "imapsim: error: ..." line naming the problem
//     (the flag or file, the value, the allowed range: the row's substrings),
//   - that no output file appears and no temporary is left behind, and that
//     an output file that existed before is left byte-identical.
// Half of the rows run into an empty output folder (nothing may appear), the
// other half with every output file the command names ({o}/NAME) pre-created
// with known content (each must be unchanged).
//
// Adding a row: one ERROR_ROW(name, exit code, "arguments", "substring", ...).
// In the arguments {in} is the folder of the prepared inputs (see Inputs),
// {o} the row's output folder and {ro} a folder where no file can be created. Rows are grouped in
// test suites; CMake registers one CTest test per suite (reliability.errors.<suite>), found in this
// file, so a new suite needs no CMake change; every test case must be inside a suite (one at the
// top level would not be run by CTest).
#define BOOST_TEST_MODULE reliability_error_matrix
#include <unistd.h>

#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <initializer_list>
#include <map>
#include <opencv2/core.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_util.hpp"

namespace fs = std::filesystem;

namespace {

constexpr int kInput = 2;  // exit codes (docs/errors.md)
constexpr int kFault = 3;

std::string read_file(const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

void write_file(const fs::path& p, const std::string& bytes) {
    std::ofstream out(p, std::ios::binary | std::ios::trunc);
    out << bytes;
    BOOST_REQUIRE(out.good());
}

// 32-bit FNV-1a, the checksum of the program file format (docs/isa.md §8).
uint32_t fnv1a(const std::string& b) {
    uint32_t h = 2166136261u;
    for (unsigned char c : b) {
        h ^= c;
        h *= 16777619u;
    }
    return h;
}

void put32(std::string& b, uint32_t v) {
    for (int i = 0; i < 4; ++i) b.push_back(static_cast<char>((v >> (8 * i)) & 0xFF));
}

// An IMAPFW01 file written from the format description (docs/isa.md §8), no
// phases, symbols or source map: independent of the assembler.
std::string program_file(const std::vector<uint64_t>& code) {
    std::string b = "IMAPFW01";
    put32(b, 1);  // version
    put32(b, 0);  // flags: no source map
    put32(b, static_cast<uint32_t>(code.size()));
    put32(b, 0);  // phases
    put32(b, 0);  // symbols
    put32(b, 0);  // files
    for (uint64_t w : code) {
        put32(b, static_cast<uint32_t>(w));
        put32(b, static_cast<uint32_t>(w >> 32));
    }
    put32(b, fnv1a(b));
    return b;
}

std::set<std::string> listing(const fs::path& dir) {
    std::set<std::string> s;
    for (const auto& e : fs::recursive_directory_iterator(dir))
        s.insert(fs::relative(e.path(), dir).string());
    return s;
}

// The prepared inputs, made once per test process in a temporary folder.
//   grey.png, grey_r.png     64x32 8-bit grey pair (right = left shifted by 3)
//   narrow.png               48x32 grey (size mismatch)
//   colour.png, colour_r.png 64x32 BGR pair; colour_grey*.png the same converted to grey
//   deep.png                 64x32 16-bit grey PNG
//   trunc.png                the first half of grey.png
//   empty.png                zero bytes
//   text.png                 a text file named .png
//   folder.png/              a folder named like an image (unreadable as an image)
//   scene_*/                 eval scene folders (left.png, right.png, gt.png): ok, trunc,
//                            empty, deep, size, folder
//   syntax.s, badaddr.s, pe.s, spin.s   programs for exec (see make())
//   badop.bin, halt.bin, cut.bin        program files: invalid opcode, valid, truncated
//   frames/                  3 numbered pairs (left_0000.png ...) of the grey pair
//   frames_bad/              the same with every left frame truncated: no usable frame
//   frames_mid/              5 pairs, left_0002.png truncated (a bad frame in the middle)
//   calib_*.yml              stereo calibrations for 64x32 frames (docs/calibration.md):
//                            ok, nokey (no D2), k1_2x3, nan (D2), rot (R not a rotation),
//                            t0 (zero baseline), size80 (made for 80x32), text (not YAML)
//   readonly/                mode 0555: {ro} when creating a file in it fails (else /sys
//                            or /proc, for root)
struct Inputs {
    fs::path dir;
    std::set<std::string> files;  // listing after creation: rows must not add to it

    Inputs() {
        dir = fs::temp_directory_path() / ("imapsim-reliability-" + std::to_string(::getpid()));
        fs::remove_all(dir);
        fs::create_directories(dir);
        make();
        files = listing(dir);
    }
    ~Inputs() {
        std::error_code ec;
        fs::permissions(dir / "readonly", fs::perms::owner_all, ec);
        fs::remove_all(dir);
    }

    // A folder in which no file can be created (see make()).
    fs::path read_only;

    void make() {
        cv::RNG rng(12345);
        cv::Mat grey(32, 64, CV_8UC1);
        rng.fill(grey, cv::RNG::UNIFORM, 0, 256);
        cv::Mat grey_r(32, 64, CV_8UC1);
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 64; ++x)
                grey_r.at<uint8_t>(y, x) = grey.at<uint8_t>(y, (x + 3) % 64);
        BOOST_REQUIRE(cv::imwrite((dir / "grey.png").string(), grey));
        BOOST_REQUIRE(cv::imwrite((dir / "grey_r.png").string(), grey_r));
        BOOST_REQUIRE(cv::imwrite((dir / "narrow.png").string(), grey.colRange(0, 48).clone()));

        cv::Mat colour(32, 64, CV_8UC3), colour_r(32, 64, CV_8UC3);
        rng.fill(colour, cv::RNG::UNIFORM, 0, 256);
        for (int y = 0; y < 32; ++y)
            for (int x = 0; x < 64; ++x)
                colour_r.at<cv::Vec3b>(y, x) = colour.at<cv::Vec3b>(y, (x + 3) % 64);
        BOOST_REQUIRE(cv::imwrite((dir / "colour.png").string(), colour));
        BOOST_REQUIRE(cv::imwrite((dir / "colour_r.png").string(), colour_r));
        cv::Mat g, gr;
        cv::cvtColor(colour, g, cv::COLOR_BGR2GRAY);
        cv::cvtColor(colour_r, gr, cv::COLOR_BGR2GRAY);
        BOOST_REQUIRE(cv::imwrite((dir / "colour_grey.png").string(), g));
        BOOST_REQUIRE(cv::imwrite((dir / "colour_grey_r.png").string(), gr));

        cv::Mat deep;
        grey.convertTo(deep, CV_16U, 257.0);
        BOOST_REQUIRE(cv::imwrite((dir / "deep.png").string(), deep));
        const std::string png = read_file(dir / "grey.png");
        write_file(dir / "trunc.png", png.substr(0, png.size() / 2));
        write_file(dir / "empty.png", "");
        write_file(dir / "text.png", "this is not an image\n");
        write_file(dir / "disp.pfm", std::string("Pf\n2 2\n-1\n") + std::string(16, '\0'));
        fs::create_directories(dir / "folder.png");

        // eval scenes: gt all zero (scale 1), every bad one differs in its left/right image
        const cv::Mat gt(32, 64, CV_8UC1, cv::Scalar(0));
        auto scene = [&](const std::string& name) {
            const fs::path d = dir / ("scene_" + name);
            fs::create_directories(d);
            fs::copy_file(dir / "grey.png", d / "left.png");
            fs::copy_file(dir / "grey_r.png", d / "right.png");
            BOOST_REQUIRE(cv::imwrite((d / "gt.png").string(), gt));
            return d;
        };
        scene("ok");
        fs::copy_file(dir / "trunc.png", scene("trunc") / "left.png",
                      fs::copy_options::overwrite_existing);
        fs::copy_file(dir / "empty.png", scene("empty") / "left.png",
                      fs::copy_options::overwrite_existing);
        fs::copy_file(dir / "deep.png", scene("deep") / "left.png",
                      fs::copy_options::overwrite_existing);
        fs::copy_file(dir / "narrow.png", scene("size") / "right.png",
                      fs::copy_options::overwrite_existing);
        const fs::path sf = scene("folder");
        fs::remove(sf / "left.png");
        fs::create_directories(sf / "left.png");

        // programs (docs/isa.md): the line / column of each problem is known from the text
        write_file(dir / "syntax.s", "nop\n  cadd c1, c1\n  halt\n");         // 2:3 missing operand
        write_file(dir / "badaddr.s", "cli c0, #5000\nld r0, [c0]\nhalt\n");  // pc 1, line 2
        // ldx at PE index + 1000: PE 24 is the first whose address (1024) is past 1023
        write_file(dir / "pe.s", "pidx r1, #0\nldx r0, [r1 + 1000]\nhalt\n");
        write_file(dir / "spin.s", "spin: jmp spin\n");
        // opcode 0xFF is not in the instruction table; 0x01 = halt
        write_file(dir / "badop.bin", program_file({0xFF, 0x01}));
        const std::string halt = program_file({0x01});
        write_file(dir / "halt.bin", halt);
        write_file(dir / "cut.bin", halt.substr(0, halt.size() - 6));

        // frame folders for stream
        auto frames = [&](const std::string& name, int n, auto&& left_of) {
            const fs::path d = dir / name;
            fs::create_directories(d);
            for (int k = 0; k < n; ++k) {
                const std::string num = "000" + std::to_string(k);
                fs::copy_file(dir / left_of(k), d / ("left_" + num + ".png"));
                fs::copy_file(dir / "grey_r.png", d / ("right_" + num + ".png"));
            }
        };
        frames("frames", 3, [](int) { return "grey.png"; });
        frames("frames_bad", 3, [](int) { return "trunc.png"; });
        frames("frames_mid", 5, [](int k) { return k == 2 ? "trunc.png" : "grey.png"; });

        // calibrations: one line per key, `over` replaces a key's text ("" drops it)
        auto calib = [&](const std::string& name, std::map<std::string, std::string> over) {
            std::map<std::string, std::string> m = {
                {"K1", "[[200, 0, 32], [0, 200, 16], [0, 0, 1]]"},
                {"D1", "[0, 0, 0, 0, 0]"},
                {"K2", "[[200, 0, 32], [0, 200, 16], [0, 0, 1]]"},
                {"D2", "[0, 0, 0, 0, 0]"},
                {"R", "[[1, 0, 0], [0, 1, 0], [0, 0, 1]]"},
                {"T", "[-0.1, 0, 0]"},
                {"image_width", "64"},
                {"image_height", "32"}};
            for (const auto& [k, t] : over) m[k] = t;
            std::string text = "%YAML:1.0\n";
            for (const auto& [k, t] : m)
                if (!t.empty()) text += k + ": " + t + "\n";
            write_file(dir / ("calib_" + name + ".yml"), text);
        };
        calib("ok", {});
        calib("nokey", {{"D2", ""}});
        calib("k1_2x3", {{"K1", "[[200, 0, 32], [0, 200, 16]]"}});
        calib("nan", {{"D2", "[0, 0, .nan, 0, 0]"}});
        calib("rot", {{"R", "[[1.1, 0, 0], [0, 1.1, 0], [0, 0, 1.1]]"}});
        calib("t0", {{"T", "[0, 0, 0]"}});
        calib("size80", {{"image_width", "80"}});
        write_file(dir / "calib_text.yml", "this is not a calibration file\n");

        // The first candidate where creating a file really fails: a folder
        // of mode 0555 stops an ordinary user, not root (nor a process with
        // CAP_DAC_OVERRIDE); sysfs and procfs refuse new files to everyone.
        const fs::path mine = dir / "readonly";
        fs::create_directories(mine);
        fs::permissions(mine, fs::perms::owner_read | fs::perms::owner_exec |
                                  fs::perms::group_read | fs::perms::group_exec |
                                  fs::perms::others_read | fs::perms::others_exec);
        for (const fs::path& c : {mine, fs::path("/sys"), fs::path("/proc")}) {
            std::string probe = (c / "probe-XXXXXX").string();
            const int fd = ::mkstemp(probe.data());
            if (fd >= 0) {
                ::close(fd);
                ::unlink(probe.c_str());
                continue;
            }
            read_only = c;
            break;
        }
        BOOST_REQUIRE_MESSAGE(!read_only.empty(),
                              "no folder found where creating a file fails ({ro} rows)");
    }
};

Inputs& inputs() {
    static Inputs in;
    return in;
}

std::string substitute(std::string s, const fs::path& o) {
    const std::pair<std::string, std::string> subs[] = {{"{in}", inputs().dir.string()},
                                                        {"{o}", o.string()},
                                                        {"{ro}", inputs().read_only.string()}};
    for (const auto& [key, val] : subs)
        for (size_t p = s.find(key); p != std::string::npos; p = s.find(key, p + val.size()))
            s.replace(p, key.size(), val);
    return s;
}

// Output files the command names directly in its output folder: "{o}/NAME"
// followed by a blank or the end (not "{o}/sub/NAME").
std::vector<std::string> named_outputs(const std::string& args) {
    std::vector<std::string> names;
    const std::string key = "{o}/";
    for (size_t p = args.find(key); p != std::string::npos; p = args.find(key, p + 1)) {
        const size_t b = p + key.size();
        const size_t e = std::min(args.find(' ', b), args.size());
        const std::string name = args.substr(b, e - b);
        if (!name.empty() && name.find('/') == std::string::npos) names.push_back(name);
    }
    return names;
}

// Runs one row in one mode; see the file comment.
void check_row_mode(const std::string& name, int code, const std::string& args,
                    const std::vector<std::string>& needles, bool pre_existing) {
    const fs::path o =
        inputs().dir.parent_path() / ("imapsim-reliability-" + std::to_string(::getpid()) + "-" +
                                      name + (pre_existing ? "-existing" : "-absent"));
    fs::remove_all(o);
    fs::create_directories(o);
    std::map<std::string, std::string> before;
    if (pre_existing)
        for (const std::string& f : named_outputs(args)) {
            const std::string content = "known content of " + f + " before the run\n";
            write_file(o / f, content);
            before[f] = content;
        }
    const std::string cmd = substitute(args, o);
    const clitest::Result r = clitest::run(cmd);
    BOOST_TEST_CONTEXT("imapsim " << cmd << (pre_existing ? " (outputs existed)" : "") << "\n"
                                  << r.out) {
        BOOST_TEST(r.code == code);
        // one error line, in the documented form
        size_t lines = 0;
        for (size_t p = r.out.find("imapsim: error: "); p != std::string::npos;
             p = r.out.find("imapsim: error: ", p + 1))
            ++lines;
        BOOST_TEST(lines == 1u, "one error line");
        if (code == kFault)
            BOOST_TEST(r.out.find("imapsim: error: machine fault: ") != std::string::npos);
        BOOST_TEST(r.out.find("internal error") == std::string::npos);
        BOOST_TEST(r.out.find("Sanitizer") == std::string::npos);
        BOOST_TEST(r.out.find("runtime error:") == std::string::npos);
        for (const std::string& n : needles)
            BOOST_TEST(r.out.find(n) != std::string::npos, "message names '" << n << "'");
        // nothing new in the output folder (no output, no temporary), old files unchanged
        std::set<std::string> want;
        for (const auto& [f, content] : before) want.insert(f);
        BOOST_TEST(listing(o) == want, "output folder holds only what was there before");
        for (const auto& [f, content] : before)
            BOOST_TEST(read_file(o / f) == content, f << " left byte-identical");
        BOOST_TEST(listing(inputs().dir) == inputs().files, "nothing written among the inputs");
    }
    fs::remove_all(o);
}

void check_row(const std::string& name, int code, const std::string& args,
               std::initializer_list<const char*> needles) {
    const std::vector<std::string> n(needles.begin(), needles.end());
    // Half of the rows (by a checksum of the name, so that a row always runs
    // the same way) pre-create their outputs; rows without outputs in {o}
    // check absence.
    const bool pre_existing = !named_outputs(args).empty() && (fnv1a(name) & 1) != 0;
    check_row_mode(name, code, args, n, pre_existing);
}

}  // namespace

#define ERROR_ROW(NAME, CODE, ARGS, ...)             \
    BOOST_AUTO_TEST_CASE(NAME) {                     \
        check_row(#NAME, CODE, ARGS, {__VA_ARGS__}); \
    }

// Common argument sets: a valid pair with its output, per subcommand.
#define PAIR "--left {in}/grey.png --right {in}/grey_r.png"
#define RUN_ARGS PAIR " --out {o}/map.png --report {o}/r.json"
#define RUN_IN "run --model core " PAIR " --D 8"         // outputs given by the row
#define RUN_ON(MODEL) "run --model " MODEL " " RUN_ARGS  // no --D: the default is 64
#define RUN RUN_ON("core") " --D 8"
#define GOLDEN_ARGS "golden " PAIR " --out {o}/map.png"
#define GOLDEN GOLDEN_ARGS " --D 8"
#define EVAL "eval --gt-scale 1 --json {o}/e.json"
#define EVAL_OK EVAL " --scene {in}/scene_ok"
#define EXEC "exec {in}/badaddr.s --out-left {o}/out.png --report {o}/r.json"
#define EXEC_L EXEC " --left {in}/grey.png"
#define LOGS " --json {o}/s.json --csv {o}/s.csv"
#define STREAM_IN "stream --frames {in}/frames" LOGS  // algorithm flags given by the row
#define STREAM STREAM_IN " --D 8"
#define CALIB(NAME) STREAM " --calib {in}/calib_" NAME ".yml"
#define SWEEP_IN "sweep --roi-size 64x32 -j 1" LOGS  // the swept axis given by the row
#define SWEEP SWEEP_IN " --D 8"

// ---- images ------------------------------------------------------------------------
BOOST_AUTO_TEST_SUITE(images)
ERROR_ROW(run_folder_as_image, kInput,
          "run --left {in}/folder.png --right {in}/grey_r.png --out {o}/map.png", "left image",
          "folder.png", "is a directory")
ERROR_ROW(golden_folder_as_image, kInput,
          "golden --left {in}/grey.png --right {in}/folder.png --D 8 --out {o}/map.png",
          "right image", "folder.png", "is a directory")
ERROR_ROW(eval_folder_as_image, kInput, EVAL " --D 8 --scene {in}/scene_folder", "left.png",
          "is a directory")
ERROR_ROW(run_text_file_as_image, kInput,
          "run --left {in}/text.png --right {in}/grey_r.png --out {o}/map.png", "left image",
          "text.png", "not an image")
ERROR_ROW(run_float_pfm_as_image, kInput,
          "run --left {in}/disp.pfm --right {in}/grey_r.png --out {o}/map.png", "left image",
          "disp.pfm", "PFM float image", "use PNG")
ERROR_ROW(golden_missing_image, kInput,
          "golden --left {in}/nosuch.png --right {in}/grey_r.png --out {o}/map.png", "nosuch.png",
          "cannot read")
ERROR_ROW(run_truncated_png, kInput,
          "run --left {in}/trunc.png --right {in}/grey_r.png --out {o}/map.png", "left image",
          "trunc.png", "corrupt or truncated PNG")
ERROR_ROW(golden_truncated_png, kInput,
          "golden --left {in}/grey.png --right {in}/trunc.png --out {o}/map.png", "right image",
          "trunc.png", "corrupt or truncated PNG")
ERROR_ROW(eval_truncated_png, kInput, EVAL " --D 8 --scene {in}/scene_trunc", "left.png",
          "corrupt or truncated PNG")
ERROR_ROW(run_empty_file, kInput,
          "run --left {in}/empty.png --right {in}/grey_r.png --out {o}/map.png", "empty.png",
          "empty file")
ERROR_ROW(golden_empty_file, kInput,
          "golden --left {in}/empty.png --right {in}/grey_r.png --out {o}/map.png", "empty.png",
          "empty file")
ERROR_ROW(eval_empty_file, kInput, EVAL " --D 8 --scene {in}/scene_empty", "left.png", "empty file")
ERROR_ROW(run_16bit_png, kInput,
          "run --left {in}/deep.png --right {in}/grey_r.png --out {o}/map.png", "deep.png",
          "16-bit", "8-bit")
ERROR_ROW(golden_16bit_png, kInput,
          "golden --left {in}/deep.png --right {in}/grey_r.png --out {o}/map.png", "deep.png",
          "16-bit", "8-bit")
ERROR_ROW(eval_16bit_png, kInput, EVAL " --D 8 --scene {in}/scene_deep", "left.png", "16-bit")
ERROR_ROW(exec_16bit_png, kInput, EXEC " --left {in}/deep.png", "deep.png", "16-bit")
ERROR_ROW(run_size_mismatch, kInput,
          "run --left {in}/grey.png --right {in}/narrow.png --out {o}/map.png", "differ in size",
          "64x32", "48x32", "narrow.png")
ERROR_ROW(golden_size_mismatch, kInput,
          "golden --left {in}/grey.png --right {in}/narrow.png --out {o}/map.png", "differ in size",
          "64x32", "48x32", "narrow.png")
ERROR_ROW(eval_size_mismatch, kInput, EVAL " --D 8 --scene {in}/scene_size", "right.png", "48x32",
          "64x32")
ERROR_ROW(exec_size_mismatch, kInput, EXEC " --left {in}/grey.png --right {in}/narrow.png",
          "differ in size", "64x32", "48x32")
ERROR_ROW(run_left_without_right, kInput, "run --left {in}/grey.png --out {o}/map.png",
          "--left and --right")
BOOST_AUTO_TEST_SUITE_END()

// ---- ROI and algorithm parameters -----------------------------------------------------
BOOST_AUTO_TEST_SUITE(parameters)
ERROR_ROW(run_roi_outside_x, kInput, RUN " --roi 40,0,32,32", "ROI", "40,0,32,32", "64x32")
ERROR_ROW(run_roi_outside_y, kInput, RUN " --roi 0,10,32,32", "ROI", "0,10,32,32", "64x32")
ERROR_ROW(golden_roi_outside, kInput, GOLDEN " --roi 0,0,65,32", "ROI", "0,0,65,32", "64x32")
ERROR_ROW(run_roi_malformed, kInput, RUN " --roi 1,2,3", "--roi", "x0,y0,w,h")
ERROR_ROW(eval_roi_refused, kInput, EVAL_OK " --D 8 --roi 0,0,8,8", "--roi", "whole image")
ERROR_ROW(run_D_zero, kInput, RUN_ON("core") " --D 0", "--D", "1..255")
ERROR_ROW(golden_D_zero, kInput, GOLDEN_ARGS " --D 0", "--D", "1..255")
ERROR_ROW(eval_D_zero, kInput, EVAL_OK " --D 0", "--D", "1..255")
ERROR_ROW(run_D_above_width, kInput, RUN_ON("core") " --D 65", "D = 65", "1..64")
ERROR_ROW(golden_D_above_width, kInput, GOLDEN_ARGS " --D 65", "D = 65", "1..64")
ERROR_ROW(eval_D_above_width, kInput, EVAL_OK " --D 65", "D = 65", "1..64")
ERROR_ROW(run_D_above_255, kInput, RUN_ON("core") " --D 256", "--D", "256", "1..255")
ERROR_ROW(golden_D_above_255, kInput, GOLDEN_ARGS " --D 300", "--D", "300", "1..255")
ERROR_ROW(eval_D_above_255, kInput, EVAL_OK " --D 256", "--D", "256", "1..255")
ERROR_ROW(run_Wo_below_Wd, kInput, RUN " --Wo 5 --Wd 10", "Wo = 5", "Wd = 10")
ERROR_ROW(golden_Wo_below_Wd, kInput, GOLDEN " --Wo 5 --Wd 10", "Wo = 5", "Wd = 10")
ERROR_ROW(eval_Wo_below_Wd, kInput, EVAL_OK " --D 8 --Wo 5 --Wd 10", "Wo = 5", "Wd = 10")
ERROR_ROW(eval_perturb_gain_zero, kInput, EVAL_OK " --D 8 --perturb gain=0", "--perturb",
          "'gain=0'", "> 0 and <= 16")
ERROR_ROW(eval_perturb_negative_noise, kInput, EVAL_OK " --D 8 --perturb noise=-1", "--perturb",
          "'noise=-1'", "0..64")
ERROR_ROW(eval_perturb_unknown_key, kInput, EVAL_OK " --D 8 --perturb blur=3", "--perturb",
          "'blur'", "noise-image")
ERROR_ROW(run_negative_km, kInput, RUN " --km -1", "--km", "-1", "0..1000000")
ERROR_ROW(golden_negative_D, kInput, GOLDEN_ARGS " --D -3", "--D", "-3", "1..255")
ERROR_ROW(run_non_numeric_D, kInput, RUN_ON("core") " --D abc", "--D", "abc", "1..255")
ERROR_ROW(golden_non_numeric_gb, kInput, GOLDEN " --gb 12x", "--gb", "12x", "0..255")
ERROR_ROW(run_bad_mode, kInput, RUN " --mode triple", "--mode", "triple", "single, bidir or joint")
BOOST_AUTO_TEST_SUITE_END()

// ---- machine configuration and memory fit ---------------------------------------------
BOOST_AUTO_TEST_SUITE(machine)
ERROR_ROW(run_pes_0, kInput, RUN " --pes 0", "--pes", "2..65536")
ERROR_ROW(run_pes_1, kInput, RUN " --pes 1", "--pes", "2..65536")
ERROR_ROW(run_pes_negative, kInput, RUN " --pes -4", "--pes", "-4", "2..65536")
ERROR_ROW(run_pes_non_numeric, kInput, RUN " --pes abc", "--pes", "abc", "integer")
ERROR_ROW(exec_pes_1, kInput, EXEC_L " --pes 1", "--pes", "2..65536")
ERROR_ROW(run_clock_0, kInput, RUN " --clock-mhz 0", "--clock-mhz", "> 0")
ERROR_ROW(run_clock_negative, kInput, RUN " --clock-mhz -5", "--clock-mhz", "-5", "> 0")
ERROR_ROW(exec_clock_0, kInput, EXEC_L " --clock-mhz 0", "--clock-mhz", "> 0")
ERROR_ROW(run_mem_bytes_zero, kInput, RUN " --mem-bytes 0", "--mem-bytes", "1..1048576")
// D = 8 on a 64-wide ROI needs more than 100 bytes per PE (the exact figure is the plan's)
ERROR_ROW(run_mem_too_small, kInput, RUN " --mem-bytes 100", "does not fit", "needs",
          "bytes of local memory per PE", "have 100", "mem_bytes")
// D = 64 with 400 bytes per PE spills pointer columns to the external memory
ERROR_ROW(run_ext_too_small, kInput, RUN_ON("core") " --mem-bytes 400 --ext-bytes 0",
          "does not fit", "external memory", "ext_bytes")
ERROR_ROW(run_set_unknown, kInput, RUN " --set nosuch=3", "nosuch")
ERROR_ROW(run_set_malformed, kInput, RUN " --set ring_hop", "--set", "NAME=VALUE")
ERROR_ROW(run_watchdog_zero, kInput, RUN " --set watchdog_cycles=0", "watchdog_cycles", "1..")
ERROR_ROW(run_unknown_model, kInput, RUN_ON("nosuch"), "--model", "nosuch")
ERROR_ROW(exec_rtl_model, kInput, EXEC_L " --model rtl", "--model", "rtl", "core")
BOOST_AUTO_TEST_SUITE_END()

// ---- firmware: assembly, loading, parameters of exec -----------------------------------
BOOST_AUTO_TEST_SUITE(firmware)
ERROR_ROW(exec_syntax_error, kInput, "exec {in}/syntax.s --report {o}/r.json",
          "syntax.s:2:3:", "cadd", "does not assemble")
ERROR_ROW(exec_missing_source, kInput, "exec {in}/nosuch.s --report {o}/r.json", "nosuch.s")
ERROR_ROW(exec_unknown_opcode_core, kInput, "exec {in}/badop.bin --model core --report {o}/r.json",
          "badop.bin", "pc 0", "unknown opcode 0xff")
ERROR_ROW(exec_unknown_opcode_tlm, kInput, "exec {in}/badop.bin --model tlm --report {o}/r.json",
          "badop.bin", "pc 0", "unknown opcode 0xff")
ERROR_ROW(exec_truncated_program, kInput, "exec {in}/cut.bin --report {o}/r.json", "cut.bin",
          "bad program file")
ERROR_ROW(exec_image_as_program, kInput, "exec {in}/grey.png --report {o}/r.json", "grey.png",
          "IMAPFW01")
ERROR_ROW(exec_define_on_binary, kInput, "exec {in}/halt.bin -D N=3 --report {o}/r.json", "-D",
          "halt.bin")
ERROR_ROW(exec_param_index, kInput, "exec {in}/halt.bin --param 256=1 --report {o}/r.json",
          "--param", "256", "0..255")
ERROR_ROW(exec_param_value, kInput, "exec {in}/halt.bin --param 3=x --report {o}/r.json", "--param",
          "x", "integer")
ERROR_ROW(asm_syntax_error, kInput, "asm {in}/syntax.s -o {o}/p.bin --listing {o}/p.txt",
          "syntax.s:2:3:", "does not assemble", "nothing written")
ERROR_ROW(asm_listing_missing_folder, kInput,
          "asm {in}/badaddr.s -o {o}/p.bin --listing {o}/nosuch/p.txt", "--listing",
          "does not exist")
ERROR_ROW(disasm_truncated_program, kInput, "disasm {in}/cut.bin -o {o}/p.s", "cut.bin",
          "bad program file")
ERROR_ROW(disasm_out_missing_folder, kInput, "disasm {in}/halt.bin -o {o}/nosuch/p.s", "--out",
          "does not exist")
ERROR_ROW(exec_out_without_input, kInput, "exec {in}/halt.bin --out-left {o}/out.png", "--out-left",
          "--left")
BOOST_AUTO_TEST_SUITE_END()

// ---- run-time faults and the watchdog (exit 3) -----------------------------------------
BOOST_AUTO_TEST_SUITE(faults)
ERROR_ROW(exec_bad_address_core, kFault, EXEC_L " --model core", "pc 1", "badaddr.s:2",
          "address 5000", "0..1023")
ERROR_ROW(exec_fault_names_pe, kFault, "exec {in}/pe.s --model core --report {o}/r.json", "pc 1",
          "pe.s:2", "PE 24", "address 1024")
ERROR_ROW(exec_watchdog_core, kFault,
          "exec {in}/spin.s --model core --set watchdog_cycles=100000 --report {o}/r.json",
          "watchdog", "watchdog_cycles = 100000", "spin.s:1")
ERROR_ROW(run_watchdog_core, kFault, RUN " --set watchdog_cycles=1000", "watchdog",
          "watchdog_cycles = 1000", "relayout.inc")
ERROR_ROW(run_watchdog_rtl, kFault, RUN_ON("rtl") " --set watchdog_cycles=1000", "watchdog",
          "watchdog_cycles = 1000")
BOOST_AUTO_TEST_SUITE_END()

// A fault on the TLM model: the exception is thrown on a SystemC coroutine
// stack and caught after sc_start() returns; its own suite, so that a
// sanitizer report here (tlm/sanitizer.hpp explains the one the model
// prevents) shows up apart from the other faults.
BOOST_AUTO_TEST_SUITE(faults_tlm)
ERROR_ROW(exec_bad_address_tlm, kFault, EXEC_L " --model tlm", "pc 1", "badaddr.s:2",
          "address 5000", "0..1023")
ERROR_ROW(exec_watchdog_tlm, kFault,
          "exec {in}/spin.s --model tlm --set watchdog_cycles=100000 --report {o}/r.json",
          "watchdog", "watchdog_cycles = 100000", "spin.s:1")
ERROR_ROW(run_watchdog_tlm, kFault, RUN_ON("tlm") " --set watchdog_cycles=1000", "watchdog",
          "watchdog_cycles = 1000")
BOOST_AUTO_TEST_SUITE_END()

// ---- output files and waves ------------------------------------------------------------
BOOST_AUTO_TEST_SUITE(outputs)
ERROR_ROW(run_out_missing_folder, kInput,
          RUN_IN " --vcd {o}/w.vcd --report {o}/r.json --out {o}/nosuch/map.png", "--out", "nosuch",
          "does not exist")
ERROR_ROW(run_out_parent_is_file, kInput, RUN_IN " --report {o}/r.json --out {in}/grey.png/map.png",
          "--out", "grey.png", "not a folder")
ERROR_ROW(run_out_is_folder, kInput, RUN_IN " --report {o}/r.json --out {in}/folder.png", "--out",
          "is a folder")
ERROR_ROW(run_out_bad_type, kInput, RUN_IN " --report {o}/r.json --out {o}/map.txt", "--out",
          "map.txt", ".png")
// A folder where files cannot be created (permissions, read-only file
// system) is found before the work too, not when the result is written.
ERROR_ROW(run_out_folder_not_writable, kInput, RUN_IN " --report {o}/r.json --out {ro}/map.png",
          "--out", "map.png", "cannot create files in folder")
ERROR_ROW(run_vcd_folder_not_writable, kInput, RUN " --vcd {ro}/w.vcd", "--vcd",
          "cannot create files in folder")
ERROR_ROW(stream_out_dir_not_writable, kInput, STREAM " --out-dir {ro}/out", "--out-dir",
          "cannot create files in folder")
ERROR_ROW(sweep_csv_folder_not_writable, kInput,
          "sweep --roi-size 64x32 --D 8 --json {o}/s.json --csv {ro}/s.csv", "--csv",
          "cannot create files in folder")
ERROR_ROW(run_report_missing_folder, kInput, RUN_IN " --out {o}/map.png --report {o}/nosuch/r.json",
          "--report", "does not exist")
ERROR_ROW(golden_out_missing_folder, kInput, "golden " PAIR " --D 8 --out {o}/nosuch/map.png",
          "--out", "does not exist")
ERROR_ROW(golden_out_parent_is_file, kInput, "golden " PAIR " --D 8 --out {in}/grey.png/map.png",
          "--out", "not a folder")
ERROR_ROW(eval_json_missing_folder, kInput,
          "eval --gt-scale 1 --scene {in}/scene_ok --D 8 --json {o}/nosuch/e.json", "--json",
          "does not exist")
ERROR_ROW(exec_out_missing_folder, kInput,
          "exec {in}/halt.bin --left {in}/grey.png --out-left {o}/nosuch/out.png "
          "--report {o}/r.json",
          "--out-left", "does not exist")
ERROR_ROW(exec_report_parent_is_file, kInput, "exec {in}/halt.bin --report {in}/halt.bin/r.json",
          "--report", "not a folder")
ERROR_ROW(bench_json_missing_folder, kInput, "bench --json {o}/nosuch/b.json", "--json",
          "does not exist")
ERROR_ROW(run_vcd_missing_folder_core, kInput, RUN " --vcd {o}/nosuch/w.vcd", "--vcd",
          "does not exist")
ERROR_ROW(run_vcd_missing_folder_tlm, kInput, RUN_ON("tlm") " --vcd {o}/nosuch/w.vcd", "--vcd",
          "does not exist")
ERROR_ROW(run_vcd_parent_is_file_rtl, kInput,
          RUN_ON("rtl") " --vcd {in}/grey.png/w.vcd --trace-pes 0:1", "--vcd", "not a folder")
ERROR_ROW(run_vcd_is_folder, kInput, RUN " --vcd {in}/folder.png", "--vcd", "is a folder")
// Issue 32 item 3: an .fst name on a model that writes VCD is refused
// before the run (it used to get VCD text under the .fst name).
ERROR_ROW(run_fst_on_tlm, kInput, RUN_ON("tlm") " --vcd {o}/w.fst", "--vcd", "w.fst",
          "writes VCD, not FST", ".vcd")
ERROR_ROW(run_fst_on_core, kInput, RUN " --vcd {o}/w.fst", "--vcd", "w.fst", "writes VCD")
ERROR_ROW(run_vcd_on_lockstep, kInput, RUN_ON("lockstep") " --vcd {o}/w.vcd", "--vcd", "lockstep")
ERROR_ROW(run_vcd_bad_trace_pes, kInput, RUN " --vcd {o}/w.vcd --trace-pes 9:2", "--trace-pes")
BOOST_AUTO_TEST_SUITE_END()

// ---- calibration files (stream --calib; docs/calibration.md) ----------------------------
BOOST_AUTO_TEST_SUITE(calibration)
ERROR_ROW(calib_missing_file, kInput, CALIB("nosuch"), "calibration", "calib_nosuch.yml",
          "cannot read")
ERROR_ROW(calib_is_folder, kInput, STREAM " --calib {in}/folder.png", "calibration", "folder.png",
          "is a directory")
ERROR_ROW(calib_missing_key, kInput, CALIB("nokey"), "calib_nokey.yml", "missing key 'D2'")
ERROR_ROW(calib_wrong_matrix_size, kInput, CALIB("k1_2x3"), "calib_k1_2x3.yml", "key 'K1'",
          "expected a 3x3 matrix, got 2x3")
ERROR_ROW(calib_nan, kInput, CALIB("nan"), "calib_nan.yml", "key 'D2'", "NaN")
ERROR_ROW(calib_not_a_rotation, kInput, CALIB("rot"), "key 'R'", "not a rotation matrix")
ERROR_ROW(calib_zero_baseline, kInput, CALIB("t0"), "key 'T'", "zero baseline")
ERROR_ROW(calib_not_yaml, kInput, CALIB("text"), "calib_text.yml", "not a calibration file")
// A calibration made for other frames: every frame is bad, so nothing runs.
ERROR_ROW(calib_other_image_size, kInput, CALIB("size80"), "no usable frame",
          "left frame size 64x32", "calibration's image size 80x32")
BOOST_AUTO_TEST_SUITE_END()

// ---- stream: sources, camera timing, outputs -------------------------------------------
BOOST_AUTO_TEST_SUITE(stream)
ERROR_ROW(stream_no_source, kInput, "stream --D 8" LOGS, "exactly one source")
ERROR_ROW(stream_two_sources, kInput, STREAM " --synthetic 3", "exactly one source")
ERROR_ROW(stream_left_video_alone, kInput, "stream --left-video {in}/l.avi --D 8" LOGS,
          "--left-video and --right-video")
ERROR_ROW(stream_video_missing, kInput,
          "stream --left-video {in}/nosuch.avi --right-video {in}/nosuch_r.avi --D 8" LOGS,
          "left video", "nosuch.avi", "no such file")
ERROR_ROW(stream_frames_missing_folder, kInput, "stream --frames {in}/nosuch --D 8" LOGS,
          "frame folder", "nosuch", "not a folder")
ERROR_ROW(stream_frames_no_pairs, kInput, "stream --frames {in}/folder.png --D 8" LOGS,
          "folder.png", "no frame pairs", "left_0000.png")
ERROR_ROW(stream_no_usable_frame, kInput, "stream --frames {in}/frames_bad --D 8" LOGS,
          "no usable frame", "left_0000.png", "corrupt or truncated PNG")
ERROR_ROW(stream_synthetic_zero, kInput, "stream --synthetic 0 --D 8" LOGS, "--synthetic",
          "1..1000000")
ERROR_ROW(stream_max_frames_zero, kInput, STREAM " --max-frames 0", "--max-frames", "1..")
ERROR_ROW(stream_fps_zero, kInput, STREAM " --fps 0", "--fps", "> 0")
ERROR_ROW(stream_fps_non_numeric, kInput, STREAM " --fps abc", "--fps", "abc")
ERROR_ROW(stream_deadline_negative, kInput, STREAM " --deadline-ms -1", "--deadline-ms", "-1",
          "> 0")
ERROR_ROW(stream_line_longer_than_frame, kInput, STREAM " --line-us 5000", "5000 us",
          "longer than the frame period", "--line-us")
ERROR_ROW(stream_D_above_255, kInput, STREAM_IN " --D 300", "--D", "300", "1..255")
ERROR_ROW(stream_D_above_width, kInput, STREAM_IN " --D 65", "D = 65", "1..64")
ERROR_ROW(stream_roi_outside, kInput, STREAM " --roi 0,0,80,32", "ROI", "0,0,80,32", "64x32")
ERROR_ROW(stream_pes_1, kInput, STREAM " --pes 1", "--pes", "2..65536")
ERROR_ROW(stream_mem_too_small, kInput, STREAM " --mem-bytes 64", "does not fit", "have 64",
          "mem_bytes")
ERROR_ROW(stream_video_not_avi, kInput, STREAM " --video {o}/v.png", "--video", "v.png", ".avi")
ERROR_ROW(stream_json_missing_folder, kInput,
          "stream --frames {in}/frames --D 8 --json {o}/nosuch/s.json", "nosuch/s.json",
          "does not exist")
// One rule for every output flag (issue 32 item 9): --out-dir, like a
// file, is created only in a folder that exists.
ERROR_ROW(stream_out_dir_missing_parent, kInput, STREAM " --out-dir {o}/nosuch/out", "--out-dir",
          "folder", "nosuch", "does not exist")
ERROR_ROW(synth_out_dir_missing_parent, kInput,
          "synth --seed 1 --size 64x32 --out-dir {o}/nosuch/s", "--out-dir", "nosuch",
          "does not exist")
ERROR_ROW(stream_out_dir_parent_is_file, kInput, STREAM " --out-dir {in}/grey.png/out", "--out-dir",
          "grey.png", "cannot create")
BOOST_AUTO_TEST_SUITE_END()

// ---- sweep and table1: axes, ranges, outputs -------------------------------------------
BOOST_AUTO_TEST_SUITE(sweep)
ERROR_ROW(sweep_pes_non_numeric, kInput, SWEEP " --pes abc", "--pes", "'abc' is not an integer")
ERROR_ROW(sweep_range_reversed, kInput, SWEEP " --pes 64..8", "--pes", "64..8", "A > B")
ERROR_ROW(sweep_range_step_zero, kInput, SWEEP " --pes 8..64:0", "--pes", "step", ">= 1")
ERROR_ROW(sweep_pes_1, kInput, SWEEP " --pes 1,2", "--pes", "2..65536")
ERROR_ROW(sweep_clock_0, kInput, SWEEP " --clock-mhz 0", "--clock-mhz", "> 0")
ERROR_ROW(sweep_clock_negative_range, kInput, SWEEP " --clock-mhz -3..5", "--clock-mhz", "-3")
ERROR_ROW(sweep_D_zero, kInput, SWEEP_IN " --D 0,8", "--D", "1..255")
ERROR_ROW(sweep_mem_bytes_zero, kInput, SWEEP " --mem-bytes 0", "--mem-bytes", "1..1048576")
ERROR_ROW(sweep_jobs_zero, kInput, "sweep --roi-size 64x32 --D 8 -j 0" LOGS, "-j", "1..1024")
ERROR_ROW(sweep_roi_size_malformed, kInput, "sweep --roi-size 64 --D 8" LOGS, "--roi-size", "WxH")
ERROR_ROW(sweep_mode_unknown, kInput, SWEEP " --mode triple", "--mode", "triple")
ERROR_ROW(sweep_set_unknown, kInput, SWEEP " --set nosuch=1", "nosuch")
ERROR_ROW(sweep_csv_missing_folder, kInput, "sweep --roi-size 64x32 --D 8 --csv {o}/nosuch/s.csv",
          "--csv", "does not exist")
ERROR_ROW(table1_json_missing_folder, kInput, "table1 --json {o}/nosuch/t.json", "--json",
          "does not exist")
BOOST_AUTO_TEST_SUITE_END()

// ---- regress --------------------------------------------------------------------------
BOOST_AUTO_TEST_SUITE(regress)
ERROR_ROW(regress_junit_missing_folder, kInput,
          "regress --junit {o}/nosuch/r.xml --json {o}/r.json", "--junit", "does not exist")
ERROR_ROW(regress_unknown_suite, kInput, "regress --suite nosuch --junit {o}/r.xml", "--suite",
          "nosuch")
ERROR_ROW(regress_unknown_model, kInput, "regress --models nosuch --junit {o}/r.xml", "--models",
          "nosuch")
ERROR_ROW(regress_missing_cases, kInput, "regress --cases {in}/nosuch.json --junit {o}/r.xml",
          "nosuch.json")
BOOST_AUTO_TEST_SUITE_END()

// ---- colour input: accepted and converted to grey ---------------------------------------
BOOST_AUTO_TEST_SUITE(images)
// Colour images are not an error: the loader converts them to grey with
// OpenCV's BGR->grey weights (docs/errors.md). The map of a colour pair must
// equal the map of the same pair converted to grey by the test itself.
BOOST_AUTO_TEST_CASE(colour_input_is_converted_to_grey) {
    const fs::path o = inputs().dir.parent_path() /
                       ("imapsim-reliability-" + std::to_string(::getpid()) + "-colour");
    fs::remove_all(o);
    fs::create_directories(o);
    const std::string in = inputs().dir.string() + "/";
    const std::pair<const char*, const char*> cmds[] = {{"run --model core --D 8", "run"},
                                                        {"golden --D 8", "golden"}};
    for (const auto& [cmd, tag] : cmds) {
        const fs::path from_colour = o / (std::string(tag) + "-colour.png");
        const fs::path from_grey = o / (std::string(tag) + "-grey.png");
        const clitest::Result a =
            clitest::run(std::string(cmd) + " --left " + in + "colour.png --right " + in +
                         "colour_r.png --out " + from_colour.string());
        const clitest::Result b =
            clitest::run(std::string(cmd) + " --left " + in + "colour_grey.png --right " + in +
                         "colour_grey_r.png --out " + from_grey.string());
        BOOST_TEST_CONTEXT(tag << "\n" << a.out << "\n" << b.out) {
            BOOST_TEST(a.code == 0);
            BOOST_TEST(b.code == 0);
            const cv::Mat ma = cv::imread(from_colour.string(), cv::IMREAD_UNCHANGED);
            const cv::Mat mb = cv::imread(from_grey.string(), cv::IMREAD_UNCHANGED);
            BOOST_REQUIRE(!ma.empty());
            BOOST_REQUIRE(!mb.empty());
            BOOST_TEST(ma.type() == CV_8UC1);
            BOOST_TEST(ma.size() == mb.size());
            BOOST_TEST(cv::countNonZero(ma != mb) == 0);
        }
    }
    fs::remove_all(o);
}

BOOST_AUTO_TEST_SUITE_END()

// A corrupt frame in the middle of a stream is not an input error: the frame
// is recorded as bad (what and which file), the others run and are
// bit-exact, and the stream ends with exit 5 (docs/errors.md). The logs and
// the maps of the good frames are complete.
BOOST_AUTO_TEST_SUITE(stream)
BOOST_AUTO_TEST_CASE(stream_corrupt_frame_in_the_middle) {
    const fs::path o = inputs().dir.parent_path() /
                       ("imapsim-reliability-" + std::to_string(::getpid()) + "-stream-mid");
    fs::remove_all(o);
    const clitest::Result r =
        clitest::run(substitute("stream --frames {in}/frames_mid --D 8 --out-dir {o}", o));
    BOOST_TEST_CONTEXT(r.out) {
        BOOST_TEST(r.code == 5);
        BOOST_TEST(r.out.find("frame 2 left_0002.png: BAD FRAME") != std::string::npos);
        BOOST_TEST(r.out.find("corrupt or truncated PNG") != std::string::npos);
        BOOST_TEST(r.out.find("imapsim: error:") == std::string::npos, "not an input error");
        BOOST_TEST(listing(o) ==
                   (std::set<std::string>{"disp_0000.png", "disp_0001.png", "disp_0003.png",
                                          "disp_0004.png", "stream.csv", "stream.json"}));
        const std::string json = read_file(o / "stream.json");
        BOOST_TEST(json.find("\"state\": \"complete\"") != std::string::npos);
        BOOST_TEST(json.find("\"status\": \"bad-frame\"") != std::string::npos);
        // the CSV: a header and one row per frame; only frame 2 is bad
        std::istringstream csv(read_file(o / "stream.csv"));
        std::vector<std::string> rows;
        for (std::string l; std::getline(csv, l);) rows.push_back(l);
        BOOST_REQUIRE_EQUAL(rows.size(), 6u);
        for (size_t k = 1; k < rows.size(); ++k) {
            const bool bad = rows[k].find("bad-frame") != std::string::npos;
            BOOST_TEST(bad == (k == 3), "CSV row " << k << ": " << rows[k]);
            if (!bad) BOOST_TEST(rows[k].find(",ok,") != std::string::npos, rows[k]);
        }
    }
    BOOST_TEST(listing(inputs().dir) == inputs().files, "nothing written among the inputs");
    fs::remove_all(o);
}
BOOST_AUTO_TEST_SUITE_END()

// A machine fault keeps the waves: the VCD (and its .gtkw) up to the fault is
// the debugging aid and is written complete; the map and the report are not
// (docs/errors.md, docs/waves.md).
BOOST_AUTO_TEST_SUITE(faults)
BOOST_AUTO_TEST_CASE(fault_keeps_only_the_waves) {
    const fs::path o = inputs().dir.parent_path() /
                       ("imapsim-reliability-" + std::to_string(::getpid()) + "-fault-waves");
    for (const char* model : {"core", "rtl"}) {
        fs::remove_all(o);
        fs::create_directories(o);
        const clitest::Result r = clitest::run(
            substitute(std::string("run --model ") + model +
                           " " PAIR " --D 8 --pes 8 --set watchdog_cycles=1000 --out {o}/map.png "
                           "--report {o}/r.json --vcd {o}/w.vcd --trace-pes 0:1",
                       o));
        BOOST_TEST_CONTEXT(model << "\n" << r.out) {
            BOOST_TEST(r.code == kFault);
            BOOST_TEST(r.out.find("watchdog") != std::string::npos);
            BOOST_TEST(listing(o) == (std::set<std::string>{"w.gtkw", "w.vcd"}));
            const std::string vcd = read_file(o / "w.vcd");
            BOOST_TEST(vcd.find("$enddefinitions") != std::string::npos);
        }
    }
    fs::remove_all(o);
}
BOOST_AUTO_TEST_SUITE_END()
