// Issue 32 item 11: `cmake --install` gives an imapsim that needs no source
// tree: the firmware is compiled in (a run from another folder assembles it,
// and its messages name firmware/asm/FILE, not the source tree's path), and
// the regression table is the installed one (share/imapsim/regress).
#define BOOST_TEST_MODULE cli_install
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli_test_util.hpp"

namespace fs = std::filesystem;

BOOST_AUTO_TEST_CASE(installed_binary_runs_without_the_source_tree) {
    const fs::path prefix =
        fs::temp_directory_path() / ("imapsim-install-" + std::to_string(::getpid()));
    fs::remove_all(prefix);
    const std::string install = std::string("'") + CMAKE_COMMAND + "' --install '" +
                                IMAP_BUILD_DIR + "' --prefix '" + prefix.string() +
                                "' > /dev/null 2>&1";
    BOOST_REQUIRE_EQUAL(std::system(install.c_str()), 0);
    const fs::path exe = prefix / "bin" / "imapsim";
    const fs::path cases = prefix / "share" / "imapsim" / "regress" / "cases.json";
    BOOST_REQUIRE(fs::exists(exe));
    BOOST_REQUIRE(fs::exists(cases));

    auto run = [&](const std::string& args) {
        return clitest::run_program(exe.string(), args, "/");  // away from the source tree
    };
    // The firmware assembles from the binary itself, run from "/".
    const clitest::Result ok = run("run --model core --size 32x12 --D 6");
    BOOST_TEST_INFO(ok.out);
    BOOST_TEST(ok.code == 0);
    BOOST_TEST(ok.out.find("bit-exact vs golden: yes") != std::string::npos);
    // A fault names the firmware file as the binary knows it.
    const clitest::Result f = run("run --model core --size 32x12 --D 6 --set watchdog_cycles=1000");
    BOOST_TEST_INFO(f.out);
    BOOST_TEST(f.code == 3);
    BOOST_TEST(f.out.find("(firmware/asm/") != std::string::npos);
    BOOST_TEST(f.out.find(IMAP_SOURCE_DIR) == std::string::npos);

    // The installed regression table is the one the binary reads.
    std::ofstream(cases) << "{\"cases\": [{\"name\": \"installed-table-marker\", \"suite\": "
                            "\"quick\", \"args\": []}]}\n";
    const clitest::Result l = run("regress --list");
    BOOST_TEST_INFO(l.out);
    BOOST_TEST(l.code == 0);
    BOOST_TEST(l.out.find("installed-table-marker") != std::string::npos);
    fs::remove_all(prefix);
}
