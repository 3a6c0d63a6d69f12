// SPEC A.9 match costs: the per-pixel terms (Birchfield-Tomasi
// dissimilarity, census Hamming distance) and the box aggregation over a
// window of sites and ROI lines. docs/golden.md ("Options") defines them.
#pragma once

#include <cstdint>
#include <vector>

#include "imap/golden/params.hpp"
#include "imap/golden/stereo.hpp"

namespace imap::golden {

// True when the match cost is not SPEC A.1's Wm (some A.9 cost option is on);
// the DP then reads the match cost from a CostVolume.
bool uses_cost_volume(const Params& p);

// Largest value of one pixel's cost term (before the aggregation sum).
int64_t pixel_cost_max(const Params& p);

// Number of pixel terms summed into one state's cost: (2 rx + 1)(2 ry + 1).
int64_t window_terms(const Params& p);

// Census code of every pixel of an ROI (row-major, w x h): bit k is set when
// the k-th neighbour of the pattern (docs/golden.md, "Census") is darker than
// the pixel. Pixels outside the ROI are those of the nearest ROI pixel
// (replicated borders).
std::vector<uint8_t> census_codes(ImageView img, const Roi& roi, int radius);

// Birchfield-Tomasi bounds of one row of n pixels: lo[x] = min, hi[x] = max
// of I(x), (I(x) + I(x-1)) >> 1, (I(x) + I(x+1)) >> 1, with I(-1) = I(0)
// and I(n) = I(n-1).
void bt_bounds(const uint8_t* row, int n, uint8_t* lo, uint8_t* hi);

// Birchfield-Tomasi dissimilarity of right pixel a (bounds alo, ahi) and left
// pixel b (bounds blo, bhi): min of max(0, a - bhi, blo - a) and
// max(0, b - ahi, alo - b).
inline int bt_dissim(int a, int alo, int ahi, int b, int blo, int bhi) {
    const int d1 = a > bhi ? a - bhi : (blo > a ? blo - a : 0);
    const int d2 = b > ahi ? b - ahi : (alo > b ? alo - b : 0);
    return d1 < d2 ? d1 : d2;
}

// The aggregated match cost Wm(i, j) of every state of every ROI line
// (docs/golden.md, "Aggregation"), produced one line at a time in increasing
// y: line(y) is valid until line(y + 1) is requested. Entry (i, j) of a line
// is at [i * D + j] for 0 <= i < N, 0 <= j < D; invalid states (i + j > N-1)
// hold an unspecified value.
template <class C>
class CostVolume {
  public:
    CostVolume(const Params& p, ImageView left, ImageView right, const Roi& roi);
    const C* line(int y);

  private:
    void pixel_row(int y, C* out) const;  // P_y(x, j) for x = -rx..N-1+rx

    Params p_;
    ImageView L_, R_;
    Roi roi_;
    int N_, D_, rx_, ry_, W_;                     // W_ = N + 2 rx: padded row width
    std::vector<uint8_t> cl_, cr_;                // census codes (kc > 0)
    std::vector<uint8_t> llo_, lhi_, rlo_, rhi_;  // BT bounds of the ROI (bt)
    std::vector<C> ring_;                         // pixel rows of lines y-ry..y+ry, (2ry+1) x W x D
    std::vector<int> ring_line_;                  // which line each ring slot holds
    std::vector<C> vsum_, out_;
};

extern template class CostVolume<int32_t>;
extern template class CostVolume<int64_t>;

}  // namespace imap::golden
