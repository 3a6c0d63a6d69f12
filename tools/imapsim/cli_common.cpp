// The algorithm flags (SPEC A.1, A.9): their CLI11 definitions (the parse
// into golden parameters is the engine's algo_params).
#include "cli_common.hpp"

namespace imapsim {

namespace g = imap::golden;

void add_algo_flags(CLI::App* app, AlgoFlags& f) {
    const g::Params d;
    const g::Params q = g::preset("quality");
    AlgoFlags* fp = &f;
    auto opt = [&](const char* name, std::string& dst, const std::string& help,
                   const std::string& def, const char* group = "Algorithm (SPEC A.1)") {
        const std::string flag = name;
        app->add_option(name, dst, help + " [default: " + def + "]")
            ->group(group)
            ->each([fp, flag](const std::string&) { fp->given.insert(flag); });
    };
    opt("--preset", f.preset,
        "starting values of all algorithm flags: paper (SPEC A.1-A.7) or quality (SPEC A.9 "
        "options, docs/golden.md); flags given override them",
        "paper");
    opt("--D", f.D, "disparity levels 0..D-1 (1..min(ROI width, 255))", std::to_string(d.D));
    opt("--km", f.km, "match weight on |R - L| (0..1000000)", std::to_string(d.km));
    opt("--kb", f.kb, "match weight on gb - min(R, L) (0..1000000)", std::to_string(d.kb));
    opt("--gb", f.gb, "intensity upper bound (0..255)", std::to_string(d.gb));
    opt("--Wo", f.Wo, "occlusion cost (Wd..1000000)", std::to_string(d.Wo));
    opt("--Wd", f.Wd, "discontinuity cost (0..Wo)", std::to_string(d.Wd));
    opt("--mode", f.mode,
        "single (one wavefront per line), bidir (two) or joint (two, meeting exactly; SPEC A.9)",
        "bidir");
    opt("--seed-col", f.seed_col, "bidir/joint seed column: balanced, center or 1..N-1",
        "balanced");
    opt("--seed-disp", f.seed_disp, "bidir/joint seed disparity: free or 0..D-1 (s + ds < N)",
        "free");
    opt("--vote", f.vote, "inter-scanline majority vote: on or off", "on");
    opt("--roi", f.roi, "region of interest x0,y0,w,h", "whole image");
    opt("--frame", f.frame, "output frame: cyc (cyclopean), left or right", "cyc");
    app->add_flag("--fill", f.fill, "replace occluded pixels (255) by the background fill")
        ->group("Algorithm (SPEC A.1)");
    const char* a9 = "Quality options (SPEC A.9, docs/golden.md)";
    const std::string qd = " (quality: ";
    opt("--dissim", f.dissim,
        "pixel dissimilarity of the km term: ad (|R - L|) or bt (Birchfield-Tomasi)",
        std::string(g::to_string(d.dissim)) + qd + g::to_string(q.dissim) + ")", a9);
    opt("--ad-max", f.ad_max, "truncation of the km term's dissimilarity (0..255; 255 = none)",
        std::to_string(d.ad_max) + qd + std::to_string(q.ad_max) + ")", a9);
    opt("--kc", f.kc, "match weight on the census Hamming distance (0..1000000; 0 = off)",
        std::to_string(d.kc) + qd + std::to_string(q.kc) + ")", a9);
    opt("--census", f.census, "census neighbour distance: 1 (3x3) or 2 (5x5)",
        std::to_string(d.census) + qd + std::to_string(q.census) + ")", a9);
    opt("--agg-rx", f.agg_rx, "match cost summed over sites i-rx..i+rx (0..7)",
        std::to_string(d.agg_rx) + qd + std::to_string(q.agg_rx) + ")", a9);
    opt("--agg-ry", f.agg_ry, "... and over ROI lines y-ry..y+ry (0..7)",
        std::to_string(d.agg_ry) + qd + std::to_string(q.agg_ry) + ")", a9);
}

}  // namespace imapsim
