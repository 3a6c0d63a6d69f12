// The RTL cache (docs/rtl.md, "Any configuration on demand"; issue 31 item
// 1): a PE count no configuration of this build has runs on the RTL and in
// lockstep, built on first use and loaded afterwards; concurrent runs of
// one new configuration build it once; an entry whose library, record or
// ownership does not match is never loaded; a cache folder others can write
// is refused; a missing tool is named with its Debian package.
#define BOOST_TEST_MODULE cli_rtl_cache
#include <sys/stat.h>
#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <filesystem>
#include <fstream>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include "cli_test_util.hpp"

namespace fs = std::filesystem;
using clitest::Result;

namespace {

// A fresh cache folder per test case.
struct TempCache {
    std::string dir;
    TempCache() {
        char t[] = "/tmp/imap-rtl-cache-test-XXXXXX";
        BOOST_REQUIRE(::mkdtemp(t) != nullptr);
        dir = std::string(t) + "/cache";  // created by imapsim
    }
    ~TempCache() {
        std::error_code ec;
        fs::permissions(dir, fs::perms::owner_all, ec);
        fs::remove_all(fs::path(dir).parent_path(), ec);
    }
    std::string flag() const { return " --rtl-cache '" + dir + "'"; }
    // the entry folders (name p...-hash)
    std::vector<std::string> entries() const {
        std::vector<std::string> v;
        std::error_code ec;
        for (const auto& d : fs::directory_iterator(dir, ec))
            if (d.is_directory() && d.path().filename().string()[0] == 'p')
                v.push_back(d.path().string());
        return v;
    }
};

int count(const std::string& text, const std::string& what) {
    int n = 0;
    for (size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
    return n;
}

// A PE count none of the test configurations of this build uses.
const char* kRun = "run --model lockstep --pes 3 --size 24x8 --D 8";

}  // namespace

BOOST_AUTO_TEST_CASE(concurrent_runs_build_once_then_load) {
    TempCache c;
    // three runs of one new configuration at once
    std::vector<Result> r(3);
    std::vector<std::thread> t;
    for (int i = 0; i < 3; ++i)
        t.emplace_back([&, i] { r[static_cast<size_t>(i)] = clitest::run(kRun + c.flag()); });
    for (std::thread& x : t) x.join();
    int built = 0;
    for (const Result& x : r) {
        BOOST_TEST_MESSAGE(x.out.substr(0, 1200));
        BOOST_CHECK_EQUAL(x.code, 0);
        BOOST_CHECK(x.out.find("lockstep: TLM and RTL agree") != std::string::npos);
        BOOST_CHECK(x.out.find("bit-exact vs golden: yes") != std::string::npos);
        built += count(x.out, "rtl-cache: built p3_m1024_x65536_fst in ");
    }
    BOOST_CHECK_EQUAL(built, 1);
    BOOST_REQUIRE_EQUAL(c.entries().size(), 1u);
    const std::string entry = c.entries()[0];
    // owner-only: the folder, the entry, its library and record
    for (const std::string& p : {c.dir, entry, entry + "/model.so", entry + "/entry.txt"}) {
        struct stat st {};
        BOOST_REQUIRE(::stat(p.c_str(), &st) == 0);
        BOOST_CHECK_MESSAGE((st.st_mode & 077) == 0, p << " is not owner-only");
        BOOST_CHECK_EQUAL(st.st_uid, ::geteuid());
    }
    // the recorded hash is the library's SHA-256 (as coreutils computes it)
    {
        std::ifstream in(entry + "/entry.txt");
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        const std::string sum =
            clitest::run_program("/usr/bin/sha256sum", "'" + entry + "/model.so'")
                .out.substr(0, 64);
        BOOST_CHECK_EQUAL(sum.size(), 64u);
        BOOST_CHECK(text.find("model_sha256=" + sum + "\n") != std::string::npos);
    }
    // later runs load it: no build, same result (the RTL run as well)
    const Result again =
        clitest::run(std::string("run --model rtl --pes 3 --size 24x8 --D 8") + c.flag());
    BOOST_CHECK_EQUAL(again.code, 0);
    BOOST_CHECK_EQUAL(count(again.out, "rtl-cache: build"), 0);
    BOOST_CHECK(again.out.find("bit-exact vs golden: yes") != std::string::npos);
    const Result list = clitest::run("rtl-cache list" + c.flag());
    BOOST_TEST_MESSAGE(list.out);
    BOOST_CHECK_EQUAL(list.code, 0);
    BOOST_CHECK(
        std::regex_search(list.out, std::regex("p3_m1024_x65536_fst +3 +1024 +65536 +FST .* ok")));

    // a tampered library is never loaded: listed invalid, rebuilt on use
    {
        std::fstream f(entry + "/model.so", std::ios::in | std::ios::out | std::ios::binary);
        f.seekp(4096);
        f.put('\x5a');
    }
    const Result bad = clitest::run("rtl-cache list" + c.flag());
    BOOST_CHECK(bad.out.find("invalid: library does not match its recorded hash") !=
                std::string::npos);
    const Result rebuilt = clitest::run(kRun + c.flag());
    BOOST_CHECK_EQUAL(rebuilt.code, 0);
    BOOST_CHECK(rebuilt.out.find("rebuilding p3_m1024_x65536_fst-") != std::string::npos);
    BOOST_CHECK(rebuilt.out.find("library does not match its recorded hash") != std::string::npos);
    BOOST_CHECK_EQUAL(count(rebuilt.out, "rtl-cache: built p3_m1024_x65536_fst in "), 1);
    BOOST_CHECK(rebuilt.out.find("bit-exact vs golden: yes") != std::string::npos);
    BOOST_CHECK(clitest::run("rtl-cache list" + c.flag()).out.find(" ok") != std::string::npos);

    // an entry others can write, or one whose record names another key,
    // is not loaded (listed; `clean --stale` removes it)
    fs::permissions(entry, fs::perms::group_write, fs::perm_options::add);
    BOOST_CHECK(clitest::run("rtl-cache list" + c.flag())
                    .out.find("invalid: folder writable by group or others") != std::string::npos);
    fs::permissions(entry, fs::perms::group_write, fs::perm_options::remove);
    {
        std::ifstream in(entry + "/entry.txt");
        std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
        const size_t k = text.find("key=");
        BOOST_REQUIRE(k != std::string::npos);
        text[k + 4] = text[k + 4] == '0' ? '1' : '0';
        std::ofstream out(entry + "/entry.txt", std::ios::trunc);
        out << text;
    }
    const Result stale = clitest::run("rtl-cache list" + c.flag());
    BOOST_CHECK(stale.out.find("invalid: folder name does not match its record") !=
                    std::string::npos ||
                stale.out.find(" stale") != std::string::npos);
    const Result clean = clitest::run("rtl-cache clean --stale" + c.flag());
    BOOST_CHECK_EQUAL(clean.code, 0);
    BOOST_CHECK(clean.out.find("1 entry removed") != std::string::npos);
    BOOST_CHECK(c.entries().empty());
}

BOOST_AUTO_TEST_CASE(unsafe_folder_missing_tools_and_off_are_refused) {
    TempCache c;
    fs::create_directories(c.dir);
    fs::permissions(c.dir, fs::perms::all);  // 0777
    Result r = clitest::run(std::string("rtl-cache build --pes 3") + c.flag());
    BOOST_TEST_MESSAGE(r.out);
    BOOST_CHECK_EQUAL(r.code, 2);
    BOOST_CHECK(r.out.find("is writable by group or others (mode 0777)") != std::string::npos);
    BOOST_CHECK(r.out.find("chmod 700") != std::string::npos);
    r = clitest::run(std::string(kRun) + c.flag());
    BOOST_CHECK_EQUAL(r.code, 2);
    BOOST_CHECK(r.out.find("writable by group or others") != std::string::npos);
    fs::permissions(c.dir, fs::perms::owner_all);

    // tools: a PATH with cmake, the compiler and pkg-config but no verilator
    const std::string bin = fs::path(c.dir).parent_path().string() + "/bin";
    fs::create_directories(bin);
    for (const char* tool : {"cmake", "c++", "pkg-config", "ninja", "make"}) {
        const std::string found =
            clitest::run_program("/bin/sh", std::string("-c 'command -v ") + tool + "'").out;
        if (!found.empty()) fs::create_symlink(found.substr(0, found.find('\n')), bin + "/" + tool);
    }
    r = clitest::run_program(
        "/usr/bin/env", "PATH=" + bin + " " + IMAPSIM_EXE + " rtl-cache build --pes 3" + c.flag());
    BOOST_TEST_MESSAGE(r.out);
    BOOST_CHECK_EQUAL(r.code, 2);
    BOOST_CHECK(r.out.find("needs verilator (Debian package verilator), not found on PATH") !=
                std::string::npos);
    r = clitest::run_program("/usr/bin/env", std::string("PATH=/nonexistent ") + IMAPSIM_EXE +
                                                 " rtl-cache build --pes 3" + c.flag());
    BOOST_CHECK(r.out.find("needs cmake (Debian package cmake), not found on PATH") !=
                std::string::npos);

    // off: refused with what to do
    r = clitest::run(std::string(kRun) + " --rtl-cache off");
    BOOST_CHECK_EQUAL(r.code, 2);
    BOOST_CHECK(r.out.find("no configuration pes=3 mem_bytes=1024 ext_bytes=65536 in this build") !=
                std::string::npos);
    BOOST_CHECK(r.out.find("building on demand is off") != std::string::npos);
    // a configuration the machine refuses is refused before any build
    r = clitest::run(std::string("rtl-cache build --pes 1") + c.flag());
    BOOST_CHECK_EQUAL(r.code, 2);
    BOOST_CHECK(c.entries().empty());
}
