// Synthetic stereo sequences for the streaming testbench: moving raised
// objects over a zero-disparity textured background, with exact ground
// truth, plus a synthetic calibration and the inverse of rectification so
// that a test can check the rectify round trip against ground truth.
#pragma once

#include <cstdint>
#include <functional>
#include <memory>
#include <opencv2/core.hpp>
#include <string>
#include <vector>

#include "imap/vision/calib.hpp"

namespace imap::vision {

// Largest disparity of a synthetic sequence (also limited to width / 4).
inline constexpr int kSequenceMaxDisp = 32;
// Largest object speed in pixels per frame, horizontally and vertically. A
// path that would leave the view at this speed is shortened, so objects of a
// long sequence move more slowly (docs/calibration.md).
inline constexpr int kSequenceMaxSpeedX = 3;
inline constexpr int kSequenceMaxSpeedY = 2;

struct SequenceFrame {
    cv::Mat left, right;  // CV_8UC1, rectified
    cv::Mat gt;           // CV_8UC1 left-view disparity, gt_scale 1 (synth.hpp convention)
    int max_disp = 0;     // largest disparity of the whole sequence (same for every frame)
};

// Frame k (0-based) of the sequence `seed` of `frames` frames, width x height.
// Deterministic on every platform. 3 to 5 objects keep their size, texture and
// disparity (up to min(width / 4, kSequenceMaxDisp); the nearest object is at
// exactly max_disp) and move with constant velocity along straight paths
// that stay inside the view for the whole sequence; the background is at
// disparity 0 and fixed. Each frame gets its own view noise (kSynthNoise).
// Same conventions and guarantees as make_synth_scene (objects inside the
// left view, at least d pixels from its left edge).
// Throws std::invalid_argument for sizes outside 16..65536, frames < 1 or k
// outside 0..frames-1.
SequenceFrame make_sequence_frame(uint64_t seed, int width, int height, int k, int frames);

// The same frames as make_sequence_frame, with the per-sequence work
// (background and object textures, paths) done once in the constructor:
// frame(k) is byte-identical to make_sequence_frame(seed, width, height, k,
// frames) and several times faster. Same exceptions.
class SequenceGenerator {
  public:
    SequenceGenerator(uint64_t seed, int width, int height, int frames);
    int frames() const;
    int max_disp() const;
    SequenceFrame frame(int k) const;

  private:
    struct Model;
    std::shared_ptr<const Model> m_;
};

// A synthetic calibration for size: equal focal lengths, small radial and
// tangential distortion, a small rotation between the cameras and a
// horizontal baseline (values listed in docs/calibration.md). Throws
// std::invalid_argument for a size outside 1..16384.
StereoCalib make_synth_calib(cv::Size size);

// The inverse of Rectifier::rectify: renders the raw camera images whose
// rectification is (approximately, up to two bilinear resamplings) the given
// rectified pair; raw pixels that the rectified view does not cover are 0.
// Every raw pixel (u, v) takes the rectified image, sampled bilinearly, at
// cv::undistortPoints((u, v), K, D, R1, P1) (R2, P2 for the right camera).
// Throws InputError if a rectified image is not CV_8UC1 of r.size().
void unrectify(const Rectifier& r, const cv::Mat& left_rect, const cv::Mat& right_rect,
               cv::Mat* left_raw, cv::Mat* right_raw);

// Numbered frame pairs in a folder: every file whose name contains "left"
// (any case) is paired with the same name with that part replaced by "right"
// (same case style), e.g. left_0007.png / right_0007.png or
// f7_Left.png / f7_Right.png; a folder with left/ and right/ subfolders pairs
// equal file names. Only non-hidden image files count (extensions png, pgm,
// ppm, pnm, pbm, bmp, jpg, jpeg, jpe, tif, tiff, webp, jp2, sr, ras, case
// ignored). If "left" occurs more than once, the first occurrence whose
// "right" counterpart exists is used, and a file that is the right frame of
// another pair is not a left frame itself. Ordered by the last number in the name
// (its stem), names without a number first, then by name.
struct FramePair {
    std::string name;         // left file name without folder
    std::string left, right;  // paths; right empty if it is missing
    std::string error;        // non-empty: why this pair cannot be used
};
// Throws InputError if `dir` is not a readable folder or holds no pair.
std::vector<FramePair> list_frame_pairs(const std::string& dir);

// Writes frames 0..frames-1 of a sequence to `dir` (created if missing) as
// left_NNNN.png, right_NNNN.png, gt_NNNN.png (at least 4 digits, from 0000),
// each file atomically; with `calib_file` non-empty, the written left/right
// frames are the raw (un-rectified) images of make_synth_calib, gt stays the
// ground truth of the rectified left frame, and the calibration is written to
// `calib_file` (before the frames, so a bad name fails before any frame is
// written). Returns the max disparity. Throws InputError for write errors
// and std::invalid_argument for arguments make_sequence_frame rejects.
// `on_frame` (optional) is called after each frame's files are written, with
// the number of frames written so far (progress output).
int write_sequence(const std::string& dir, uint64_t seed, int width, int height, int frames,
                   const std::string& calib_file,
                   const std::function<void(int)>& on_frame = nullptr);

}  // namespace imap::vision
