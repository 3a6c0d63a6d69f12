#include "imap/golden/stereo.hpp"

#include <algorithm>

#include <array>
#include <limits>
#include "imap/golden/cost.hpp"

namespace imap::golden {
namespace {

// Cost arithmetic is exact: costs use 32-bit integers when the bound below
// proves that every candidate of every state fits, 64-bit otherwise.
// Unreachable states hold kInf; any candidate from one is >= kInf and so
// never beats a reachable candidate (whose value is < bound < kInf).
template <class C>
struct CostTraits;
template <>
struct CostTraits<int32_t> {
    static constexpr int32_t kInf = int32_t{1} << 30;
};
template <>
struct CostTraits<int64_t> {
    static constexpr int64_t kInf = int64_t{1} << 62;
};

// Upper bound of any path cost to any state plus one step: a path to (i, j)
// has at most (i + 1) right-pixel steps and (i + 1 + j) left-pixel steps.
// With the A.9 cost options Wm is a sum of window_terms pixel terms.
int64_t cost_bound(const Params& p, int N) {
    const int64_t wm_max = window_terms(p) * pixel_cost_max(p);
    const int64_t w = std::max({wm_max, int64_t{p.Wo}, int64_t{p.Wd}});
    return (2 * int64_t{N} + p.D + 4) * w;
}

// kTable: the match cost of state (i, j) is cost[i * D + j] (SPEC A.9 cost
// options, a CostVolume line) instead of Wm(R[i], L[i + j]).
template <class C, bool kTable>
struct Line {
    const Params& p;
    const uint8_t* L;
    const uint8_t* R;
    const C* cost;
    int N, D;
    C km, kb, Wo, Wd;
    int gb;

    Line(const Params& pp, const uint8_t* l, const uint8_t* r, const C* c, int n)
        : p(pp),
          L(l),
          R(r),
          cost(c),
          N(n),
          D(pp.D),
          km(pp.km),
          kb(pp.kb),
          Wo(pp.Wo),
          Wd(pp.Wd),
          gb(pp.gb) {}

    // Wm(i, j) with a = R[i], b = L[i + j].
    C wm(int a, int b) const {
        const int diff = a > b ? a - b : b - a;
        const int dark = gb - std::min(a, b);
        return km * diff + kb * (dark > 0 ? dark : 0);
    }
    int top(int i) const { return std::min(D - 1, N - 1 - i); }  // last valid level at site i

    // Right wavefront (A.3 recurrence) over sites first..last, starting from
    // column `first - 1` whose costs are in prev[0..D-1] (prev[D] = kInf).
    // Pointers go to tab rows starting at site `first`. Returns E(last, 0);
    // prev holds E(last, j) afterwards.
    // Each column is two passes: M and D do not depend on the column itself
    // (a vectorisable loop), O is a serial scan in increasing j. The result
    // is the A.3 tie order: M, then D if strictly smaller, then O if
    // strictly smaller.
    C right(std::vector<C>& prev, std::vector<C>& cur, int first, int last, uint8_t* tab) const {
        for (int i = first; i <= last; ++i) {
            const int jm = top(i);
            uint8_t* bp = tab + static_cast<size_t>(i - first) * D;
            const C* pv = prev.data();
            C* cv = cur.data();
            match_diag(pv, pv + 1, i, jm, cv, bp);  // E(i-1, j) + Wm(i, j), E(i-1, j+1) + Wd
            close_column<+1>(cv, bp, jm, cur);
            prev.swap(cur);
        }
        return prev[0];
    }

    // Left wavefront (A.4): cost-to-go G for sites hi-1 down to lo, starting
    // from site hi whose costs are in next[1..D] (index = level + 1, with
    // next[0] = kInf so that D from level -1 is absent). Pointer row r of
    // tab is site r + tab_first. Same two-pass structure, O scanned in
    // decreasing j. Returns G(lo, 0); next holds G(lo, j) afterwards.
    C left(std::vector<C>& next, std::vector<C>& cur, int hi, int lo, uint8_t* tab,
           int tab_first) const {
        for (int i = hi - 1; i >= lo; --i) {
            const int jm = i < 0 ? D - 1 : top(i);
            uint8_t* fp = tab + static_cast<size_t>(i - tab_first) * D;
            const C* nv = next.data();
            C* cv = cur.data() + 1;                     // cv[j] = G(i, j)
            const int jm_m = std::min(jm, top(i + 1));  // M needs (i+1, j) valid
            // G(i+1, j) + Wm(i+1, j), G(i+1, j-1) + Wd
            match_diag(nv + 1, nv, i + 1, jm_m, cv, fp);
            if (jm > jm_m) {  // top level: M would leave the valid states, D only
                cv[jm] = nv[jm] + Wd;
                fp[jm] = kD;
            }
            close_column<-1>(cv, fp, jm, cur);
            next.swap(cur);
        }
        return next[1];
    }

