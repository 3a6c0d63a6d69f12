// The request of `imapsim run` as its flags give it: where the images come
// from (--scene, --left/--right with --gt, or the synthetic scene), checked
// with imapsim's messages; and the score of the golden against the ground
// truth with the lines imapsim prints. Running the model is model_run.hpp's.
#pragma once

#include <cstdint>
#include <functional>
#include <nlohmann/json.hpp>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "imap/golden/params.hpp"
#include "imap/vision/scene.hpp"

namespace imap::engine::run {

// The input flags of imapsim run.
struct Request {
    std::string left, right, scene, gt, gt_scale;
    uint64_t seed = 1;
    std::string size = "160x128";
    bool explicit_D = false;  // --D given
};

// The images and what they are scored against.
struct Input {
    cv::Mat L, R, gt;     // gt: the synthetic scene's ground truth
    vision::Scene scene;  // ground truth and masks, when `scored`
    bool scored = false;
    std::string source;  // "scene NAME", "LEFT + RIGHT", "synthetic scene seed S WxH"
};

// Loads the input (engine::Error, exit 2, with imapsim's messages); sets
// p->D from a scene without --D, and *roi (whole image, or the headline ROI
// of a synthetic scene of 128x128 or more) when has_roi is false; then
// checks the ROI and frame against the images. `note` gets the note for
// stderr when the images lie in a scene folder whose D is not the run's.
Input load_input(const Request& r, golden::Params* p, golden::Roi* roi, bool has_roi,
                 const std::function<void(const std::string&)>& note);

// The golden's left-frame map after the fill scored against the input's
// ground truth (as eval scores it): the lines to print and the report's
// "ground_truth" (null when there is no ground truth).
struct Truth {
    std::vector<std::string> lines;
    nlohmann::json json;
};
Truth score_truth(const Input& in, const golden::Params& p, const golden::Roi& roi);

}  // namespace imap::engine::run
