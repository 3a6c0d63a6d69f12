#include "imap/vision/colour.hpp"

#include <algorithm>
#include <array>
#include <opencv2/imgproc.hpp>
#include <stdexcept>
#include <string>

namespace imap::vision {

namespace {

constexpr int kBarRows = 10, kTextRows = 12;

// COLORMAP_JET of every level 0..255, from OpenCV once.
const std::array<cv::Vec3b, 256>& jet() {
    static const std::array<cv::Vec3b, 256> table = [] {
        cv::Mat ramp(1, 256, CV_8UC1), colour;
        for (int i = 0; i < 256; ++i) ramp.at<uint8_t>(0, i) = static_cast<uint8_t>(i);
        cv::applyColorMap(ramp, colour, cv::COLORMAP_JET);
        std::array<cv::Vec3b, 256> t{};
        for (int i = 0; i < 256; ++i) t[static_cast<size_t>(i)] = colour.at<cv::Vec3b>(0, i);
        return t;
    }();
    return table;
}

int level(int d, int D) {
    return D > 1 ? (255 * d + (D - 1) / 2) / (D - 1) : 0;
}

}  // namespace

cv::Vec3b disparity_colour(int d, int D) {
    if (D < 1 || D > 255) throw std::invalid_argument("disparity_colour: D must be 1..255");
    if (d == 255) return kOccludedColour;
    if (d < 0 || d >= D)
        throw std::invalid_argument("disparity_colour: disparity " + std::to_string(d) +
                                    " outside 0.." + std::to_string(D - 1) + " and not 255");
    return jet()[static_cast<size_t>(level(d, D))];
}

cv::Mat colorize_disparity(const cv::Mat& disp, int D) {
    if (disp.type() != CV_8UC1)
        throw std::invalid_argument("colorize_disparity: the map must be CV_8UC1");
    std::array<cv::Vec3b, 256> lut{};
    for (int v = 0; v < 256; ++v)
        lut[static_cast<size_t>(v)] = v == 255 ? kOccludedColour
                                      : v < D  ? disparity_colour(v, D)
                                               : cv::Vec3b(128, 128, 128);  // cannot happen
    cv::Mat out(disp.size(), CV_8UC3);
    for (int y = 0; y < disp.rows; ++y) {
        const uint8_t* s = disp.ptr<uint8_t>(y);
        cv::Vec3b* o = out.ptr<cv::Vec3b>(y);
        for (int x = 0; x < disp.cols; ++x) o[x] = lut[s[x]];
    }
    return out;
}

int legend_height() {
    return kBarRows + kTextRows;
}

cv::Mat disparity_legend(int width, int D) {
    if (width < 1) throw std::invalid_argument("disparity_legend: width must be >= 1");
    cv::Mat out(legend_height(), width, CV_8UC3, cv::Scalar(0, 0, 0));
    // The occlusion box takes the right end (a fifth of the width, 8..24 px).
    const int box = std::min(std::max(width / 5, 8), std::max(width / 2, 1));
    const int bar = std::max(width - box - 2, 1);
    for (int x = 0; x < bar; ++x) {
        const int d = bar > 1 ? (x * (D - 1) + (bar - 1) / 2) / (bar - 1) : 0;
        out(cv::Rect(x, 0, 1, kBarRows)).setTo(cv::Scalar(disparity_colour(d, D)));
    }
    if (bar + 2 < width)
        out(cv::Rect(bar + 2, 0, width - bar - 2, kBarRows)).setTo(cv::Scalar(kOccludedColour));
    const cv::Scalar ink(255, 255, 255);
    const int font = cv::FONT_HERSHEY_PLAIN;
    const double scale = 0.7;
    const int base = legend_height() - 2;
    cv::putText(out, "0", cv::Point(0, base), font, scale, ink, 1, cv::LINE_8);
    const std::string hi = std::to_string(D - 1);
    int baseline = 0;
    const cv::Size hs = cv::getTextSize(hi, font, scale, 1, &baseline);
    cv::putText(out, hi, cv::Point(std::max(bar - hs.width, 0), base), font, scale, ink, 1,
                cv::LINE_8);
    if (bar + 2 < width) {
        const cv::Size os = cv::getTextSize("occl", font, scale, 1, &baseline);
        if (os.width <= width - bar)
            cv::putText(out, "occl", cv::Point(width - os.width, base), font, scale, ink, 1,
                        cv::LINE_8);
    }
    return out;
}

}  // namespace imap::vision
