// imapsim run's input: the images of --scene, --left/--right (with --gt) or
// the synthetic scene, checked; the golden scored against the ground truth.
#include "imap/engine/run_request.hpp"

#include <cstdio>

#include "imap/engine/error.hpp"
#include "imap/engine/flag_values.hpp"
#include "imap/engine/output_files.hpp"
#include "imap/golden/stereo.hpp"
#include "imap/vision/image_io.hpp"
#include "imap/vision/score.hpp"
#include "imap/vision/synth.hpp"

namespace imap::engine::run {

namespace g = imap::golden;
namespace v = imap::vision;

namespace {

// --left/--right with --gt: the ground truth, every pixel scored.
void load_gt(const Request& r, double gt_scale, Input* in) {
    in->scene.name = r.gt;
    in->scene.gt = v::load_grey8(r.gt, "ground truth");
    const cv::Mat& L = in->L;
    if (in->scene.gt.size() != L.size())
        throw Error("ground truth '" + r.gt + "' is " + std::to_string(in->scene.gt.cols) + "x" +
                    std::to_string(in->scene.gt.rows) + " but the left image is " +
                    std::to_string(L.cols) + "x" + std::to_string(L.rows));
    in->scene.gt_scale = gt_scale > 0 ? gt_scale : 1.0;
    in->scene.default_masks = true;
    in->scene.nonocc = cv::Mat(L.size(), CV_8UC1, cv::Scalar(255));
    in->scene.all = in->scene.nonocc.clone();
    in->scene.disc = in->scene.nonocc.clone();
    in->scored = true;
}

// The images of a scene folder without --D: say that its D differs.
std::string scene_d_note(const std::string& left, int D) {
    try {
        const v::Scene sc = v::load_scene(folder_of(left));
        if (sc.ndisp == D) return "";
        return "note: " + left + " lies in scene folder '" + sc.name +
               "', whose scenes.json gives ndisp " + std::to_string(sc.ndisp) +
               "; this run uses --D " + std::to_string(D) + " (the default): --scene " +
               folder_of(left) + " takes the scene's D and scores it\n";
    } catch (const std::exception&) {
        return "";
    }
}

}  // namespace

Input load_input(const Request& r, g::Params* p, g::Roi* roi, bool has_roi,
                 const std::function<void(const std::string&)>& note) {
    double gt_scale = 0;
    if (!r.gt_scale.empty()) {
        if (r.scene.empty() && r.gt.empty()) throw Error("--gt-scale needs --scene or --gt");
        gt_scale = parse_real_flag("--gt-scale", r.gt_scale, 0, 1e6, true);
    }
    Input in;
    if (r.left.empty() != r.right.empty()) throw Error("--left and --right must be given together");
    if (!r.scene.empty() && !r.left.empty())
        throw Error("give either --scene DIR or --left/--right, not both");
    if (!r.gt.empty() && r.left.empty())
        throw Error("--gt needs --left and --right (--scene has its own)");
    if (!r.scene.empty()) {
        in.scene = v::load_scene(r.scene, gt_scale, r.explicit_D ? p->D : 0);
        if (!r.explicit_D) p->D = in.scene.ndisp;
        in.L = in.scene.left;
        in.R = in.scene.right;
        in.scored = true;
        in.source = "scene " + in.scene.name;
    } else if (!r.left.empty()) {
        in.L = v::load_grey8(r.left, "left image");
        in.R = v::load_grey8(r.right, "right image");
        in.source = r.left + " + " + r.right;
        if (!r.gt.empty()) {
            load_gt(r, gt_scale, &in);
        } else if (!r.explicit_D) {
            if (const std::string n = scene_d_note(r.left, p->D); !n.empty()) note(n);
        }
    } else {
        int w = 0, h = 0;
        char x = 0;
        if (std::sscanf(r.size.c_str(), "%d%c%d", &w, &x, &h) != 3 || x != 'x' || w < 2 || h < 1 ||
            w > 4096 || h > 4096)
            throw Error("invalid value '" + r.size +
                        "' for --size: expected WxH with W in 2..4096, H in 1..4096");
        v::SynthScene sc = v::make_synth_scene(r.seed, w, h);
        in.L = sc.left;
        in.R = sc.right;
        in.gt = sc.gt;
        in.source = "synthetic scene seed " + std::to_string(r.seed) + " " + r.size;
        if (!has_roi && w >= 128 && h >= 128) {
            *roi = {(w - 128) / 2, (h - 128) / 2, 128, 128};  // the headline ROI
            has_roi = true;
        }
    }
    check_same_size(r.left, in.L.cols, in.L.rows, r.right, in.R.cols, in.R.rows);
    if (!has_roi) *roi = {0, 0, in.L.cols, in.L.rows};
    validate_frame(*p, *roi, in.L.cols, in.L.rows);
    return in;
}

Truth score_truth(const Input& in, const g::Params& p, const g::Roi& roi) {
    Truth t;
    if (in.gt.empty() && !in.scored) return t;
    g::Params pl = p;
    pl.frame = g::Frame::Left;
    const g::ImageView lv = v::view_of(in.L), rv = v::view_of(in.R);
    const g::DisparityMap ml = g::compute(pl, lv, rv, roi, true);
    char buf[256];
    if (!in.gt.empty()) {
        const double bad = v::bad_percent_roi(ml, in.gt, roi);
        std::snprintf(buf, sizeof buf,
                      "  golden bad-1 vs ground truth (left frame, filled): %.2f%%", bad);
        t.json = {{"bad1_all", bad}};
    } else {
        // As eval scores it: the golden's left-frame map after the fill.
        const v::BadScores b = v::score_bad_roi(ml, in.scene, roi, 1.0);
        if (in.scene.default_masks)
            std::snprintf(buf, sizeof buf,
                          "  golden bad-1 vs ground truth (left frame, filled, every pixel of the "
                          "ROI): %.2f%%",
                          b.all);
        else
            std::snprintf(buf, sizeof buf,
                          "  golden bad-1 vs ground truth (left frame, filled%s): nonocc %.2f%%, "
                          "all %.2f%%, disc %.2f%%",
                          roi.w == in.L.cols && roi.h == in.L.rows ? "" : ", inside the ROI",
                          b.nonocc, b.all, b.disc);
        t.json = {{"bad1_nonocc", b.nonocc},
                  {"bad1_all", b.all},
                  {"bad1_disc", b.disc},
                  {"gt_scale", in.scene.gt_scale},
                  {"masks", !in.scene.default_masks}};
    }
    t.lines.push_back(buf);
    // The score is the golden's left-frame map after the fill (as eval
    // scores it), not the map this run checked and writes.
    t.json["scored_map"] = {{"source", "golden"}, {"frame", "left"}, {"fill", true}};
    t.json["output_map"] = {{"frame", g::to_string(p.frame)}, {"fill", false}};
    if (p.frame != g::Frame::Left)
        t.lines.push_back(std::string("  (scored: the golden's left-frame map after the fill; the "
                                      "model's map and --out are the ") +
                          g::to_string(p.frame) + " frame, unfilled)");
    return t;
}

}  // namespace imap::engine::run
