// Disparity maps for the eye: the raw maps (PNG, 8-bit grey) hold the
// disparity d in 0..D-1 as the pixel value and 255 where a pixel is occluded
// or unmatched (SPEC A.7), so they look almost black with white speckles.
// These helpers colour-map them (docs/scoring.md, "Looking at a map").
#pragma once

#include <opencv2/core.hpp>

namespace imap::vision {

// The colour of an occluded / unmatched pixel (value 255) in every
// colour-mapped map and in the stream's video: white (BGR 255,255,255),
// which the JET colour map never produces.
inline const cv::Vec3b kOccludedColour{255, 255, 255};

// The colour (BGR) of disparity d of 0..D-1: OpenCV's COLORMAP_JET at
// level round(255 d / (D-1)) (dark blue = 0 = far, dark red = D-1 = near;
// D = 1: level 0). d = 255 gives kOccludedColour; other d >= D are refused
// (std::invalid_argument). Computed from a table (integer arithmetic and a
// lookup), so the colours do not depend on the CPU.
cv::Vec3b disparity_colour(int d, int D);

// A CV_8UC3 image of a CV_8UC1 disparity map: each pixel disparity_colour.
cv::Mat colorize_disparity(const cv::Mat& disp, int D);

// A legend strip `width` pixels wide (CV_8UC3): the colour bar from 0 to
// D-1 with the end values written under it, and a box in the occlusion
// colour marked "occl". legend_height() rows.
cv::Mat disparity_legend(int width, int D);
int legend_height();

}  // namespace imap::vision
