// Middlebury-style scoring of a disparity map (SPEC A.8).
#pragma once

#include <opencv2/core.hpp>

#include "imap/golden/stereo.hpp"
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

// score_bad of an ROI-sized LEFT-frame map (disparities, scale 1) over the
// ROI of the scene: ground truth and masks are taken inside the ROI only.
BadScores score_bad_roi(const golden::DisparityMap& m, const Scene& sc, const golden::Roi& roi,
                        double delta = 1.0);

// Share (0..100) of the pixels of an ROI-sized LEFT-frame map whose disparity
// differs from the ground truth by more than `delta` levels; gt is the
// whole-image CV_8UC1 ground truth (gt_scale 1), sampled at the ROI.
double bad_percent_roi(const golden::DisparityMap& m, const cv::Mat& gt, const golden::Roi& roi,
                       int delta = 1);

}  // namespace imap::vision
