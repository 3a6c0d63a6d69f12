// A small line plot drawn with OpenCV (imapsim sweep --plot): series with
// markers, legend, axis labels and ticks, optional log2 x / log10 y scales,
// dashed horizontal reference lines and a note in the corner.
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <utility>
#include <vector>

namespace imapsim::plot {

struct Series {
    std::string label;      // legend text (empty: no legend entry)
    std::vector<double> x;  // same length as y
    std::vector<double> y;
};

struct HLine {
    double y = 0;
    std::string label;
};

struct Figure {
    std::string title, subtitle, xlabel, ylabel;
    bool logx = false;  // log2 x scale (all x > 0)
    bool logy = false;  // log10 y scale (all y > 0)
    // Categorical x: tick positions and their labels (x values are indices).
    std::vector<std::pair<double, std::string>> xcategories;
    // Numeric x ticks to use instead of automatic ones (e.g. the swept values).
    std::vector<double> xticks;
    std::vector<Series> series;
    std::vector<HLine> hlines;  // drawn dashed, included in the y range
    std::string note;           // top-left corner of the plot area
    int width = 900, height = 600;
};

// Renders the figure (CV_8UC3, white background). Throws std::invalid_argument
// when there is nothing to draw or a log scale gets a value <= 0.
cv::Mat render(const Figure& f);

// Tick values a plot axis would use for [lo, hi] (exposed for tests).
std::vector<double> linear_ticks(double lo, double hi, int target);

}  // namespace imapsim::plot