    // The M / D pass of a column: cv[j] = min(mp[j] + Wm(site, j), dp[j] + Wd)
    // for j = 0..jm (M on ties), the winner in ptr[j].
    void match_diag(const C* mp, const C* dp, int site, int jm, C* cv, uint8_t* ptr) const {
        if constexpr (kTable) {
            const C* cr = cost + static_cast<size_t>(site) * D;
            for (int j = 0; j <= jm; ++j) {
                const C m = mp[j] + cr[j];
                const C d = dp[j] + Wd;
                const bool take_d = d < m;
                cv[j] = take_d ? d : m;
                ptr[j] = take_d ? kD : kM;
            }
        } else {
            const uint8_t* lp = L + site;
            const int a = R[site];
            for (int j = 0; j <= jm; ++j) {
                const C m = mp[j] + wm(a, lp[j]);
                const C d = dp[j] + Wd;
                const bool take_d = d < m;
                cv[j] = take_d ? d : m;
                ptr[j] = take_d ? kD : kM;
            }
        }
    }

    // The rest of a column after match_diag: the serial O scan (kDir = +1:
    // O from level j-1, in increasing j; -1: from level j+1, in decreasing
    // j), the unreachable states, and the levels above jm (kNone, and kInf
    // from cv[jm + 1] to the end of buf, the buffer cv points into).
    template <int kDir>
    void close_column(C* cv, uint8_t* ptr, int jm, std::vector<C>& buf) const {
        constexpr C kInf = CostTraits<C>::kInf;
        int j = kDir > 0 ? 0 : jm;
        C run = cv[j];
        for (int n = 0; n < jm; ++n) {
            j += kDir;
            const C o = run + Wo;
            const C c = cv[j];
            const bool take_o = o < c;
            run = take_o ? o : c;
            cv[j] = run;
            ptr[j] = take_o ? uint8_t{kO} : ptr[j];
        }
        mark_unreachable(cv, ptr, jm);
        for (int k = jm + 1; k < D; ++k) ptr[k] = kNone;
        std::fill(cv + jm + 1, buf.data() + buf.size(), kInf);
    }

