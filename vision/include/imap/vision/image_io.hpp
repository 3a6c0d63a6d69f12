// Image input/output for the tools: strict 8-bit grey loading and atomic
// writes (a failed write never leaves a half-written or clobbered file).
#pragma once

#include <opencv2/core.hpp>
#include <stdexcept>
#include <string>

#include "imap/golden/stereo.hpp"

namespace imap::vision {

// Bad input or output file: the message names the file and the problem on one
// line, e.g. "left image 'x.png': cannot read (missing, unreadable or not an image)".
class InputError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

// Reads an 8-bit image (any format OpenCV reads) as single-channel grey.
// Colour (3 or 4 channels, palette PNGs included) is converted with OpenCV's
// BGR->grey weights, which leave equal-channel (grey) pixels unchanged.
// Rejects missing/unreadable/non-image files, empty images and 16-bit or
// floating-point images. `what` names the role of the file in messages.
cv::Mat load_grey8(const std::string& path, const std::string& what);

// Non-owning golden view of a CV_8UC1 matrix (throws std::invalid_argument
// for any other type). The matrix must outlive the view.
golden::ImageView view_of(const cv::Mat& m);

// Writes `img` to `path` atomically: the extension must be one OpenCV can
// write; the image goes to a temporary file in the same folder
// (".<name>.tmp-<pid><ext>") that is then renamed over the target. On any
// failure the temporary is removed, the target is left untouched and
// InputError names the path.
void write_image_atomic(const std::string& path, const cv::Mat& img);

// Same for a text file (temporary ".<name>.tmp-<pid>").
void write_text_atomic(const std::string& path, const std::string& text);

}  // namespace imap::vision
