// Line plots drawn by gnuplot (pngcairo or svg terminal, chosen by the file
// name): series with markers, a legend, axis labels, optional log2 x / log10 y
// scales, dashed horizontal reference lines, a note, and labelled points
// (the knees of a sweep). Beside every plot NAME.png the gnuplot script
// NAME.gp and its data NAME.dat are written, so that it can be restyled and
// redrawn by hand (`cd FOLDER && gnuplot NAME.gp`).
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace imap::engine::plot {

struct Series {
    std::string label;      // legend text (empty: no legend entry)
    std::vector<double> x;  // same length as y
    std::vector<double> y;
    // The bound of another series (its index): drawn as a dashed line in
    // that series' colour, without points.
    int bound_of = -1;
    // Points without lines (a scatter). `size`, when it has one value per
    // point, is each point's size (gnuplot `ps variable`, third data column).
    bool scatter = false;
    std::vector<double> size{};
};

struct HLine {
    double y = 0;
    std::string label;
};

// A marked point with a text beside it.
struct Annotation {
    double x = 0, y = 0;
    std::string text;
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
    std::vector<Annotation> annotations;
    std::string note;  // top-left corner of the plot area
    std::string key;   // gnuplot `set key` placement ("below", ...); empty: automatic
    int width = 900, height = 600;
};

// The data file of a figure: one gnuplot data block per series ("x y" lines,
// "x y size" for a scatter with sizes; blocks separated by two blank lines,
// each headed by a comment naming it).
std::string data_text(const Figure& f);
// The gnuplot script: reads `data_name`, writes `out_name` with the terminal
// of its extension (.png: pngcairo, .svg: svg); both may be overridden with
// gnuplot -e "datafile='...'; outfile='...'". Throws std::invalid_argument
// when there is nothing to draw or a log scale gets a value <= 0.
std::string script_text(const Figure& f, const std::string& data_name, const std::string& out_name);

// Checks, before any work, that a plot can be made at `path`: the extension
// is .png or .svg and gnuplot is on PATH. engine::Error (exit 2) naming `flag`.
void check_plot_path(const std::string& flag, const std::string& path);

// Writes NAME.gp and NAME.dat beside `path`, runs gnuplot, and moves the
// picture into place only when gnuplot succeeded. engine::Error with
// gnuplot's message otherwise.
void write_plot(const Figure& f, const std::string& path);

// The script and data files that write_plot puts beside `path`.
std::string script_path(const std::string& path);
std::string data_path(const std::string& path);

}  // namespace imap::engine::plot
