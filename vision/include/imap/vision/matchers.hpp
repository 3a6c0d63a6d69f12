// The matchers that `imapsim eval` compares: the golden DP reference and two
// OpenCV reference matchers, all returning the same kind of map.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "imap/golden/params.hpp"
#include "imap/vision/scene.hpp"

namespace imap::vision {

// Names accepted by run_matcher, in table order.
const std::vector<std::string>& matcher_names();

// OpenCV settings derived from the search range (documented in docs/scoring.md).
struct OpenCvSettings {
    int num_disparities = 16;  // D rounded up to a multiple of 16
    int block_size = 0;
    int p1 = 0, p2 = 0;  // SGBM smoothness penalties
    int uniqueness_ratio = 0;
    int speckle_window = 0, speckle_range = 0;
    int disp12_max_diff = 0;
    int pre_filter_cap = 0;
    int texture_threshold = 0;  // BM only
};
OpenCvSettings opencv_settings(const std::string& name, int D);

// Runs matcher `name` (golden, opencv-bm or opencv-sgbm) on the whole scene
// and returns the LEFT-frame disparity map: CV_8UC1, integer disparities,
// after the fill post-step of SPEC A.7 (golden::fill_row on every row, 255 =
// unknown before the fill) - the same fill for every matcher.
//  - golden: imap::golden::compute with `p` (p.D as given), frame forced to
//    Left, ROI = whole image, fill on. Invalid parameters throw ParamError.
//  - opencv-bm / opencv-sgbm: StereoBM / StereoSGBM on the grey images with
//    opencv_settings(name, p.D); the 16x fixed-point output becomes
//    (d + 8) / 16 clamped to 254, negative (invalid) -> 255, then the fill.
//    They run single-threaded (cv::setNumThreads(1)), like the golden.
// `seconds` (optional) receives the matcher's wall time, compute only (the
// format conversion and fill included, image I/O not).
// Unknown names throw std::invalid_argument.
cv::Mat run_matcher(const std::string& name, const Scene& sc, const golden::Params& p,
                    double* seconds);

}  // namespace imap::vision
