// The layering of docs/architecture.md, checked on the sources: every
// `#include "imap/<lib>/..."` of a library names itself or a library on a
// lower tier; the plain-C++ libraries include neither SystemC nor Verilator;
// no C++ source file outside tests/ grows past the length a newcomer reads in
// one sitting.
#define BOOST_TEST_MODULE arch_layering
#include <boost/test/unit_test.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace fs = std::filesystem;

namespace {

const fs::path kRoot = IMAP_SOURCE_DIR;

// A library: its folder, the include prefix of its public headers
// (imap/<prefix>/), its tier, and whether it is plain C++ (no SystemC, no
// Verilator). A library may include its own headers and those of any library
// on a lower tier, never one on its own tier or above.
struct Lib {
    std::string dir, prefix;
    int tier;
    bool plain;
};
const std::vector<Lib>& libs() {
    static const std::vector<Lib> l = {
        {"golden", "golden", 0, true},     {"isa", "isa", 0, true},
        {"firmware", "firmware", 1, true}, {"vision", "vision", 1, true},
        {"waves", "waves", 1, true},       {"tlm", "tlm", 1, false},
        {"cosim", "rtl", 2, false},        {"testbench", "testbench", 2, false},
        {"engine", "engine", 3, false},    {"tools", "", 4, false},
    };
    return l;
}

bool is_cpp(const fs::path& p) {
    const auto e = p.extension().string();
    return e == ".cpp" || e == ".hpp" || e == ".h" || e == ".cc";
}

std::vector<fs::path> sources_of(const std::string& dir) {
    std::vector<fs::path> out;
    const fs::path base = kRoot / dir;
    if (!fs::exists(base)) return out;
    for (const auto& e : fs::recursive_directory_iterator(base))
        if (e.is_regular_file() && is_cpp(e.path())) out.push_back(e.path());
    return out;
}

// `#include` targets of a file, one per line that has one.
std::vector<std::pair<int, std::string>> includes_of(const fs::path& p) {
    static const std::regex re(R"(^\s*#\s*include\s*[<"]([^>"]+)[>"])");
    std::vector<std::pair<int, std::string>> out;
    std::ifstream in(p);
    std::string line;
    for (int n = 1; std::getline(in, line); ++n) {
        std::smatch m;
        if (std::regex_search(line, m, re)) out.emplace_back(n, m[1].str());
    }
    return out;
}

// The findings of the include rules in the tree below kRoot.
std::vector<std::string> layering_findings() {
    std::map<std::string, const Lib*> by_prefix;
    for (const auto& l : libs())
        if (!l.prefix.empty()) by_prefix[l.prefix] = &l;
    static const std::regex imap_re(R"(^imap/([a-z_]+)/)");
    std::vector<std::string> found;
    for (const auto& lib : libs()) {
        for (const auto& file : sources_of(lib.dir)) {
            const auto rel = fs::relative(file, kRoot).string();
            for (const auto& [line, target] : includes_of(file)) {
                const std::string where = rel + ":" + std::to_string(line) + ": ";
                std::smatch m;
                if (std::regex_search(target, m, imap_re)) {
                    const auto it = by_prefix.find(m[1].str());
                    if (it == by_prefix.end()) {
                        found.push_back(where + "includes " + target + " of no known library");
                    } else if (it->second != &lib && it->second->tier >= lib.tier) {
                        found.push_back(where + lib.dir + " (tier " + std::to_string(lib.tier) +
                                        ") includes " + target + " of " + it->second->dir +
                                        " (tier " + std::to_string(it->second->tier) +
                                        "): the dependency must point downward");
                    }
                }
                const bool simulator = target.rfind("systemc", 0) == 0 ||
                                       target.rfind("tlm_utils", 0) == 0 || target == "tlm" ||
                                       target == "tlm.h" || target.rfind("verilated", 0) == 0;
                if (lib.plain && simulator)
                    found.push_back(where + lib.dir + " is plain C++ but includes " + target);
            }
        }
    }
    return found;
}

}  // namespace

BOOST_AUTO_TEST_CASE(every_library_includes_only_itself_and_lower_tiers) {
    const auto found = layering_findings();
    for (const auto& f : found) BOOST_TEST_MESSAGE(f);
    BOOST_TEST(found.empty(), found.size() << " include(s) against the layering; first: "
                                           << (found.empty() ? "" : found.front()));
}

BOOST_AUTO_TEST_CASE(the_rules_see_every_library_and_its_includes) {
    // The scan is not vacuous: each library has sources, and the known
    // downward edges are found (firmware uses isa, the engine uses firmware).
    std::set<std::string> edges;
    for (const auto& lib : libs()) {
        BOOST_TEST(!sources_of(lib.dir).empty(), lib.dir << " has no C++ sources");
        for (const auto& file : sources_of(lib.dir))
            for (const auto& inc : includes_of(file)) {
                const auto& t = inc.second;
                if (t.rfind("imap/", 0) == 0)
                    edges.insert(lib.dir + "->" + t.substr(5, t.find('/', 5) - 5));
            }
    }
    for (const char* e : {"firmware->isa", "firmware->golden", "tlm->isa", "cosim->tlm",
                          "engine->firmware", "tools->engine"})
        BOOST_TEST(edges.count(e) == 1, "edge " << e << " not seen");
}

BOOST_AUTO_TEST_CASE(no_source_file_outside_the_tests_is_too_long_to_read) {
    // docs/architecture.md: about 800 lines at most; the limit leaves a
    // margin for a comment, not for another concern.
    constexpr int kMaxLines = 850;
    std::vector<std::string> longer;
    for (const auto& lib : libs())
        for (const auto& file : sources_of(lib.dir)) {
            std::ifstream in(file);
            int n = 0;
            for (std::string s; std::getline(in, s);) ++n;
            if (n > kMaxLines)
                longer.push_back(fs::relative(file, kRoot).string() + " " + std::to_string(n));
        }
    for (const auto& l : longer) BOOST_TEST_MESSAGE(l);
    BOOST_TEST(longer.empty(), longer.size() << " file(s) over " << kMaxLines << " lines; first: "
                                             << (longer.empty() ? "" : longer.front()));
}
