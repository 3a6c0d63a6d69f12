#include "imap/vision/matchers.hpp"

#include <chrono>
#include <opencv2/calib3d.hpp>
#include <stdexcept>

#include "imap/golden/stereo.hpp"
#include "imap/vision/image_io.hpp"

namespace imap::vision {

namespace g = imap::golden;

namespace {

using Clock = std::chrono::steady_clock;

double since(Clock::time_point t0) {
    return std::chrono::duration<double>(Clock::now() - t0).count();
}

// Restores OpenCV's thread count on scope exit.
class SingleThreaded {
  public:
    SingleThreaded() : saved_(cv::getNumThreads()) { cv::setNumThreads(1); }
    ~SingleThreaded() { cv::setNumThreads(saved_); }
    SingleThreaded(const SingleThreaded&) = delete;
    SingleThreaded& operator=(const SingleThreaded&) = delete;

  private:
    int saved_;
};

// OpenCV 16x fixed-point disparities -> integer levels (255 = unknown), then fill.
cv::Mat from_fixed_point(const cv::Mat& d16) {
    cv::Mat out(d16.size(), CV_8UC1);
    for (int y = 0; y < d16.rows; ++y) {
        const int16_t* s = d16.ptr<int16_t>(y);
        uint8_t* o = out.ptr<uint8_t>(y);
        for (int x = 0; x < d16.cols; ++x) {
            const int v = s[x];
            o[x] = v < 0 ? g::kOccluded : static_cast<uint8_t>(std::min((v + 8) / 16, 254));
        }
        g::fill_row(o, out.cols);
    }
    return out;
}

}  // namespace

const std::vector<std::string>& matcher_names() {
    static const std::vector<std::string> names = {"golden", "opencv-bm", "opencv-sgbm"};
    return names;
}

OpenCvSettings opencv_settings(const std::string& name, int D) {
    OpenCvSettings s;
    s.num_disparities = ((std::max(D, 1) + 15) / 16) * 16;
    if (name == "opencv-bm") {
        // OpenCV's StereoBM defaults apart from the block size, which was chosen
        // from 5..21 on the shared scenes (docs/scoring.md).
        s.block_size = 11;
        s.pre_filter_cap = 31;
        s.texture_threshold = 10;
        s.uniqueness_ratio = 15;
        s.disp12_max_diff = -1;
    } else if (name == "opencv-sgbm") {
        // The settings of OpenCV's samples/cpp/stereo_match.cpp for grey input
        // (block size 3), with the speckle range the OpenCV docs recommend.
        s.block_size = 3;
        s.p1 = 8 * s.block_size * s.block_size;
        s.p2 = 32 * s.block_size * s.block_size;
        s.pre_filter_cap = 63;
        s.uniqueness_ratio = 10;
        s.speckle_window = 100;
        s.speckle_range = 2;
        s.disp12_max_diff = 1;
    } else {
        throw std::invalid_argument("unknown OpenCV matcher '" + name + "'");
    }
    return s;
}

cv::Mat run_matcher(const std::string& name, const Scene& sc, const g::Params& p, double* seconds) {
    if (sc.left.type() != CV_8UC1 || sc.right.type() != CV_8UC1 ||
        sc.left.size() != sc.right.size())
        throw InputError("scene '" + sc.name + "': left and right must be grey images of one size");
    const int W = sc.left.cols, H = sc.left.rows;

    if (name == "golden") {
        g::Params q = p;
        q.frame = g::Frame::Left;
        const g::Roi roi{0, 0, W, H};
        g::validate(q, roi, W, H);
        const auto t0 = Clock::now();
        g::DisparityMap m = g::compute(q, view_of(sc.left), view_of(sc.right), roi, true);
        if (seconds) *seconds = since(t0);
        return cv::Mat(m.height, m.width, CV_8UC1, m.data.data()).clone();
    }

    const OpenCvSettings s = opencv_settings(name, p.D);
    cv::Mat d16;
    double secs = 0;
    try {
        SingleThreaded one;
        if (name == "opencv-bm") {
            cv::Ptr<cv::StereoBM> bm = cv::StereoBM::create(s.num_disparities, s.block_size);
            bm->setPreFilterCap(s.pre_filter_cap);
            bm->setTextureThreshold(s.texture_threshold);
            bm->setUniquenessRatio(s.uniqueness_ratio);
            bm->setDisp12MaxDiff(s.disp12_max_diff);
            const auto t0 = Clock::now();
            bm->compute(sc.left, sc.right, d16);
            cv::Mat out = from_fixed_point(d16);
            secs = since(t0);
            if (seconds) *seconds = secs;
            return out;
        }
        cv::Ptr<cv::StereoSGBM> sgbm = cv::StereoSGBM::create(
            0, s.num_disparities, s.block_size, s.p1, s.p2, s.disp12_max_diff, s.pre_filter_cap,
            s.uniqueness_ratio, s.speckle_window, s.speckle_range, cv::StereoSGBM::MODE_SGBM);
        const auto t0 = Clock::now();
        sgbm->compute(sc.left, sc.right, d16);
        cv::Mat out = from_fixed_point(d16);
        secs = since(t0);
        if (seconds) *seconds = secs;
        return out;
    } catch (const cv::Exception& e) {
        std::string what = e.what();
        if (const auto nl = what.find('\n'); nl != std::string::npos) what.resize(nl);
        throw InputError("scene '" + sc.name + "': " + name + " failed (" + what + ")");
    }
}

}  // namespace imap::vision
