// Seeded mutation fuzzing without extra tools: a deterministic PRNG, byte
// mutators, and a campaign runner that bounds the run by an input count and
// a wall-time budget, records the outcome of every input, saves the input
// under test before each call (so a crash or a hang leaves it on disk) and
// stops the process when one call runs longer than the per-call limit.
// docs/testing.md describes the targets and how to run them longer.
#pragma once

#include <chrono>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <map>
#include <string>
#include <vector>

#include "imap/vision/splitmix64.hpp"

namespace imap::fuzz {

using Bytes = std::vector<uint8_t>;

// The fuzzers' generator: splitmix64 (the same sequence on every platform)
// with the draws the mutators use.
class Rng : public vision::SplitMix64 {
  public:
    using SplitMix64::SplitMix64;
    // Uniform-enough value in 0..n-1 (0 when n == 0).
    uint64_t below(uint64_t n) { return n == 0 ? 0 : next() % n; }
    size_t index(size_t n) { return static_cast<size_t>(below(n)); }
    bool chance(unsigned percent) { return below(100) < percent; }
    template <class T>
    const T& pick(const std::vector<T>& v) {
        return v[index(v.size())];
    }
};

// Budget and seed. Defaults come from the caller; the environment
// (IMAP_FUZZ_SECONDS, IMAP_FUZZ_ITERATIONS, IMAP_FUZZ_SEED,
// IMAP_FUZZ_CALL_LIMIT) and then the test's own arguments
// (`test_fuzz_asm -- --seconds 600 --iterations 0 --seed 7 --replay FILE`)
// override them. iterations = 0 means no count limit.
struct Options {
    double seconds = 20;
    uint64_t iterations = 1000000;
    uint64_t seed = 1;
    double call_limit = 120;  // seconds for one call before it counts as a hang
    std::string replay;       // run this one file only (debugging a saved input)
};
Options options(double default_seconds, uint64_t default_iterations, int argc, char** argv);

// What one input did. `outcome` is a short class ("AsmError: unknown
// instruction '_'"); `violation` is empty when the oracle holds, otherwise
// what went wrong (the input is then saved and the test fails).
struct Result {
    std::string outcome;
    std::string violation;
};

// Class of an error message: the first line, with numbers replaced by N and
// quoted text by '_', cut to 90 characters.
std::string signature(const std::string& prefix, const std::string& message);

// Reads every regular file of `dir` (sorted by name; missing dir = none).
std::vector<std::pair<std::string, Bytes>> read_dir(const std::string& dir);
Bytes read_file(const std::string& path);
void write_file(const std::string& path, const Bytes& b);
// Puts `b` in a scratch file of this process and returns its path. Scratch
// files live in IMAP_FUZZ_TMP, else /dev/shm when it is writable, else the
// work dir: rewriting a file on a disk file system thousands of times a
// second stalls on write-back. They are removed at exit.
std::string put_scratch_file(const std::string& name, const Bytes& b);

// Byte-level mutations (havoc style): 1..stack random edits among bit
// flips, interesting bytes and words, inserts, deletes, block copies and
// splices with `others`. The result is at most max_size bytes.
void mutate_bytes(Rng& rng, Bytes& b, const std::vector<Bytes>& others, size_t max_size,
                  int stack = 4);

// Runs inputs through one target and keeps the figures.
class Campaign {
  public:
    // The input under test is kept in a scratch file; when the process dies
    // or hangs it is copied to <work_dir>/fuzz-<target>-crash<ext>.
    // `work_dir` also receives fuzz-<target>-violation-<n><ext> (inputs that
    // broke the oracle) and fuzz-<target>-slowest<ext> (the slowest input,
    // when over 0.5 s).
    Campaign(std::string target, const Options& opt, std::string work_dir, std::string ext);
    ~Campaign();
    // Stops the watchdog, restores stderr and the signal handlers, removes
    // the current-input file (also done by the destructor).
    void finish();
    Campaign(const Campaign&) = delete;
    Campaign& operator=(const Campaign&) = delete;

    // True while the count and the time budget allow another input.
    bool more() const;
    // Runs one input; returns its result (the violation, if any, is recorded).
    Result run(const Bytes& input, const std::function<Result(const Bytes&)>& fn);

    uint64_t tried() const { return tried_; }
    size_t distinct() const { return outcomes_.size(); }
    const std::vector<std::string>& violations() const { return violations_; }
    const std::map<std::string, uint64_t>& outcomes() const { return outcomes_; }
    double seconds() const;
    // Prints the summary line and the most frequent outcomes to stdout.
    void report(std::ostream& os) const;

  private:
    std::string target_, work_, ext_;
    Options opt_;
    std::chrono::steady_clock::time_point start_;
    uint64_t tried_ = 0;
    std::map<std::string, uint64_t> outcomes_;
    std::vector<std::string> violations_;
    double slowest_ = 0;
    std::string slowest_outcome_;
    std::string cur_path_;
    bool finished_ = false;
    double wall_ = 0;
};

using Checker = std::function<Result(const Bytes&)>;
using Mutator = std::function<void(Rng&, Bytes&, const std::vector<Bytes>&)>;

// Runs every seed once, then mutants of a pool (the seeds plus, up to 1000,
// mutants of at most 16 KB that produced an outcome class not seen before)
// until the campaign's budget ends.
void fuzz_loop(Campaign& c, Rng& rng, const std::vector<Bytes>& seeds, const Mutator& mutate,
               const Checker& check);

// The directory holding corpus/ and regressions/ (from CMake).
std::string fuzz_dir();
// The directory for work files (the test's binary dir, from CMake).
std::string work_dir();

}  // namespace imap::fuzz
