// Optional libFuzzer entry point for one fuzz target (configure with
// -DIMAP_LIBFUZZER=ON and clang; scripts/fuzz.sh --libfuzzer does it). The
// oracle and the structure-aware mutator are those of the seeded loop;
// libFuzzer adds coverage feedback. An oracle violation aborts, so libFuzzer
// saves the input as crash-<hash>.
#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include "fuzz_common.hpp"
#include "fuzz_isa.hpp"
#include "fuzz_vision.hpp"

namespace {

using namespace imap::fuzz;

#if defined(IMAP_FUZZ_TARGET_asm)
const Checker kCheck = check_asm;
const char* const kName = "asm";
const Mutator kMutate = mutate_asm;
#elif defined(IMAP_FUZZ_TARGET_program)
const Checker kCheck = check_program;
const char* const kName = "program";
const Mutator kMutate = mutate_program;
#elif defined(IMAP_FUZZ_TARGET_image)
const Checker kCheck = check_image;
const char* const kName = "image";
const Mutator kMutate = mutate_image;
#elif defined(IMAP_FUZZ_TARGET_calib)
const Checker kCheck = check_calib;
const char* const kName = "calib";
const Mutator kMutate = mutate_calib;
#else
#error "define IMAP_FUZZ_TARGET_<target>"
#endif

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
    const Result r = kCheck(Bytes(data, data + size));
    if (!r.violation.empty()) {
        std::fprintf(stderr, "fuzz oracle violated: %s\n", r.violation.c_str());
        std::abort();
    }
    return 0;
}

extern "C" size_t LLVMFuzzerMutate(uint8_t* data, size_t size, size_t max_size);

// Half of the mutations are ours (structure-aware), half libFuzzer's own.
extern "C" size_t LLVMFuzzerCustomMutator(uint8_t* data, size_t size, size_t max_size,
                                          unsigned int seed) {
    if (seed % 2 == 0) return LLVMFuzzerMutate(data, size, max_size);
    static const std::vector<Bytes> seeds = [] {
        std::vector<Bytes> v;
        for (auto& [path, bytes] : read_dir(fuzz_dir() + "/corpus/" + kName)) v.push_back(bytes);
        return v;
    }();
    Rng rng(seed);
    Bytes b(data, data + size);
    kMutate(rng, b, seeds);
    if (b.size() > max_size) b.resize(max_size);
    std::copy(b.begin(), b.end(), data);
    return b.size();
}
