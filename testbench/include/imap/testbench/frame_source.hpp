// Where the streamed frames come from (host side, no SystemC): numbered image
// pairs in a folder, two video files, or the built-in synthetic sequence;
// optionally rectified with a calibration (vision/calib.hpp).
#pragma once

#include <cstdint>
#include <memory>
#include <opencv2/core.hpp>
#include <string>

#include "imap/vision/calib.hpp"

namespace imap::testbench {

// One frame of a source: the pair as CV_8UC1 (rectified when the source has a
// calibration), or the reason why this frame cannot be used.
struct SourceFrame {
    int index = 0;     // 0-based position in the stream
    std::string name;  // file name or "frame N"
    cv::Mat left, right;
    cv::Mat gt;         // ground truth (synthetic source only), else empty
    std::string error;  // non-empty: bad frame (unreadable, wrong size, ...)
};

class FrameSource {
  public:
    virtual ~FrameSource() = default;
    // The next frame, or false at the end of the stream. Errors of a single
    // frame are reported in SourceFrame::error (the stream goes on).
    virtual bool next(SourceFrame& f) = 0;
    // Number of frames if known up front, else -1.
    virtual int count() const = 0;
    virtual std::string describe() const = 0;
};

// Numbered pairs in a folder (vision::list_frame_pairs naming). Throws
// vision::InputError if the folder holds no pair.
std::unique_ptr<FrameSource> open_folder(const std::string& dir);
// Two video files read in step with cv::VideoCapture (colour -> grey). Throws
// vision::InputError if a file cannot be opened.
std::unique_ptr<FrameSource> open_videos(const std::string& left, const std::string& right);
// The built-in synthetic sequence (vision/sequence.hpp), already rectified,
// with ground truth.
std::unique_ptr<FrameSource> open_synthetic(uint64_t seed, int width, int height, int frames);

// Wraps a source: every good frame is rectified (maps computed once); a frame
// of the wrong size becomes a bad frame naming both sizes.
std::unique_ptr<FrameSource> rectified(std::unique_ptr<FrameSource> src,
                                       const vision::StereoCalib& calib);

// Wraps a source: every good frame must be width x height (a bad frame
// otherwise) and the left and right images must match.
std::unique_ptr<FrameSource> size_checked(std::unique_ptr<FrameSource> src, cv::Size size);

}  // namespace imap::testbench
