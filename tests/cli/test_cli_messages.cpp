// Messages a new user meets (issue 32, items 12 to 16): misspelt commands
// and options get a suggestion, a data folder given as a scene says so,
// limits name what they depend on, and --help says what no command does.
#define BOOST_TEST_MODULE cli_messages
#include <boost/test/unit_test.hpp>
#include <string>

#include "cli_test_util.hpp"

namespace {

using clitest::Result;
using clitest::run;

bool has(const Result& r, const std::string& s) {
    return r.out.find(s) != std::string::npos;
}

// Runs `args`, which must fail with exit 2 and print `needle`.
Result expect_input_error(const std::string& args, const std::string& needle) {
    const Result r = run(args);
    BOOST_TEST_CONTEXT(args << "\n" << r.out) {
        BOOST_TEST(r.code == 2);
        BOOST_TEST(has(r, needle));
    }
    return r;
}

}  // namespace

BOOST_AUTO_TEST_CASE(misspelt_commands_and_options_are_named_with_a_suggestion) {
    expect_input_error("swep --pes 8",
                       "imapsim: error: unknown command 'swep' (did you mean sweep?)");
    expect_input_error("run --out-colour x.png",
                       "unknown option --out-colour (did you mean --out-color?) for imapsim run");
    // no subcommand: the options are run's
    expect_input_error("--sizee 64x32", "unknown option --sizee (did you mean --size?)");
    // nothing close: no suggestion, still the name
    const Result f =
        expect_input_error("sweep --frobnicate 3", "unknown option --frobnicate for imapsim sweep");
    BOOST_TEST(!has(f, "did you mean"));
    expect_input_error("zzzz", "unknown command 'zzzz'; commands: run, golden");
}

BOOST_AUTO_TEST_CASE(a_data_folder_given_as_a_scene_says_so) {
    const std::string data = std::string(IMAP_SHARED_DATA) + "/middlebury";
    for (const char* cmd : {"eval --scene ", "run --model core --scene "}) {
        const Result r = run(cmd + data);
        BOOST_TEST_INFO(r.out);
        BOOST_TEST(r.code == 2);
        BOOST_TEST(has(r, "not a scene folder (no left.png)"));
        BOOST_TEST(has(r, "scene folder(s) (cones, teddy, tsukuba, venus)"));
        BOOST_TEST(has(r, "eval --all " + data));
        BOOST_TEST(!has(r, "--gt-scale"));
    }
}

BOOST_AUTO_TEST_CASE(eval_help_shows_the_frame_it_accepts) {
    const Result h = run("eval --help");
    BOOST_TEST(h.code == 0);
    BOOST_TEST(has(h, "left only (scenes are scored in the left frame) [default: left]"), h.out);
    BOOST_TEST(!has(h, "[default: cyc]"), h.out);
}

BOOST_AUTO_TEST_CASE(limits_name_what_they_depend_on) {
    expect_input_error("run --model core --size 32x64 --D 40", "with N = 32 the ROI width");
    expect_input_error("run --model core --left /nonexistent/l.png --right /nonexistent/r.png",
                       "left image '/nonexistent/l.png': cannot read (no such file)");
}

// Issue 30, item 4: the census over video segments refuses only a last
// segment narrower than its radius, and says which widths run.
BOOST_AUTO_TEST_CASE(a_census_roi_with_a_narrow_last_segment_names_it) {
    expect_input_error("run --model core --kc 4 --mode bidir --size 33x12 --D 8 --pes 32",
                       "imapsim: error: firmware: --kc 4 (census) over 2 video segments of 32 "
                       "pixels needs the last one at least 2 pixels wide (the census radius): the "
                       "ROI is 33 wide, the last segment 1; use a ROI width of 32 or at least 34 "
                       "(--roi), or other --pes\n");
    const Result r = run("run --model core --kc 4 --mode bidir --size 34x12 --D 8 --pes 32");
    BOOST_TEST(r.code == 0, r.out);
    BOOST_TEST(has(r, "bit-exact vs golden: yes"), r.out);
}

BOOST_AUTO_TEST_CASE(help_says_what_no_command_does_and_the_exit_codes) {
    const Result h = run("--help");
    BOOST_TEST_INFO(h.out);
    BOOST_TEST(h.code == 0);
    BOOST_TEST(has(h, "With no command, imapsim runs 'imapsim run'"));
    BOOST_TEST(has(h, "Exit codes: 0 success; 1 "));
    BOOST_TEST(has(h, "130 interrupted"));
}
