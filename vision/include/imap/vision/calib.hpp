// Stereo calibration files and rectification (OpenCV): the streaming
// testbench rectifies raw camera frames before they enter the model.
#pragma once

#include <opencv2/core.hpp>
#include <string>

#include "imap/vision/image_io.hpp"

namespace imap::vision {

// A stereo calibration as OpenCV's stereo-calibration tools write it
// (cv::FileStorage, YAML, XML or JSON; docs/calibration.md lists the keys):
//   K1 (alias M1, camera_matrix_left)   3x3 camera matrix of the left camera
//   D1 (alias dist_left)                1x4, 1x5, 1x8, 1x12 or 1x14 distortion (or Nx1)
//   K2 / M2, D2                         the same for the right camera
//   R                                   3x3 rotation from the left to the right camera
//   T                                   3x1 (or 1x3) translation, left to right camera
//   image_size ([w, h]) or image_width + image_height
struct StereoCalib {
    cv::Mat K1, D1, K2, D2, R, T;  // CV_64F; as loaded: D1, D2 1xN, T 3x1
    cv::Size size;
};

// Reads and validates a calibration file. Throws InputError naming the file
// and the key: missing key, wrong matrix size, non-finite value, non-positive
// focal length or image size, R not a rotation (|R^T R - I| > 1e-3 or
// det(R) < 0), zero baseline.
StereoCalib load_stereo_calib(const std::string& path);

// Writes a calibration (YAML for .yml/.yaml, XML for .xml, JSON for .json)
// atomically; keys as above (K1 D1 K2 D2 R T image_width image_height).
// Throws InputError for another extension, a calibration that fails the
// checks of load_stereo_calib, or a write error.
void write_stereo_calib(const std::string& path, const StereoCalib& c);

// Alpha of cv::stereoRectify [A]: 0 = the rectified images show only valid
// pixels (no black borders), which the DP matcher needs.
inline constexpr double kRectifyAlpha = 0.0;

// Rectification maps computed once from a calibration (cv::stereoRectify with
// CALIB_ZERO_DISPARITY and kRectifyAlpha, then cv::initUndistortRectifyMap,
// CV_16SC2 maps) and applied per frame with cv::remap (bilinear, 0 outside
// the raw image).
class Rectifier {
  public:
    // Throws InputError if the calibration fails the checks of
    // load_stereo_calib, if its baseline is not horizontal with the right
    // camera on the right (needs T_x < 0 and |T_x| > |T_y|), or if the
    // rectification comes out degenerate.
    explicit Rectifier(const StereoCalib& c);
    const StereoCalib& calib() const { return c_; }
    cv::Size size() const { return c_.size; }  // raw and rectified size (the same)
    const cv::Mat& R1() const { return R1_; }
    const cv::Mat& R2() const { return R2_; }
    const cv::Mat& P1() const { return P1_; }
    const cv::Mat& P2() const { return P2_; }
    // Rectifies one raw CV_8UC1 pair; throws InputError if a size differs
    // from the calibration's (message names both sizes).
    void rectify(const cv::Mat& left_raw, const cv::Mat& right_raw, cv::Mat* left,
                 cv::Mat* right) const;

  private:
    StereoCalib c_;
    cv::Mat R1_, R2_, P1_, P2_, Q_;
    cv::Mat map1l_, map2l_, map1r_, map2r_;
};

}  // namespace imap::vision
