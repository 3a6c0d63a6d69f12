// The golden reference of SPEC Part A: per-scanline dynamic programming
// (single and bidirectional), inter-scanline majority vote, backtrack events,
// output frames and the fill post-step. Plain C++, integer only.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include "imap/golden/params.hpp"

namespace imap::golden {

// Steps of SPEC A.2. The numeric values are also the pointer encoding used
// by the tables below (and by the firmware).
enum Step : uint8_t { kM = 0, kD = 1, kO = 2, kNone = 3 /* unreachable state */ };

inline constexpr uint8_t kOccluded = 255;

// Non-owning view of an 8-bit grey image.
struct ImageView {
    const uint8_t* data = nullptr;
    int width = 0;
    int height = 0;
    std::ptrdiff_t stride = 0;  // bytes between rows
    const uint8_t* row(int y) const { return data + static_cast<std::ptrdiff_t>(y) * stride; }
};

// Match cost Wm of SPEC A.1 for right pixel a and left pixel b.
inline int64_t match_cost(const Params& p, int a, int b) {
    const int diff = a > b ? a - b : b - a;
    const int mn = a < b ? a : b;
    const int dark = p.gb - mn > 0 ? p.gb - mn : 0;
    return static_cast<int64_t>(p.km) * diff + static_cast<int64_t>(p.kb) * dark;
}

// One event of a backtrack: the path arrived at state (i, j) by `step`.
struct Event {
    int i = 0;
    int j = 0;
    Step step = kM;
    bool operator==(const Event& o) const { return i == o.i && j == o.j && step == o.step; }
};

// Pointer tables of one scanline after the forward pass(es).
//  - single: `right` holds bp(i,j) for sites 0..N-1.
//  - bidir : `right` holds bp(i,j) for sites s..N-1 (site s: kO above a fixed
//            seed, kM at the seed / every level when free, kNone below);
//            `left` holds fp(i,j) for sites -1..s-1 (site s-1: kO below a
//            fixed seed, kM at the seed / every level when free, kNone above).
//  - joint : `right` holds bp(i,j) for sites 0..s (forward from column -1),
//            `left` holds fp(i,j) for sites s..N-1 (cost-to-go to (N-1,0);
//            site N-1: kM at level 0), `js` the meeting level at site s and
//            right_cost the whole line's optimum E(s,js) + G(s,js).
// The O steps down to a fixed seed (right) are recorded as O events before
// the seed's M event; only M events reach the output maps.
// Entry (i, j) of a table with first site f is at [(i - f) * D + j]; invalid
// states (i + j > N - 1) hold kNone.
struct LineTables {
    int N = 0;
    int D = 0;
    int s = 0;    // seed column (bidir) or 0 (single)
    int ds = -1;  // seed disparity, -1 = free (bidir)
    bool bidir = false;
    bool joint = false;   // SPEC A.9 joint mode (see below)
    int right_first = 0;  // first site stored in `right`
    int left_first = -1;  // first site stored in `left`
    int js = -1;          // joint: the meeting level at site s
    std::vector<uint8_t> right;
    std::vector<uint8_t> left;  // sites -1..s-1 (bidir only)
    int64_t right_cost = 0;     // E(N-1, 0)
    int64_t left_cost = 0;      // G(-1, 0) (bidir only)

    uint8_t bp(int i, int j) const { return right[static_cast<size_t>(i - right_first) * D + j]; }
    uint8_t fp(int i, int j) const { return left[static_cast<size_t>(i - left_first) * D + j]; }
};

// Forward pass(es) of one scanline: L and R point at the ROI's first pixel of
// the left and right rows (N pixels each; the left row is read at i + j).
// Parameters must have passed validate_for_width(p, N).
void forward_line(const Params& p, const uint8_t* L, const uint8_t* R, int N, LineTables& out);

// The same with the match cost of state (i, j) read from cost[i * p.D + j]
// (SPEC A.9: a CostVolume line, or any table of N * D costs, each at most
// window_terms(p) * pixel_cost_max(p)).
void forward_line_cost(const Params& p, const int64_t* cost, int N, LineTables& out);

// Voted pointer of SPEC A.5 for `self` at state (i, j) of the right (bp) or
// left (fp) table; `above`/`below` are the neighbouring lines or nullptr.
// Falls back to the line's own pointer if the voted step would leave the
// valid/reachable states (SPEC A.6).
uint8_t voted_bp(const LineTables* above, const LineTables& self, const LineTables* below, int i,
                 int j);
uint8_t voted_fp(const LineTables* above, const LineTables& self, const LineTables* below, int i,
                 int j);

// Backtrack of SPEC A.6. Events are returned in output order: in bidir mode
// the left wavefront's events (in path order from (-1,0)) come first, then the
// right wavefront's (in backtrack order from (N-1,0), seed last).
std::vector<Event> backtrack(const LineTables* above, const LineTables& self,
                             const LineTables* below, bool vote);

// Output map of SPEC A.7 for one line (width N, kOccluded where unmatched).
void render_line(const std::vector<Event>& events, Frame frame, int N, uint8_t* out);

// Fill post-step of SPEC A.7, in place on one row of width n.
void fill_row(uint8_t* row, int n);

// Disparity map of a whole ROI (h rows of w bytes, row-major).
struct DisparityMap {
    int width = 0;
    int height = 0;
    std::vector<uint8_t> data;
    uint8_t at(int x, int y) const { return data[static_cast<size_t>(y) * width + x]; }
};

// Validates, runs the DP on every ROI line (with the vote if enabled) and
// renders the requested frame. `fill` applies the post-step.
DisparityMap compute(const Params& p, ImageView left, ImageView right, const Roi& roi,
                     bool fill = false);

}  // namespace imap::golden
