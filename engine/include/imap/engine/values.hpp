// Value lists and ranges of sweep axes: "8,16,32", "A..B" (step 1), "A..B:S"
// (additive step S), "A..B*F" (geometric, factor F), e.g. 8..1024*2.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace imap::engine {

// What a parameter's values are: integers, real numbers or words.
enum class ValueType { Int, Real, Text };

// Largest number of values of one list, and of points of one sweep.
inline constexpr size_t kMaxPoints = 10000;

// Parses a comma list of values and ranges. Ranges need numbers (integers
// for ValueType::Int); Text takes plain words; a value may not appear twice.
// Throws engine::Error naming `flag`, the text and the accepted syntax.
std::vector<std::string> parse_value_list(const std::string& flag, const std::string& text,
                                          ValueType type);

// Strict parses used by the axes (no sign, no spaces): true on success.
bool parse_uint_text(const std::string& s, long long* out);
bool parse_real_text(const std::string& s, double* out);

// "%.3f"-style formatting into a string.
std::string fmt(const char* f, double v);

}  // namespace imap::engine
