// Middlebury-style scoring of a disparity map (SPEC A.8).
#pragma once

#include <opencv2/core.hpp>

#include "imap/vision/scene.hpp"

namespace imap::vision {

// Percentages (0..100) of bad pixels in the three evaluation masks.
struct BadScores {
    double nonocc = 0, all = 0, disc = 0;
};

// Scores a LEFT-frame disparity map against the scene's ground truth: a pixel
// is bad if |disp / disp_scale - gt / gt_scale| > delta; each percentage is
// taken over the pixels whose mask value is 255 (and 0 if a mask is empty).
// disp: CV_8U, CV_16U or CV_32F, same size as the scene; values are not
// special-cased (an unfilled 255 is simply a wrong disparity). Ground-truth
// zeros are scored like any other value: the Middlebury masks already leave
// out pixels of unknown disparity.
BadScores score_bad(const cv::Mat& disp, double disp_scale, const Scene& sc, double delta = 1.0);

}  // namespace imap::vision
