// Exhaustive path enumeration over the state lattice of SPEC A.1/A.2, the
// independent oracle for the DP costs on small scanlines.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "imap/golden/params.hpp"
#include "imap/golden/stereo.hpp"

namespace bf {

namespace g = imap::golden;

// One step of a path: it arrives at state (i, j) by `step` (kM, kD or kO).
struct Step {
    int i, j, step;
};
using Path = std::vector<Step>;

struct Line {
    const g::Params& p;
    const uint8_t* L;
    const uint8_t* R;
    int N;
    std::function<int64_t(int, int)> wm = nullptr;  // match cost of (i, j); empty = SPEC A.1
};

inline bool valid(int N, int D, int i, int j) {
    return j >= 0 && j < D && i >= -1 && i <= N - 1 && i + j <= N - 1;
}

// A.1/A.2: cost of the step arriving at (i, j).
inline int64_t step_cost(const Line& l, int i, int j, int step) {
    if (step == g::kD) return l.p.Wd;
    if (step == g::kO) return l.p.Wo;
    if (l.wm) return l.wm(i, j);
    const int a = l.R[i], b = l.L[i + j];
    const int64_t diff = a > b ? a - b : b - a;
    const int64_t dark = l.p.gb - (a < b ? a : b);
    return static_cast<int64_t>(l.p.km) * diff +
           static_cast<int64_t>(l.p.kb) * (dark > 0 ? dark : 0);
}

using Visit = std::function<void(const Path&, int64_t)>;
using IsEnd = std::function<bool(int, int)>;

// Every path from (i, j) with M/D/O steps over valid states of sites <= hi
// that stops at the first state where is_end holds.
inline void enumerate(const Line& l, int hi, int i, int j, Path& path, int64_t cost,
                      const IsEnd& is_end, const Visit& visit) {
    if (is_end(i, j)) {
        visit(path, cost);
        return;
    }
    const int D = l.p.D;
    const int next[3][3] = {{i + 1, j, g::kM}, {i + 1, j - 1, g::kD}, {i, j + 1, g::kO}};
    for (const auto& n : next) {
        if (n[0] > hi || !valid(l.N, D, n[0], n[1])) continue;
        path.push_back({n[0], n[1], n[2]});
        enumerate(l, hi, n[0], n[1], path, cost + step_cost(l, n[0], n[1], n[2]), is_end, visit);
        path.pop_back();
    }
}

// Pixels a path consumes (A.2): M at (i,j): right i and left i+j; D: right i;
// O: left i+j. Adds to the counters.
inline void consume(const Path& path, std::vector<int>& right, std::vector<int>& left) {
    for (const Step& s : path) {
        if (s.step == g::kM || s.step == g::kD) ++right.at(static_cast<size_t>(s.i));
        if (s.step == g::kM || s.step == g::kO) ++left.at(static_cast<size_t>(s.i + s.j));
    }
}

// True if right pixels [r0, r1) and left pixels [l0, l1) are each consumed
// exactly once and no other pixel is consumed.
inline bool consumes_exactly(const Path& path, int N, int r0, int r1, int l0, int l1) {
    std::vector<int> right(static_cast<size_t>(N), 0), left(static_cast<size_t>(N), 0);
    consume(path, right, left);
    for (int x = 0; x < N; ++x) {
        if (right[x] != ((x >= r0 && x < r1) ? 1 : 0)) return false;
        if (left[x] != ((x >= l0 && x < l1) ? 1 : 0)) return false;
    }
    return true;
}

struct Result {
    bool any = false;
    int64_t best = 0;
    long paths = 0;
    bool consumption_ok = true;
    std::string first_bad;  // description of the first path with bad consumption
};

inline std::string path_string(const Path& path) {
    std::string s;
    for (const Step& st : path) {
        s += "MDO?"[st.step < 3 ? st.step : 3];
        s += "(" + std::to_string(st.i) + "," + std::to_string(st.j) + ")";
    }
    return s;
}

inline void record(Result& r, const Path& path, int64_t cost, bool consumption_ok) {
    ++r.paths;
    if (!r.any || cost < r.best) r.best = cost;
    r.any = true;
    if (!consumption_ok && r.consumption_ok) {
        r.consumption_ok = false;
        r.first_bad = path_string(path);
    }
}

// single: all paths (-1,0) -> (N-1,0); O steps in column -1 cost Wo each
// (E(-1,j) = j*Wo) and consume left pixels 0..j-1.
inline Result single(const Line& l) {
    Result r;
    Path path;
    enumerate(
        l, l.N - 1, -1, 0, path, 0, [&](int i, int j) { return i == l.N - 1 && j == 0; },
        [&](const Path& p, int64_t c) {
            record(r, p, c, consumes_exactly(p, l.N, 0, l.N, 0, l.N));
        });
    return r;
}

// bidir right wavefront: from the seed (s, ds) (fixed; O steps at site s cost
// Wo) or from any (s, j) at cost 0 (free, ds < 0) to (N-1, 0). The seed
// consumed right 0..s and left 0..s+j0, the path must consume the rest.
inline Result bidir_right(const Line& l, int s, int ds) {
    Result r;
    Path path;
    for (int j0 = 0; j0 < l.p.D; ++j0) {
        if (!valid(l.N, l.p.D, s, j0)) continue;
        if (ds >= 0 && j0 != ds) continue;
        enumerate(
            l, l.N - 1, s, j0, path, 0, [&](int i, int j) { return i == l.N - 1 && j == 0; },
            [&](const Path& p, int64_t c) {
                record(r, p, c, consumes_exactly(p, l.N, s + 1, l.N, s + j0 + 1, l.N));
            });
    }
    return r;
}

// bidir left wavefront: from (-1,0) to (s-1, ds) (fixed) or to the first state
// of site s-1 (free), over sites <= s-1. Consumes right 0..s-1 and left
// 0..s-1+j_end.
inline Result bidir_left(const Line& l, int s, int ds) {
    Result r;
    Path path;
    enumerate(
        l, s - 1, -1, 0, path, 0, [&](int i, int j) { return i == s - 1 && (ds < 0 || j == ds); },
        [&](const Path& p, int64_t c) {
            const int jend = p.empty() ? 0 : p.back().j;
            record(r, p, c, consumes_exactly(p, l.N, 0, s, 0, s + jend));
        });
    return r;
}

}  // namespace bf
