#include "plot.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <opencv2/imgproc.hpp>
#include <stdexcept>

namespace imapsim::plot {

namespace {

const cv::Scalar kBlack(0, 0, 0), kGrid(225, 225, 225), kAxis(60, 60, 60);
// Distinguishable colours (BGR).
const cv::Scalar kPalette[] = {{180, 119, 31},  {14, 127, 255}, {44, 160, 44},   {40, 39, 214},
                               {189, 103, 148}, {75, 86, 140},  {194, 119, 227}, {127, 127, 127},
                               {34, 189, 188},  {207, 190, 23}};
constexpr int kFont = cv::FONT_HERSHEY_SIMPLEX;

std::string num(double v) {
    char b[32];
    if (v != 0 && (std::fabs(v) >= 1e6 || std::fabs(v) < 1e-3))
        std::snprintf(b, sizeof b, "%.3g", v);
    else
        std::snprintf(b, sizeof b, "%.6g", v);
    return b;
}

cv::Size text_size(const std::string& s, double scale, int thick = 1) {
    int base = 0;
    return cv::getTextSize(s, kFont, scale, thick, &base);
}

void text(cv::Mat& img, const std::string& s, cv::Point p, double scale,
          const cv::Scalar& c = kBlack, int thick = 1) {
    cv::putText(img, s, p, kFont, scale, c, thick, cv::LINE_AA);
}

void dashed(cv::Mat& img, cv::Point a, cv::Point b, const cv::Scalar& c, int thick, int on,
            int off) {
    const double len = std::hypot(b.x - a.x, b.y - a.y);
    if (len <= 0) return;
    for (double t = 0; t < len; t += on + off) {
        const double t1 = std::min(len, t + on);
        cv::line(img, a + cv::Point(cvRound((b.x - a.x) * t / len), cvRound((b.y - a.y) * t / len)),
                 a + cv::Point(cvRound((b.x - a.x) * t1 / len), cvRound((b.y - a.y) * t1 / len)), c,
                 thick, cv::LINE_AA);
    }
}

void marker(cv::Mat& img, cv::Point p, int kind, const cv::Scalar& c) {
    const int r = 5;
    switch (kind % 4) {
        case 0:
            cv::circle(img, p, r, c, cv::FILLED, cv::LINE_AA);
            break;
        case 1:
            cv::rectangle(img, p - cv::Point(r - 1, r - 1), p + cv::Point(r - 1, r - 1), c,
                          cv::FILLED, cv::LINE_AA);
            break;
        case 2: {
            std::vector<cv::Point> t = {p + cv::Point(0, -r - 1), p + cv::Point(r + 1, r),
                                        p + cv::Point(-r - 1, r)};
            cv::fillConvexPoly(img, t, c, cv::LINE_AA);
            break;
        }
        default: {
            std::vector<cv::Point> d = {p + cv::Point(0, -r - 1), p + cv::Point(r + 1, 0),
                                        p + cv::Point(0, r + 1), p + cv::Point(-r - 1, 0)};
            cv::fillConvexPoly(img, d, c, cv::LINE_AA);
        }
    }
}

// Ticks on a log10 axis: 1-2-5 per decade, or decades only when wide.
std::vector<double> log10_ticks(double lo, double hi) {
    std::vector<double> t;
    const int d0 = static_cast<int>(std::floor(std::log10(lo))) - 1;
    const int d1 = static_cast<int>(std::ceil(std::log10(hi))) + 1;
    const bool decades_only = d1 - d0 > 6;
    for (int d = d0; d <= d1; ++d)
        for (double m : {1.0, 2.0, 5.0}) {
            if (decades_only && m != 1.0) continue;
            const double v = m * std::pow(10.0, d);
            if (v >= lo * (1 - 1e-9) && v <= hi * (1 + 1e-9)) t.push_back(v);
        }
    return t;
}

std::vector<double> log2_ticks(double lo, double hi) {
    std::vector<double> t;
    const int e0 = static_cast<int>(std::ceil(std::log2(lo) - 1e-9));
    const int e1 = static_cast<int>(std::floor(std::log2(hi) + 1e-9));
    const int step = std::max(1, (e1 - e0 + 1 + 11) / 12);
    for (int e = e0; e <= e1; e += step) t.push_back(std::ldexp(1.0, e));
    return t;
}

}  // namespace

std::vector<double> linear_ticks(double lo, double hi, int target) {
    std::vector<double> t;
    if (!(hi > lo)) return {lo};
    const double raw = (hi - lo) / std::max(1, target);
    const double mag = std::pow(10.0, std::floor(std::log10(raw)));
    double step = mag;
    for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
        if (m * mag >= raw) {
            step = m * mag;
            break;
        }
    for (double v = std::ceil(lo / step - 1e-9) * step; v <= hi + step * 1e-9; v += step)
        t.push_back(std::fabs(v) < step * 1e-9 ? 0.0 : v);
    return t;
}

cv::Mat render(const Figure& f) {
    std::vector<double> xs, ys;
    for (const Series& s : f.series) {
        if (s.x.size() != s.y.size()) throw std::invalid_argument("plot: series x/y size differ");
        xs.insert(xs.end(), s.x.begin(), s.x.end());
        ys.insert(ys.end(), s.y.begin(), s.y.end());
    }
    if (xs.empty()) throw std::invalid_argument("plot: no points to draw");
    for (const HLine& h : f.hlines) ys.push_back(h.y);
    for (const auto& [p, l] : f.xcategories) xs.push_back(p);
    if (f.logx && *std::min_element(xs.begin(), xs.end()) <= 0)
        throw std::invalid_argument("plot: log x scale needs x > 0");
    if (f.logy && *std::min_element(ys.begin(), ys.end()) <= 0)
        throw std::invalid_argument("plot: log y scale needs y > 0");

    auto tx = [&](double v) { return f.logx ? std::log2(v) : v; };
    auto ty = [&](double v) { return f.logy ? std::log10(v) : v; };
    double x0 = tx(*std::min_element(xs.begin(), xs.end()));
    double x1 = tx(*std::max_element(xs.begin(), xs.end()));
    double y0 = ty(*std::min_element(ys.begin(), ys.end()));
    double y1 = ty(*std::max_element(ys.begin(), ys.end()));
    if (x1 - x0 < 1e-12) {
        x0 -= 0.5;
        x1 += 0.5;
    }
    if (y1 - y0 < 1e-12) {
        y0 -= f.logy ? 0.1 : std::max(0.5, std::fabs(y0) * 0.1);
        y1 += f.logy ? 0.1 : std::max(0.5, std::fabs(y1) * 0.1);
    }
    if (!f.logy && y0 > 0 && y0 < (y1 - y0) * 0.5) y0 = 0;  // start linear time axes at 0
    const double px = (x1 - x0) * 0.05, py = (y1 - y0) * 0.07;
    x0 -= px;
    x1 += px;
    if (f.logy || y0 != 0) y0 -= py;
    y1 += py;

    // Layout.
    size_t legend_n = 0;
    int legend_w = 0;
    for (const Series& s : f.series)
        if (!s.label.empty()) {
            ++legend_n;
            legend_w = std::max(legend_w, text_size(s.label, 0.45).width);
        }
    const int W = f.width, H = f.height;
    const int left = 78, top = f.subtitle.empty() ? 44 : 62, bottom = 58;
    const int right = legend_n ? std::min(W / 3, legend_w + 56) : 24;
    const cv::Rect area(left, top, W - left - right, H - top - bottom);
    if (area.width < 50 || area.height < 50)
        throw std::invalid_argument("plot: the image is too small");
    cv::Mat img(H, W, CV_8UC3, cv::Scalar(255, 255, 255));
    auto X = [&](double v) { return cvRound(area.x + (tx(v) - x0) / (x1 - x0) * area.width); };
    auto Y = [&](double v) {
        return cvRound(area.y + area.height - (ty(v) - y0) / (y1 - y0) * area.height);
    };

    // Ticks and grid.
    std::vector<std::pair<double, std::string>> xt;
    if (!f.xcategories.empty()) {
        xt = f.xcategories;
    } else if (!f.xticks.empty()) {
        for (double v : f.xticks) xt.emplace_back(v, num(v));
    } else {
        const double lo = f.logx ? std::exp2(x0) : x0, hi = f.logx ? std::exp2(x1) : x1;
        for (double v : f.logx ? log2_ticks(lo, hi) : linear_ticks(lo, hi, 8))
            xt.emplace_back(v, num(v));
    }
    std::vector<double> ytv;
    if (f.logy) {
        ytv = log10_ticks(std::pow(10.0, y0), std::pow(10.0, y1));
        if (ytv.size() < 2) ytv = linear_ticks(std::pow(10.0, y0), std::pow(10.0, y1), 4);
    } else {
        ytv = linear_ticks(y0, y1, 8);
    }
    int last_label_end = -1000;
    for (const auto& [v, l] : xt) {
        const int x = X(v);
        if (x < area.x - 1 || x > area.x + area.width + 1) continue;
        cv::line(img, {x, area.y}, {x, area.y + area.height}, kGrid, 1);
        cv::line(img, {x, area.y + area.height}, {x, area.y + area.height + 5}, kAxis, 1);
        const cv::Size ts = text_size(l, 0.42);
        if (x - ts.width / 2 > last_label_end + 6) {
            text(img, l, {x - ts.width / 2, area.y + area.height + 20}, 0.42);
            last_label_end = x + ts.width / 2;
        }
    }
    for (double v : ytv) {
        const int y = Y(v);
        if (y < area.y - 1 || y > area.y + area.height + 1) continue;
        cv::line(img, {area.x, y}, {area.x + area.width, y}, kGrid, 1);
        cv::line(img, {area.x - 5, y}, {area.x, y}, kAxis, 1);
        const std::string l = num(v);
        const cv::Size ts = text_size(l, 0.42);
        text(img, l, {area.x - 8 - ts.width, y + ts.height / 2}, 0.42);
    }
    cv::rectangle(img, area, kAxis, 1);

    // Reference lines.
    for (const HLine& h : f.hlines) {
        const int y = Y(h.y);
        dashed(img, {area.x, y}, {area.x + area.width, y}, cv::Scalar(70, 70, 200), 1, 9, 6);
        const cv::Size ts = text_size(h.label, 0.42);
        text(img, h.label, {area.x + area.width - ts.width - 6, y - 5}, 0.42,
             cv::Scalar(70, 70, 200));
    }

    // Series.
    for (size_t k = 0; k < f.series.size(); ++k) {
        const Series& s = f.series[k];
        const cv::Scalar c = kPalette[k % (sizeof kPalette / sizeof kPalette[0])];
        std::vector<size_t> order(s.x.size());
        std::iota(order.begin(), order.end(), 0);
        std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return s.x[a] < s.x[b]; });
        for (size_t i = 1; i < order.size(); ++i)
            cv::line(img, {X(s.x[order[i - 1]]), Y(s.y[order[i - 1]])},
                     {X(s.x[order[i]]), Y(s.y[order[i]])}, c, 2, cv::LINE_AA);
        for (size_t i : order) marker(img, {X(s.x[i]), Y(s.y[i])}, static_cast<int>(k), c);
    }

    // Legend (right of the plot area).
    if (legend_n) {
        int y = area.y + 8;
        const int x = area.x + area.width + 14;
        for (size_t k = 0; k < f.series.size(); ++k) {
            const Series& s = f.series[k];
            if (s.label.empty()) continue;
            if (y > area.y + area.height - 10) {
                text(img, "...", {x, y + 4}, 0.45);
                break;
            }
            const cv::Scalar c = kPalette[k % (sizeof kPalette / sizeof kPalette[0])];
            cv::line(img, {x, y}, {x + 24, y}, c, 2, cv::LINE_AA);
            marker(img, {x + 12, y}, static_cast<int>(k), c);
            text(img, s.label, {x + 32, y + 5}, 0.45);
            y += 22;
        }
    }

    // Titles and labels.
    text(img, f.title, {left, 24}, 0.6, kBlack, 1);
    if (!f.subtitle.empty()) text(img, f.subtitle, {left, 46}, 0.45, cv::Scalar(80, 80, 80));
    {
        const cv::Size ts = text_size(f.xlabel, 0.5);
        text(img, f.xlabel, {area.x + (area.width - ts.width) / 2, H - 14}, 0.5);
    }
    if (!f.ylabel.empty()) {
        const cv::Size ts = text_size(f.ylabel, 0.5);
        cv::Mat lab(ts.height + 10, ts.width + 4, CV_8UC3, cv::Scalar(255, 255, 255));
        text(lab, f.ylabel, {2, ts.height + 3}, 0.5);
        cv::Mat rot;
        cv::rotate(lab, rot, cv::ROTATE_90_COUNTERCLOCKWISE);
        const int yy = std::max(0, area.y + (area.height - rot.rows) / 2);
        if (rot.rows <= H - yy && rot.cols <= W)
            rot.copyTo(img(cv::Rect(6, yy, rot.cols, rot.rows)));
    }
    if (!f.note.empty()) {
        const cv::Size ts = text_size(f.note, 0.42);
        const cv::Rect box(area.x + 6, area.y + 6, ts.width + 10, ts.height + 10);
        cv::rectangle(img, box, cv::Scalar(255, 255, 255), cv::FILLED);
        cv::rectangle(img, box, cv::Scalar(180, 180, 180), 1);
        text(img, f.note, {box.x + 5, box.y + ts.height + 4}, 0.42, cv::Scalar(60, 60, 60));
    }
    return img;
}

}  // namespace imapsim::plot
