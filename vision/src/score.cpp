#include "imap/vision/score.hpp"

#include <cmath>
#include <string>

#include "imap/vision/image_io.hpp"

namespace imap::vision {

namespace {

double pixel(const cv::Mat& m, int y, int x) {
    switch (m.depth()) {
        case CV_8U:
            return m.at<uint8_t>(y, x);
        case CV_16U:
            return m.at<uint16_t>(y, x);
        default:
            return m.at<float>(y, x);
    }
}

}  // namespace

BadScores score_bad(const cv::Mat& disp, double disp_scale, const Scene& sc, double delta) {
    const int t = disp.type();
    if (t != CV_8UC1 && t != CV_16UC1 && t != CV_32FC1)
        throw InputError("scene '" + sc.name +
                         "': disparity map must be 8-bit, 16-bit or float single-channel");
    if (disp.size() != sc.gt.size())
        throw InputError("scene '" + sc.name + "': disparity map is " + std::to_string(disp.cols) +
                         "x" + std::to_string(disp.rows) + " but the ground truth is " +
                         std::to_string(sc.gt.cols) + "x" + std::to_string(sc.gt.rows));
    if (!(disp_scale > 0) || !(sc.gt_scale > 0))
        throw InputError("scene '" + sc.name + "': disparity scales must be positive");

    const cv::Mat* masks[3] = {&sc.nonocc, &sc.all, &sc.disc};
    if (sc.gt.type() != CV_8UC1)
        throw InputError("scene '" + sc.name + "': ground truth must be 8-bit grey");
    for (const cv::Mat* m : masks)
        if (m->type() != CV_8UC1 || m->size() != sc.gt.size())
            throw InputError("scene '" + sc.name +
                             "': masks must be 8-bit grey and the size of the ground truth");
    size_t bad[3] = {0, 0, 0}, total[3] = {0, 0, 0};
    for (int y = 0; y < disp.rows; ++y) {
        const uint8_t* g = sc.gt.ptr<uint8_t>(y);
        for (int x = 0; x < disp.cols; ++x) {
            const double err = std::fabs(pixel(disp, y, x) / disp_scale - g[x] / sc.gt_scale);
            const bool is_bad = err > delta;
            for (int k = 0; k < 3; ++k) {
                if (masks[k]->at<uint8_t>(y, x) != 255) continue;
                ++total[k];
                bad[k] += is_bad;
            }
        }
    }
    auto pct = [](size_t b, size_t n) {
        return n == 0 ? 0.0 : 100.0 * static_cast<double>(b) / static_cast<double>(n);
    };
    return {pct(bad[0], total[0]), pct(bad[1], total[1]), pct(bad[2], total[2])};
}

BadScores score_bad_roi(const golden::DisparityMap& m, const Scene& sc, const golden::Roi& roi,
                        double delta) {
    const cv::Rect r(roi.x0, roi.y0, roi.w, roi.h);
    if (m.width != roi.w || m.height != roi.h || r.x < 0 || r.y < 0 || r.x + r.width > sc.gt.cols ||
        r.y + r.height > sc.gt.rows)
        throw InputError("scene '" + sc.name + "': the map or the ROI does not fit the scene");
    Scene c = sc;
    c.gt = sc.gt(r).clone();
    c.nonocc = sc.nonocc(r).clone();
    c.all = sc.all(r).clone();
    c.disc = sc.disc(r).clone();
    const cv::Mat disp(m.height, m.width, CV_8UC1, const_cast<uint8_t*>(m.data.data()));
    return score_bad(disp, 1.0, c, delta);
}

double bad_percent_roi(const golden::DisparityMap& m, const cv::Mat& gt, const golden::Roi& roi,
                       int delta) {
    if (m.data.empty()) return 0;
    size_t bad = 0;
    for (int y = 0; y < m.height; ++y)
        for (int x = 0; x < m.width; ++x) {
            const int d = m.at(x, y);
            const int t = gt.at<uint8_t>(roi.y0 + y, roi.x0 + x);
            bad += (d > t ? d - t : t - d) > delta;
        }
    return 100.0 * static_cast<double>(bad) / static_cast<double>(m.data.size());
}

}  // namespace imap::vision