    // States whose every candidate came from an unreachable state.
    static void mark_unreachable(C* cv, uint8_t* ptr, int jm) {
        constexpr C kInf = CostTraits<C>::kInf;
        for (int j = 0; j <= jm; ++j) {
            const bool none = cv[j] >= kInf;
            cv[j] = none ? kInf : cv[j];
            ptr[j] = none ? uint8_t{kNone} : ptr[j];
        }
    }
};

// SPEC A.9 joint mode: the A.3 forward pass over sites 0..s (pointers bp in
// t.right), the A.4 cost-to-go from the end state (N-1, 0) down to site s
// (pointers fp in t.left, first site s), and the meeting level
// js = argmin_j E(s, j) + G(s, j) (smallest j on ties; j = ds when fixed).
template <class C, bool kTable>
void forward_joint(const Params& p, const Line<C, kTable>& line, std::vector<C>& a,
                   std::vector<C>& b, int N, LineTables& t) {
    constexpr C kInf = CostTraits<C>::kInf;
    const int D = p.D;
    const int s = resolve_seed_col(p, N);
    const int ds = p.seed_disp.free ? -1 : p.seed_disp.value;
    t.s = s;
    t.ds = ds;
    t.right_first = 0;
    t.right.resize(static_cast<size_t>(s + 1) * D);
    t.left_first = s;
    t.left.resize(static_cast<size_t>(N - s) * D);

    for (int j = 0; j < D; ++j) a[j] = C(j) * line.Wo;  // E(-1, j) = j * Wo
    a[D] = kInf;
    line.right(a, b, 0, s, t.right.data());
    thread_local std::vector<C> e;
    e.assign(a.begin(), a.begin() + D);  // E(s, j)

    // Cost-to-go: G(N-1, 0) = 0, the other levels of site N-1 are invalid.
    a.assign(D + 2, kInf);
    b.assign(D + 2, kInf);
    a[1] = 0;
    uint8_t* last = t.left.data() + static_cast<size_t>(N - 1 - s) * D;
    std::fill(last, last + D, uint8_t{kNone});
    last[0] = kM;                                 // the end state; never followed
    line.left(a, b, N - 1, s, t.left.data(), s);  // a[j + 1] = G(s, j)

    const int jm = line.top(s);
    C best = kInf;
    int js = -1;
    for (int j = 0; j <= jm; ++j) {
        if (ds >= 0 && j != ds) continue;
        if (e[j] >= kInf || a[j + 1] >= kInf) continue;
        const C total = e[j] + a[j + 1];
        if (js < 0 || total < best) {
            best = total;
            js = j;
        }
    }
    t.js = js;  // always found: every valid state of site s lies on a complete path
    t.right_cost = best;
    t.left_cost = 0;
}

template <class C, bool kTable>
void forward_typed(const Params& p, const uint8_t* L, const uint8_t* R, const C* cost, int N,
                   LineTables& t) {
    constexpr C kInf = CostTraits<C>::kInf;
    thread_local std::vector<C> a, b;
    const int D = p.D;
    a.assign(D + 2, kInf);
    b.assign(D + 2, kInf);
    Line<C, kTable> line(p, L, R, cost, N);

    t.N = N;
    t.D = D;
    t.bidir = p.mode == Mode::Bidir;
    t.joint = p.mode == Mode::Joint;
    t.left_first = -1;
    t.js = -1;
    if (t.joint) {
        forward_joint(p, line, a, b, N, t);
        return;
    }
    if (!t.bidir) {
        t.s = 0;
        t.ds = -1;
        t.right_first = 0;
        t.right.resize(static_cast<size_t>(N) * D);
        t.left.clear();
        for (int j = 0; j < D; ++j) a[j] = C(j) * line.Wo;  // E(-1, j) = j * Wo
        a[D] = kInf;
        t.right_cost = line.right(a, b, 0, N - 1, t.right.data());
        t.left_cost = 0;
        return;
    }

    const int s = resolve_seed_col(p, N);
    const int ds = p.seed_disp.free ? -1 : p.seed_disp.value;
    t.s = s;
    t.ds = ds;
    t.right_first = s;
    t.right.resize(static_cast<size_t>(N - s) * D);
    t.left.resize(static_cast<size_t>(s + 1) * D);

    // Right wavefront: column s is the start (A.4).
    {
        uint8_t* bp = t.right.data();
        const int jm = line.top(s);
        for (int j = 0; j < D; ++j) {
            if (j > jm || (ds >= 0 && j < ds)) {
                a[j] = kInf;
                bp[j] = kNone;
            } else if (ds < 0) {
                a[j] = 0;
                bp[j] = kM;
            } else {
                a[j] = C(j - ds) * line.Wo;
                bp[j] = j == ds ? kM : kO;
            }
        }
        a[D] = kInf;
        t.right_cost = line.right(a, b, s + 1, N - 1, bp + D);  // = E(s, 0) when s = N-1
    }

    // Left wavefront: site s-1 is the start, stored at row s.
    {
        uint8_t* fp = t.left.data() + static_cast<size_t>(s) * D;
        a.assign(D + 2, kInf);
        b.assign(D + 2, kInf);  // index 0 (level -1) must stay kInf in both buffers
        const int jm = line.top(s - 1);
        for (int j = 0; j < D; ++j) {
            if (j > jm || (ds >= 0 && j > ds)) {
                fp[j] = kNone;
            } else if (ds < 0) {
                a[j + 1] = 0;
                fp[j] = kM;
            } else {
                a[j + 1] = C(ds - j) * line.Wo;
                fp[j] = j == ds ? kM : kO;
            }
        }
        t.left_cost = line.left(a, b, s - 1, -1, t.left.data(), -1);
    }
}

bool right_state_ok(const LineTables& t, int i, int j) {
    if (j < 0 || j >= t.D) return false;
    if (!t.bidir && i == -1) return true;  // virtual start column
    const int last = t.joint ? t.s : t.N - 1;
    if (i < t.right_first || i > last || i + j > t.N - 1) return false;
    return t.bp(i, j) != kNone;
}

bool left_state_ok(const LineTables& t, int i, int j) {
    if (j < 0 || j >= t.D) return false;
    const int last = t.joint ? t.N - 1 : t.s - 1;
    if (i < t.left_first || i > last || (i >= 0 && i + j > t.N - 1)) return false;
    return t.fp(i, j) != kNone;
}

bool neighbours_agree(const LineTables* above, const LineTables* below) {
    return above != nullptr && below != nullptr;
}

}  // namespace

void forward_line(const Params& p, const uint8_t* L, const uint8_t* R, int N, LineTables& out) {
    if (cost_bound(p, N) < (int64_t{1} << 29))
        forward_typed<int32_t, false>(p, L, R, nullptr, N, out);
    else
        forward_typed<int64_t, false>(p, L, R, nullptr, N, out);
}

void forward_line_cost(const Params& p, const int64_t* cost, int N, LineTables& out) {
    if (cost_bound(p, N) < (int64_t{1} << 29)) {
        thread_local std::vector<int32_t> c32;
        c32.assign(cost, cost + static_cast<size_t>(N) * p.D);
        forward_typed<int32_t, true>(p, nullptr, nullptr, c32.data(), N, out);
    } else {
        forward_typed<int64_t, true>(p, nullptr, nullptr, cost, N, out);
    }
}

namespace {

// One step along a pointer: kDir = -1 follows bp back (towards site -1),
// +1 follows fp forward (towards site N-1). M moves one site, D one site
// and one level towards level 0 going forward, O one level.
template <int kDir>
inline void step(uint8_t v, int& i, int& j) {
    switch (v) {
        case kM:
            i += kDir;
            break;
        case kD:
            i += kDir;
            j -= kDir;
            break;
        default:  // kO; kNone cannot occur on a reachable path
            j += kDir;
            break;
    }
}

// The pointer of state (i, j) of the bp (kDir = -1) or fp (+1) table, with
// the A.9 vote: the neighbours' common pointer when it differs from the own
// one and leads to a valid state of this line.
template <int kDir>
inline uint8_t voted(const LineTables* above, const LineTables& self, const LineTables* below,
                     int i, int j) {
    auto ptr = [&](const LineTables& t) { return kDir < 0 ? t.bp(i, j) : t.fp(i, j); };
    const uint8_t own = ptr(self);
    if (!neighbours_agree(above, below)) return own;
    const uint8_t v = ptr(*above);
    if (v == own || v != ptr(*below) || v > kO) return own;
    int ni = i, nj = j;
    step<kDir>(v, ni, nj);
    const bool ok = kDir < 0 ? right_state_ok(self, ni, nj) : left_state_ok(self, ni, nj);
    return ok ? v : own;
}

// Follows the pointers from (i, j) while more(i, j), appending one event a
// step: back along bp (kDir = -1) the event of the state left, forward
// along fp (+1) the event of the state reached.
template <int kDir, class More>
void walk(const LineTables* above, const LineTables& self, const LineTables* below, int& i, int& j,
          std::vector<Event>& ev, More&& more) {
    while (more(i, j)) {
        const uint8_t v = voted<kDir>(above, self, below, i, j);
        if (kDir < 0) ev.push_back({i, j, static_cast<Step>(v)});
        step<kDir>(v, i, j);
        if (kDir > 0) ev.push_back({i, j, static_cast<Step>(v)});
    }
}

}  // namespace

uint8_t voted_bp(const LineTables* above, const LineTables& self, const LineTables* below, int i,
                 int j) {
    return voted<-1>(above, self, below, i, j);
}

uint8_t voted_fp(const LineTables* above, const LineTables& self, const LineTables* below, int i,
                 int j) {
    return voted<+1>(above, self, below, i, j);
}

std::vector<Event> backtrack(const LineTables* above, const LineTables& self,
                             const LineTables* below, bool vote) {
    if (!vote) above = below = nullptr;
    std::vector<Event> ev;
    ev.reserve(static_cast<size_t>(2 * self.N + self.D));

    if (self.joint) {
        // Right part: forward from (s, js) to the end state (N-1, 0), then
        // reversed, so that the events come in backtrack order as in single.
        int i = self.s, j = self.js;
        walk<+1>(above, self, below, i, j, ev, [&](int ii, int) { return ii < self.N - 1; });
        std::reverse(ev.begin(), ev.end());
        // Left part: back from (s, js) to column -1.
        i = self.s;
        j = self.js;
        walk<-1>(above, self, below, i, j, ev, [](int ii, int) { return ii > -1; });
        return ev;
    }

    if (self.bidir) {
        // Left wavefront: forward from (-1, 0) to (s-1, ds) or any state of site s-1.
        int i = -1, j = 0;
        const int last = self.s - 1;
        walk<+1>(above, self, below, i, j, ev,
                 [&](int ii, int jj) { return !(ii == last && (self.ds < 0 || jj == self.ds)); });
    }

    // Right wavefront (or the whole line in single mode): back from (N-1, 0).
    const int stop = self.bidir ? self.s : -1;
    int i = self.N - 1, j = 0;
    walk<-1>(above, self, below, i, j, ev, [&](int ii, int) { return ii > stop; });
    if (self.bidir) {
        while (self.ds >= 0 && j > self.ds) {  // O chain above a fixed seed
            ev.push_back({i, j, kO});
            --j;
        }
        ev.push_back({i, j, kM});  // the seed
    }
    return ev;
}

void render_line(const std::vector<Event>& events, Frame frame, int N, uint8_t* out) {
    std::fill(out, out + N, kOccluded);
    for (const Event& e : events) {
        if (e.step != kM) continue;
        int x = 0;
        switch (frame) {
            case Frame::Right:
                x = e.i;
                break;
            case Frame::Left:
                x = e.i + e.j;
                break;
            case Frame::Cyclopean:
                x = (2 * e.i + e.j) >> 1;
                break;
        }
        if (x >= 0 && x < N) out[x] = static_cast<uint8_t>(e.j);
    }
}

void fill_row(uint8_t* row, int n) {
    thread_local std::vector<int> left_val;
    left_val.assign(static_cast<size_t>(n), -1);
    int last = -1;
    for (int x = 0; x < n; ++x) {
        if (row[x] != kOccluded) last = row[x];
        left_val[x] = last;
    }
    int right = -1;
    for (int x = n - 1; x >= 0; --x) {
        if (row[x] != kOccluded) {
            right = row[x];
            continue;
        }
        const int l = left_val[x];
        int v = 0;
        if (l >= 0 && right >= 0)
            v = std::min(l, right);
        else if (l >= 0)
            v = l;
        else if (right >= 0)
            v = right;
        row[x] = static_cast<uint8_t>(v);
    }
}

namespace {

// The rolling three-line loop of compute(): `fwd(y, tables)` runs the
// forward pass of ROI line y (called in increasing y).
template <class Fwd>
void compute_lines(const Params& p, int N, int H, bool fill, DisparityMap& map, Fwd&& fwd) {
    std::array<LineTables, 3> tabs;  // lines y-1, y, y+1 (rolling)
    fwd(0, tabs[0]);
    for (int y = 0; y < H; ++y) {
        if (y + 1 < H) fwd(y + 1, tabs[static_cast<size_t>((y + 1) % 3)]);
        const LineTables* above = y > 0 ? &tabs[static_cast<size_t>((y - 1) % 3)] : nullptr;
        const LineTables* below = y + 1 < H ? &tabs[static_cast<size_t>((y + 1) % 3)] : nullptr;
        const std::vector<Event> ev =
            backtrack(above, tabs[static_cast<size_t>(y % 3)], below, p.vote);
        uint8_t* row = map.data.data() + static_cast<size_t>(y) * N;
        render_line(ev, p.frame, N, row);
        if (fill) fill_row(row, N);
    }
}

template <class C>
void compute_volume(const Params& p, ImageView left, ImageView right, const Roi& roi, bool fill,
                    DisparityMap& map) {
    CostVolume<C> vol(p, left, right, roi);
    compute_lines(p, roi.w, roi.h, fill, map, [&](int y, LineTables& t) {
        forward_typed<C, true>(p, nullptr, nullptr, vol.line(y), roi.w, t);
    });
}

}  // namespace

DisparityMap compute(const Params& p, ImageView left, ImageView right, const Roi& roi, bool fill) {
    if (left.width != right.width || left.height != right.height)
        throw ParamError("left and right images differ in size: " + std::to_string(left.width) +
                         "x" + std::to_string(left.height) + " vs " + std::to_string(right.width) +
                         "x" + std::to_string(right.height));
    validate(p, roi, left.width, left.height);
    const int N = roi.w, H = roi.h;
    DisparityMap map;
    map.width = N;
    map.height = H;
    map.data.assign(static_cast<size_t>(N) * H, kOccluded);

    if (uses_cost_volume(p)) {
        if (cost_bound(p, N) < (int64_t{1} << 29))
            compute_volume<int32_t>(p, left, right, roi, fill, map);
        else
            compute_volume<int64_t>(p, left, right, roi, fill, map);
        return map;
    }
    compute_lines(p, N, H, fill, map, [&](int y, LineTables& t) {
        forward_line(p, left.row(roi.y0 + y) + roi.x0, right.row(roi.y0 + y) + roi.x0, N, t);
    });
    return map;
}

}  // namespace imap::golden
