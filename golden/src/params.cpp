#include "imap/golden/params.hpp"

#include <algorithm>
#include <cstdlib>
#include <sstream>

namespace imap::golden {
namespace {

[[noreturn]] void fail(const std::string& name, long long value, const std::string& allowed) {
    std::ostringstream os;
    os << "parameter " << name << " = " << value << " is out of range (allowed: " << allowed << ")";
    throw ParamError(os.str());
}

void check_range(const std::string& name, long long value, long long lo, long long hi,
                 const std::string& hint = "") {
    if (value < lo || value > hi) {
        std::ostringstream os;
        os << lo << ".." << hi;
        if (!hint.empty()) os << ", " << hint;
        fail(name, value, os.str());
    }
}

}  // namespace

void validate_params(const Params& p) {
    check_range("D", p.D, 1, kMaxLevels, "at most the ROI width");
    check_range("km", p.km, 0, kMaxWeight);
    check_range("kb", p.kb, 0, kMaxWeight);
    check_range("kc", p.kc, 0, kMaxWeight);
    if (p.km == 0 && p.kb == 0 && p.kc == 0)
        throw ParamError(
            "parameters km = 0, kb = 0 and kc = 0: at least one match weight must be > 0");
    check_range("gb", p.gb, 0, 255);
    check_range("Wd", p.Wd, 0, kMaxWeight);
    if (p.Wo < p.Wd) {
        std::ostringstream os;
        os << p.Wd << ".." << kMaxWeight << ", Wo >= Wd = " << p.Wd;
        fail("Wo", p.Wo, os.str());
    }
    check_range("Wo", p.Wo, p.Wd, kMaxWeight);
    if (p.dissim != Dissim::Ad && p.dissim != Dissim::Bt)
        fail("dissim", static_cast<long long>(p.dissim), "0 (ad) or 1 (bt)");
    check_range("ad-max", p.ad_max, 0, 255);
    check_range("census", p.census, 1, kMaxCensusRadius, "the census neighbour distance");
    check_range("agg-rx", p.agg_rx, 0, kMaxAggRadius);
    check_range("agg-ry", p.agg_ry, 0, kMaxAggRadius);
    if (p.mode != Mode::Single && p.mode != Mode::Bidir && p.mode != Mode::Joint)
        fail("mode", static_cast<long long>(p.mode), "single, bidir or joint");
    if (p.mode != Mode::Single) {
        if (p.seed_col.kind == SeedColKind::Fixed)
            check_range("seed-col", p.seed_col.value, 1, kMaxWidth - 1, "1..N-1");
        if (!p.seed_disp.free) check_range("seed-disp", p.seed_disp.value, 0, kMaxLevels - 1);
    }
}

void validate_for_width(const Params& p, int N) {
    validate_params(p);
    check_range("ROI width N", N, 1, kMaxWidth);
    const int dmax = std::min(N, kMaxLevels);
    {
        std::ostringstream hint;
        hint << "min(N, 255) with N = " << N << " the ROI width (the image width without --roi)";
        check_range("D", p.D, 1, dmax, hint.str());
    }
    if (p.mode == Mode::Single) return;
    if (N < 2)
        fail("ROI width N", N,
             std::string("2.. in ") + to_string(p.mode) +
                 " mode (the seed column needs 1 <= s <= N-1)");
    if (p.seed_col.kind == SeedColKind::Fixed) {
        std::ostringstream hint;
        hint << "1 <= s <= N-1 with N = " << N;
        check_range("seed-col", p.seed_col.value, 1, N - 1, hint.str());
    }
    if (!p.seed_disp.free) {
        const int s = resolve_seed_col(p, N);
        const int hi = std::min(p.D - 1, N - 1 - s);
        std::ostringstream hint;
        hint << "0 <= ds < D and s + ds < N with D = " << p.D << ", s = " << s << ", N = " << N;
        check_range("seed-disp", p.seed_disp.value, 0, hi, hint.str());
    }
}

void validate(const Params& p, const Roi& roi, int img_w, int img_h) {
    std::ostringstream where;
    where << "ROI " << roi.x0 << "," << roi.y0 << "," << roi.w << "," << roi.h << " vs image "
          << img_w << "x" << img_h;
    if (img_w <= 0 || img_h <= 0) throw ParamError("empty image (" + where.str() + ")");
    if (roi.w < 1 || roi.h < 1)
        throw ParamError("ROI width and height must be >= 1 (" + where.str() + ")");
    if (roi.x0 < 0 || roi.y0 < 0 || roi.x0 > img_w - roi.w || roi.y0 > img_h - roi.h)
        throw ParamError("ROI lies outside the image (" + where.str() +
                         "; need 0 <= x0, x0 + w <= width, 0 <= y0, y0 + h <= height)");
    validate_for_width(p, roi.w);
}

int resolve_seed_col(const Params& p, int N) {
    switch (p.seed_col.kind) {
        case SeedColKind::Fixed:
            return p.seed_col.value;
        case SeedColKind::Center:
            return N / 2;
        case SeedColKind::Balanced:
            break;
    }
    long long total = 0;
    for (int i = 0; i < N; ++i) total += levels_at(i, N, p.D);
    long long prefix = 0, best_diff = -1;
    int best = 1;
    for (int s = 1; s <= N - 1; ++s) {
        prefix += levels_at(s - 1, N, p.D);  // nodes of sites < s
        const long long diff = std::llabs(prefix - (total - prefix));
        if (best_diff < 0 || diff < best_diff) {  // ties keep the smaller s
            best_diff = diff;
            best = s;
        }
    }
    return best;
}

const char* to_string(Mode m) {
    switch (m) {
        case Mode::Single:
            return "single";
        case Mode::Joint:
            return "joint";
        case Mode::Bidir:
            break;
    }
    return "bidir";
}

const char* to_string(Dissim d) {
    return d == Dissim::Bt ? "bt" : "ad";
}

bool uses_options(const Params& p) {
    return !options_string(p).empty();
}

std::string options_string(const Params& p) {
    const Params off;
    std::ostringstream os;
    auto add = [&](const std::string& flag, const std::string& value) {
        os << (os.tellp() > 0 ? " " : "") << flag << " " << value;
    };
    if (p.mode == Mode::Joint) add("--mode", "joint");
    if (p.dissim != off.dissim) add("--dissim", to_string(p.dissim));
    if (p.ad_max != off.ad_max) add("--ad-max", std::to_string(p.ad_max));
    if (p.kc != off.kc) add("--kc", std::to_string(p.kc));
    if (p.kc != off.kc && p.census != off.census) add("--census", std::to_string(p.census));
    if (p.agg_rx != off.agg_rx) add("--agg-rx", std::to_string(p.agg_rx));
    if (p.agg_ry != off.agg_ry) add("--agg-ry", std::to_string(p.agg_ry));
    return os.str();
}

Params preset(const std::string& name) {
    Params p;
    if (name == "paper") return p;
    if (name != "quality")
        throw ParamError("unknown preset '" + name + "' (allowed: " + preset_names() + ")");
    // docs/golden.md, "Presets": chosen by the tuning sweep on the development scenes.
    p.mode = Mode::Joint;
    p.km = 1;
    p.kb = 0;
    p.gb = 0;
    p.ad_max = 16;
    p.kc = 4;
    p.census = 2;
    p.agg_rx = 2;
    p.agg_ry = 2;  // the 5x5 window (the 5x1 window: variant quality-5x1)
    p.Wo = 400;
    p.Wd = 400;
    return p;
}

const char* preset_names() {
    return "paper, quality";
}

const char* to_string(Frame f) {
    switch (f) {
        case Frame::Left:
            return "left";
        case Frame::Right:
            return "right";
        case Frame::Cyclopean:
            break;
    }
    return "cyc";
}

std::string seed_col_string(const SeedCol& s) {
    switch (s.kind) {
        case SeedColKind::Balanced:
            return "balanced";
        case SeedColKind::Center:
            return "center";
        case SeedColKind::Fixed:
            break;
    }
    return std::to_string(s.value);
}

std::string seed_disp_string(const SeedDisp& s) {
    return s.free ? std::string("free") : std::to_string(s.value);
}

}  // namespace imap::golden
