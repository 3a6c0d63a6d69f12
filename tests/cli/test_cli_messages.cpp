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

}  // namespace

BOOST_AUTO_TEST_CASE(misspelt_commands_and_options_are_named_with_a_suggestion) {
    const Result c = run("swep --pes 8");
    BOOST_TEST_INFO(c.out);
    BOOST_TEST(c.code == 2);
    BOOST_TEST(has(c, "imapsim: error: unknown command 'swep' (did you mean sweep?)"));
    const Result o = run("run --out-colour x.png");
    BOOST_TEST_INFO(o.out);
    BOOST_TEST(o.code == 2);
    BOOST_TEST(has(o, "unknown option --out-colour (did you mean --out-color?) for imapsim run"));
    // no subcommand: the options are run's
    const Result n = run("--sizee 64x32");
    BOOST_TEST_INFO(n.out);
    BOOST_TEST(n.code == 2);
    BOOST_TEST(has(n, "unknown option --sizee (did you mean --size?)"));
    // nothing close: no suggestion, still the name
    const Result f = run("sweep --frobnicate 3");
    BOOST_TEST_INFO(f.out);
    BOOST_TEST(f.code == 2);
    BOOST_TEST(has(f, "unknown option --frobnicate for imapsim sweep"));
    BOOST_TEST(!has(f, "did you mean"));
    const Result z = run("zzzz");
    BOOST_TEST(z.code == 2);
    BOOST_TEST(has(z, "unknown command 'zzzz'; commands: run, golden"), z.out);
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
    const Result d = run("run --model core --size 32x64 --D 40");
    BOOST_TEST_INFO(d.out);
    BOOST_TEST(d.code == 2);
    BOOST_TEST(has(d, "with N = 32 the ROI width"));
    const Result m = run("run --model core --left /nonexistent/l.png --right /nonexistent/r.png");
    BOOST_TEST_INFO(m.out);
    BOOST_TEST(m.code == 2);
    BOOST_TEST(has(m, "left image '/nonexistent/l.png': cannot read (no such file)"));
}

BOOST_AUTO_TEST_CASE(help_says_what_no_command_does_and_the_exit_codes) {
    const Result h = run("--help");
    BOOST_TEST_INFO(h.out);
    BOOST_TEST(h.code == 0);
    BOOST_TEST(has(h, "With no command, imapsim runs 'imapsim run'"));
    BOOST_TEST(has(h, "Exit codes: 0 success; 1 "));
    BOOST_TEST(has(h, "130 interrupted"));
}
