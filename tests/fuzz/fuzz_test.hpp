// Boost.Test side of the fuzz targets: seeds, regression replay, one
// campaign per test (figures printed at the end).
#pragma once

#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <chrono>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "fuzz_common.hpp"

namespace imap::fuzz {

// Default wall-time budget of a fuzz test (CMake IMAP_FUZZ_SECONDS).
inline constexpr double kDefaultSeconds = IMAP_FUZZ_DEFAULT_SECONDS;

// The files of corpus/<sub>.
inline std::vector<Bytes> seeds(const std::string& sub) {
    std::vector<Bytes> out;
    for (auto& [path, bytes] : read_dir(fuzz_dir() + "/corpus/" + sub)) out.push_back(bytes);
    return out;
}

struct Replayed {
    Result result;
    double seconds = 0;
};

// Replays every file of regressions/<target> under the campaign's crash and
// hang guard (`limit` seconds per file): each must satisfy the oracle.
// Returns the outcome of each, by file name.
inline std::map<std::string, Replayed> replay_regressions(const std::string& target,
                                                          const Checker& check, double limit = 60) {
    const auto& m = boost::unit_test::framework::master_test_suite();
    Options o = options(kDefaultSeconds, 1000000, m.argc, m.argv);
    o.call_limit = limit;
    o.seconds = 1e9;
    o.iterations = 0;
    std::map<std::string, Replayed> out;
    {
        Campaign c(target + "-replay", o, work_dir(), "");
        for (const auto& [path, bytes] : read_dir(fuzz_dir() + "/regressions/" + target)) {
            const auto t0 = std::chrono::steady_clock::now();
            const Result r = c.run(bytes, check);
            const double s =
                std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
            out[path.substr(path.find_last_of('/') + 1)] = {r, s};
        }
    }  // stderr back before Boost reports anything
    for (const auto& [name, r] : out) {
        BOOST_TEST_MESSAGE(name << ": " << r.result.outcome << " (" << r.seconds << " s)");
        BOOST_CHECK_MESSAGE(r.result.violation.empty(), name << ": " << r.result.violation);
    }
    BOOST_TEST_MESSAGE(out.size() << " reproducer(s) of " << target << " replayed");
    return out;
}

// One campaign: every seed, then mutants until the budget ends. With
// `--replay FILE` only that file is checked.
inline void run_campaign(const std::string& target, const std::string& ext,
                         const std::vector<Bytes>& seed_files, const Mutator& mutate,
                         const Checker& check) {
    const auto& m = boost::unit_test::framework::master_test_suite();
    const Options o = options(kDefaultSeconds, 1000000, m.argc, m.argv);
    if (!o.replay.empty()) {
        const Result r = check(read_file(o.replay));
        std::cout << o.replay << ": " << r.outcome << (r.violation.empty() ? "" : " !! ")
                  << r.violation << std::endl;
        BOOST_CHECK_MESSAGE(r.violation.empty(), r.violation);
        return;
    }
    BOOST_REQUIRE_MESSAGE(!seed_files.empty(), "no seed files for target " << target);
    Rng rng(o.seed);
    Campaign c(target, o, work_dir(), ext);
    fuzz_loop(c, rng, seed_files, mutate, check);
    c.finish();  // stderr back before Boost reports anything
    c.report(std::cout);
    BOOST_CHECK_GE(c.tried(), seed_files.size());
    const std::string first = c.violations().empty() ? "" : c.violations().front();
    BOOST_CHECK_MESSAGE(c.violations().empty(), c.violations().size()
                                                    << " input(s) broke the oracle of " << target
                                                    << "; first: " << first);
}

}  // namespace imap::fuzz
