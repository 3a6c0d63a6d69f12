// Image perturbations for robustness checks (`imapsim eval --perturb`):
// a gain and offset on one or both images and additive noise, all in integer
// arithmetic so that a SPEC and a seed give the same bytes on every CPU,
// compiler and standard library (docs/scoring.md, "Perturbations").
#pragma once

#include <cstdint>
#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>

namespace imap::vision {

// Which images a part of the perturbation applies to.
enum class PerturbImages { Left, Right, Both };

struct Perturbation {
    double gain = 1.0;    // (0, 16]
    double offset = 0.0;  // [-255, 255]
    double noise = 0.0;   // sigma in grey levels, [0, 64]
    uint64_t seed = 1;
    PerturbImages image = PerturbImages::Right;       // gain and offset go here
    PerturbImages noise_image = PerturbImages::Both;  // noise goes here
    bool identity() const { return gain == 1.0 && offset == 0.0 && noise == 0.0; }
};

// A SPEC refused by parse_perturbation: the offending item (key=value, or
// the whole SPEC) and what is allowed; what() = "'ITEM': WANT".
class PerturbSpecError : public std::invalid_argument {
  public:
    PerturbSpecError(const std::string& item, const std::string& want)
        : std::invalid_argument("'" + item + "': " + want), item_(item), want_(want) {}
    const std::string& item() const { return item_; }
    const std::string& want() const { return want_; }

  private:
    std::string item_, want_;
};

// Parses "key=value[,key=value...]" with the keys gain, offset, noise, seed,
// image (left|right|both: the images gain and offset change) and
// noise-image (left|right|both); a key given twice, an unknown key, a
// missing '=', a value out of range or not a number throws
// PerturbSpecError naming the item and the allowed range (the caller adds
// the option name).
Perturbation parse_perturbation(const std::string& spec);

// The canonical text of `p` (every key, parse_perturbation reads it back).
std::string to_string(const Perturbation& p);

// Perturbs one CV_8UC1 image in place; `is_right` selects which of the
// images it is (the two noise streams are independent). Per pixel:
// out = clamp(round(g * x + o + sigma * n), 0, 255), with g, o and sigma
// rounded to multiples of 2^-16, n = (sum of 12 uniform 16-bit draws -
// its mean) / 65536 (Irwin-Hall: mean 0, standard deviation 1 - 2^-33,
// bounded at +-6) from splitmix64 seeded with the seed and the image, and
// round = half up; every step is integer arithmetic.
void perturb_image(cv::Mat& img, const Perturbation& p, bool is_right);

// Both images of a pair.
void perturb_pair(cv::Mat& left, cv::Mat& right, const Perturbation& p);

}  // namespace imap::vision
