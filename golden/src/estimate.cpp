#include "imap/golden/estimate.hpp"

#include <algorithm>
#include <sstream>

#include "imap/golden/cost.hpp"

namespace imap::golden {
namespace {

int bytes_of(int64_t max) {
    return max <= 255 ? 1 : (max <= 65535 ? 2 : 3);
}

// Shift-and-add multiplication of a `bytes`-wide value by the constant k:
// one shift per set bit after the first and one add per further set bit.
int mul_ops(int k, int bytes) {
    if (k <= 1) return 0;
    const int bits = __builtin_popcount(static_cast<unsigned>(k));
    return (2 * bits - 1) * bytes;
}

std::string fmt(const char* name, double node, double pixel, int64_t bytes) {
    std::ostringstream os;
    os << name << ": " << node << " cycles/node";
    if (pixel > 0) os << ", " << pixel << " cycles/pixel";
    if (bytes > 0) os << ", " << bytes << " bytes/PE";
    return os.str();
}

}  // namespace

Params paper_part(const Params& p) {
    Params q = p;
    const Params off;
    if (q.mode == Mode::Joint) q.mode = Mode::Bidir;
    q.dissim = off.dissim;
    q.ad_max = off.ad_max;
    q.kc = off.kc;
    q.census = off.census;
    q.agg_rx = off.agg_rx;
    q.agg_ry = off.agg_ry;
    if (q.km == 0 && q.kb == 0) q.km = 1;  // a census-only cost: keep the paper part valid
    return q;
}

OptionCost estimate_options(const Params& p, int N, bool in_firmware) {
    OptionCost c;
    // the firmware runs every A.9 option: nothing of it is estimated
    if (!uses_options(p) || in_firmware) return c;
    const int D = p.D;
    const bool two = p.mode != Mode::Single;  // two PEs per line
    int kmax = N;
    if (two) {
        const int s = resolve_seed_col(p, N);
        kmax = p.mode == Mode::Joint ? std::max(s + 1, N - 1 - s) : std::max(s, N - 1 - s);
    }
    const int hop = two ? 2 : 1;  // ring hops between neighbouring lines
    const int rx = p.agg_rx, ry = p.agg_ry;
    c.nodes = int64_t{kmax} * D;
    c.pixels = (two ? (kmax + 1) + (kmax + D + 1) : N + (N + D)) + 4 * rx;

    const int64_t cmax = pixel_cost_max(p);
    const int cb = bytes_of(cmax);                    // one pixel term
    const int hb = bytes_of((2 * rx + 1) * cmax);     // its sum over the sites
    const int sb = bytes_of(window_terms(p) * cmax);  // the whole window
    if (p.ad_max < 255) {
        c.per_node += 1;  // mini
        c.items.push_back(fmt("ad-max", 1, 0, 0));
    }
    if (p.dissim == Dissim::Bt) {
        // two loads (lo, hi of the left pixel) and 10 ALU operations instead of
        // max/min/sub; lo/hi of both images per pixel: 2 loads, 2 adds, 2
        // shifts, 4 min/max, 2 stores.
        c.per_node += 12;
        c.per_pixel += 12;
        c.local_bytes += 2 * c.pixels;
        c.items.push_back(fmt("dissim bt", 12, 12, 2 * c.pixels));
    }
    if (p.kc > 0) {
        // ld code, xor, andi + shri (nibbles), 2 ldx of a 16-entry table (2
        // cycles each), add, kc by shift-and-add, add into the pixel cost.
        const double node = 1 + 1 + 2 + 4 + 1 + mul_ops(p.kc, 1) + cb;
        // per pixel: rows y-r and y+r over the ring and stored, 2 border
        // selects, 8 x (ld, sub, rolc) and the store of the code.
        const double pixel = 2.0 * p.census * hop + 2 + 2 + 8 * 3 + 1;
        c.per_node += node;
        c.per_pixel += pixel;
        c.local_bytes += c.pixels + 16;
        c.items.push_back(fmt("census", node, pixel, c.pixels + 16));
    }
    if (rx > 0) {
        // the pixel costs of the 2 rx previous columns live in a rolling
        // buffer: load them, add them to the new one, store the new one over
        // the oldest (read just before).
        const double node = cb + 2.0 * rx * cb + 2.0 * rx * hb;
        const int64_t bytes = int64_t{2 * rx} * D * cb;
        c.per_node += node;
        c.local_bytes += bytes;
        c.items.push_back(fmt("agg-rx", node, 0, bytes));
    }
    if (ry > 0) {
        // per line distance v: the row sums of lines y-v and y+v over the ring
        // (hop PEs further each), a border select each, two adds.
        const double node = ry * (2.0 * hop * hb + 2.0 * hb + 2.0 * sb);
        c.per_node += node;
        c.items.push_back(fmt("agg-ry", node, 0, 0));
    }
    if (p.mode == Mode::Joint) {
        // E(s, .) to the partner PE (3 bytes, 1 hop, stored), 24-bit
        // compare-and-select with the level index, js back (1 hop).
        c.per_batch += 3 * D + 3 * D + 8 * D + 20;
        std::ostringstream os;
        os << "joint: " << c.per_batch << " cycles/batch";
        c.items.push_back(os.str());
    }
    c.cycles = static_cast<int64_t>(static_cast<double>(c.nodes) * c.per_node +
                                    static_cast<double>(c.pixels) * c.per_pixel + 0.5) +
               c.per_batch;
    return c;
}

const std::vector<Variant>& tradeoff_variants() {
    static const std::vector<Variant> v = [] {
        std::vector<Variant> out;
        const Params paper = preset("paper");
        const Params quality = preset("quality");
        auto add = [&](const char* name, const char* what, Params p) {
            out.push_back({name, what, p});
        };
        add("paper", "SPEC A.1-A.7, the tuned defaults", paper);
        Params p = paper;
        p.mode = Mode::Single;
        add("paper-single", "paper, mode single", p);
        p.mode = Mode::Joint;
        add("paper-joint", "paper, mode joint", p);
        p = paper;
        p.mode = Mode::Joint;
        p.agg_rx = p.agg_ry = 1;
        p.Wo = p.Wd = 500;
        add("joint-agg", "paper costs summed over 3x3, joint, Wo = Wd = 500", p);
        p = quality;
        p.agg_rx = p.agg_ry = 0;
        p.Wo = p.Wd = 16;
        add("joint-census", "quality without the aggregation, Wo = Wd = 16", p);
        p = quality;
        p.agg_rx = p.agg_ry = 1;
        p.Wo = p.Wd = 144;
        add("quality-3x3", "quality with a 3x3 window, Wo = Wd = 144", p);
        p = quality;
        p.agg_rx = 1;
        p.agg_ry = 0;
        p.Wo = p.Wd = 80;
        add("quality-3x1", "quality with a 3x1 window, Wo = Wd = 80", p);
        p = quality;
        p.ad_max = 255;
        add("quality-notrunc", "quality, ad-max 255", p);
        add("quality", "the quality preset", quality);
        p = quality;
        p.agg_ry = 0;
        p.Wo = p.Wd = 80;
        add("quality-5x1", "quality with a 5x1 window, Wo = Wd = 80", p);
        p = quality;
        p.dissim = Dissim::Bt;
        add("quality-bt", "quality, dissim bt", p);
        p = quality;
        p.census = 1;
        add("quality-census1", "quality, census 1 (3x3)", p);
        p = quality;
        p.vote = false;
        add("quality-novote", "quality, vote off", p);
        p = quality;
        p.mode = Mode::Bidir;
        add("quality-bidir", "quality, mode bidir (free seed)", p);
        p = quality;
        p.mode = Mode::Single;
        add("quality-single", "quality, mode single", p);
        return out;
    }();
    return v;
}

}  // namespace imap::golden
