// splitmix64: a tiny, well-mixed 64-bit generator whose sequence is the
// same on every platform and standard library (std:: distributions are
// not). The seeded synthetic scenes and sequences and the fuzzers draw
// from it, so a seed names the same input everywhere.
#pragma once

#include <cstdint>

namespace imap::vision {

class SplitMix64 {
  public:
    explicit SplitMix64(uint64_t seed) : s_(seed) {}
    uint64_t next() {
        uint64_t z = (s_ += 0x9E3779B97F4A7C15ull);
        z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
        z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
        return z ^ (z >> 31);
    }

  private:
    uint64_t s_;
};

}  // namespace imap::vision
