// imapsim golden: the SPEC Part A reference on one stereo pair.
#include <chrono>
#include <cstdio>

#include "cli_common.hpp"
#include "imap/golden/stereo.hpp"
#include "imap/vision/colour.hpp"
#include "imap/vision/image_io.hpp"

namespace imapsim {

namespace g = imap::golden;
namespace v = imap::vision;

namespace {
struct GoldenOptions {
    std::string left, right, out, out_color;
    AlgoFlags algo;
};
}  // namespace

Subcommand register_golden(CLI::App& app) {
    auto o = std::make_shared<GoldenOptions>();
    CLI::App* sub = app.add_subcommand(
        "golden", "Run the golden reference (SPEC Part A) on one rectified stereo pair");
    sub->add_option("--left", o->left, "left image (any format OpenCV reads)")->required();
    sub->add_option("--right", o->right, "right image")->required();
    sub->add_option("--out", o->out, "output disparity map (8-bit, 255 = occluded)")->required();
    sub->add_option("--out-color", o->out_color,
                    "also write it colour-mapped here (JET from 0 = blue to D-1 = red, occluded "
                    "white; docs/scoring.md)");
    add_algo_flags(sub, o->algo);

    return {sub, [o]() {
                g::Roi roi;
                bool has_roi = false;
                const g::Params p = parse_algo_flags(o->algo, &roi, &has_roi);
                check_output_file("--out", o->out, true);
                check_output_file("--out-color", o->out_color, true);
                const cv::Mat L = v::load_grey8(o->left, "left image");
                const cv::Mat R = v::load_grey8(o->right, "right image");
                check_same_size(o->left, L.cols, L.rows, o->right, R.cols, R.rows);
                if (!has_roi) roi = {0, 0, L.cols, L.rows};
                validate_frame(p, roi, L.cols, L.rows);
                const auto t0 = std::chrono::steady_clock::now();
                const g::DisparityMap m =
                    g::compute(p, v::view_of(L), v::view_of(R), roi, o->algo.fill);
                const double ms =
                    std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0)
                        .count();
                cv::Mat out(m.height, m.width, CV_8UC1, const_cast<uint8_t*>(m.data.data()));
                v::write_image_atomic(o->out, out);
                if (!o->out_color.empty())
                    v::write_image_atomic(o->out_color, v::colorize_disparity(out, p.D));
                size_t matched = 0;
                for (uint8_t d : m.data) matched += d != g::kOccluded;
                std::printf(
                    "golden: ROI %d,%d,%dx%d D=%d %s vote %s frame %s: %.2f ms, %.1f%% matched "
                    "-> %s\n",
                    roi.x0, roi.y0, roi.w, roi.h, p.D, g::to_string(p.mode), p.vote ? "on" : "off",
                    g::to_string(p.frame), ms,
                    100.0 * static_cast<double>(matched) / static_cast<double>(m.data.size()),
                    o->out.c_str());
                return static_cast<int>(kExitOk);
            }};
}

}  // namespace imapsim
