// Algorithm parameters of SPEC Part A.1, their defaults and their validation.
#pragma once

#include <cstdint>
#include <stdexcept>
#include <string>

namespace imap::golden {

enum class Mode : uint8_t { Single, Bidir };
enum class Frame : uint8_t { Cyclopean, Left, Right };
enum class SeedColKind : uint8_t { Balanced, Center, Fixed };

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
std::string seed_col_string(const SeedCol& s);
std::string seed_disp_string(const SeedDisp& s);

}  // namespace imap::golden
