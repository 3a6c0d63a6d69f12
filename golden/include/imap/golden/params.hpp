// Algorithm parameters of SPEC Part A.1, their defaults and their validation.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace imap::golden {

// Joint (SPEC A.9): two PEs per line as in bidir, but the line's exact
// optimum as in single (docs/golden.md, "Joint mode").
enum class Mode : uint8_t { Single, Bidir, Joint };
enum class Frame : uint8_t { Cyclopean, Left, Right };
enum class SeedColKind : uint8_t { Balanced, Center, Fixed };
// SPEC A.9: the pixel dissimilarity weighted by km (docs/golden.md, "Options").
enum class Dissim : uint8_t { Ad, Bt };

struct SeedCol {
    SeedColKind kind = SeedColKind::Balanced;
    int value = 0;  // only for Fixed
};

struct SeedDisp {
    bool free = true;
    int value = 0;  // only when !free
};

// Region of interest inside the images; N = w is the scanline length.
struct Roi {
    int x0 = 0, y0 = 0, w = 0, h = 0;
};

// Largest accepted weight (km, kb, Wo, Wd). Bounds all costs so that the
// 64-bit path is exact for any image width up to kMaxWidth; the golden uses a
// 32-bit path automatically when the bound proves it exact.
inline constexpr int64_t kMaxWeight = 1'000'000;
inline constexpr int kMaxWidth = 1 << 16;
inline constexpr int kMaxLevels = 255;

// Defaults: tuned on the shared Middlebury scenes (docs/golden.md, "Defaults").
struct Params {
    int D = 64;
    int km = 8;
    int kb = 1;
    int gb = 64;
    int Wo = 100;
    int Wd = 100;
    Mode mode = Mode::Bidir;
    SeedCol seed_col{};
    SeedDisp seed_disp{};
    bool vote = true;
    Frame frame = Frame::Cyclopean;

    // SPEC A.9 quality options (docs/golden.md, "Options"). Each default is
    // "off"; with all of them off (and mode single or bidir) the algorithm is
    // SPEC A.1-A.7 exactly. The match cost becomes
    //   Wm(i,j) = sum over the window of  km * min(dis(a, b), ad_max)
    //             + kb * max(0, gb - min(a, b)) + kc * hamming(census(a), census(b))
    Dissim dissim = Dissim::Ad;  // dis: |a - b| (ad) or Birchfield-Tomasi (bt)
    int ad_max = 255;            // truncation of dis (255 = none)
    int kc = 0;                  // weight of the census Hamming distance (0 = off)
    int census = 2;              // census pattern: 8 neighbours at distance 1 (3x3) or 2 (5x5)
    int agg_rx = 0;              // window: sites i-agg_rx..i+agg_rx
    int agg_ry = 0;              //         and ROI lines y-agg_ry..y+agg_ry
};

// Raised for any invalid parameter: the message names the parameter, the
// offending value and the allowed range.
class ParamError : public std::invalid_argument {
  public:
    using std::invalid_argument::invalid_argument;
};

// Checks everything that does not depend on the ROI (D range against 255,
// weights, gb, Wo >= Wd, numeric seed values >= their absolute minimum).
void validate_params(const Params& p);

// Full check for a scanline of length N (D <= min(N,255), seed column and
// seed disparity ranges). Implies validate_params.
void validate_for_width(const Params& p, int N);

// Full check for images of size img_w x img_h and the given ROI.
void validate(const Params& p, const Roi& roi, int img_w, int img_h);

// Largest census radius and aggregation radius accepted.
inline constexpr int kMaxCensusRadius = 2;
inline constexpr int kMaxAggRadius = 7;

// True when any SPEC A.9 option is on (joint mode included): the parameters
// are not the paper's algorithm of SPEC A.1-A.7.
bool uses_options(const Params& p);

// The A.9 options that are on, as flag text ("--mode joint --kc 4 ..."), or ""
// (for messages: "the firmware does not implement ...").
std::string options_string(const Params& p);

// Presets (docs/golden.md, "Presets"): "paper" = SPEC A.1-A.7 with the tuned
// defaults (Params{}), "quality" = the A.9 options chosen by the tuning on the
// development scenes. Throws ParamError for an unknown name.
Params preset(const std::string& name);
const char* preset_names();  // "paper, quality"

// Seed column s actually used for a scanline of length N (bidir only);
// requires validate_for_width(p, N) to pass.
int resolve_seed_col(const Params& p, int N);

// Number of valid levels at site i (0 <= i < N): min(D, N - i).
inline int levels_at(int i, int N, int D) {
    return (N - i) < D ? (N - i) : D;
}

// Text forms used by the command line and the reports.
const char* to_string(Mode m);
const char* to_string(Frame f);
const char* to_string(Dissim d);
std::string seed_col_string(const SeedCol& s);
std::string seed_disp_string(const SeedDisp& s);

}  // namespace imap::golden
