#include "imap/engine/plot.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "imap/engine/error.hpp"
#include "imap/engine/process.hpp"
#include "imap/engine/run_dir.hpp"

namespace imap::engine::plot {

namespace fs = std::filesystem;

namespace {

std::string num(double v) {
    char b[40];
    std::snprintf(b, sizeof b, "%.10g", v);
    return b;
}

// A gnuplot double-quoted string.
std::string quoted(const std::string& s) {
    std::string q = "\"";
    for (char c : s) {
        if (c == '"' || c == '\\')
            q += std::string("\\") + c;
        else if (c == '\n')
            q += "\\n";
        else
            q += c;
    }
    return q + "\"";
}

std::string lower_ext(const std::string& path) {
    std::string e = fs::path(path).extension().string();
    for (char& c : e) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return e;
}

}  // namespace

std::string script_path(const std::string& path) {
    return (fs::path(path).parent_path() / (fs::path(path).stem().string() + ".gp")).string();
}

std::string data_path(const std::string& path) {
    return (fs::path(path).parent_path() / (fs::path(path).stem().string() + ".dat")).string();
}

std::string data_text(const Figure& f) {
    std::ostringstream o;
    o << "# data of " << quoted(f.title) << ": one block per series (gnuplot index), columns x y\n";
    for (size_t i = 0; i < f.series.size(); ++i) {
        const Series& s = f.series[i];
        if (i) o << "\n\n";
        o << "# index " << i << ": " << (s.label.empty() ? "(no label)" : s.label) << "\n";
        const bool sized = s.size.size() == s.x.size();
        for (size_t k = 0; k < s.x.size() && k < s.y.size(); ++k)
            o << num(s.x[k]) << " " << num(s.y[k]) << (sized ? " " + num(s.size[k]) : std::string())
              << "\n";
    }
    return o.str();
}

std::string script_text(const Figure& f, const std::string& data_name,
                        const std::string& out_name) {
    double xmin = INFINITY, xmax = -INFINITY, ymin = INFINITY, ymax = -INFINITY;
    size_t points = 0;
    for (const Series& s : f.series) {
        if (s.x.size() != s.y.size())
            throw std::invalid_argument("plot: series x and y differ in size");
        for (size_t k = 0; k < s.x.size(); ++k) {
            if (!std::isfinite(s.x[k]) || !std::isfinite(s.y[k]))
                throw std::invalid_argument("plot: a value is not finite");
            if (f.logx && s.x[k] <= 0) throw std::invalid_argument("plot: log x scale needs x > 0");
            if (f.logy && s.y[k] <= 0) throw std::invalid_argument("plot: log y scale needs y > 0");
            xmin = std::min(xmin, s.x[k]);
            xmax = std::max(xmax, s.x[k]);
            ymin = std::min(ymin, s.y[k]);
            ymax = std::max(ymax, s.y[k]);
            ++points;
        }
    }
    if (points == 0) throw std::invalid_argument("plot: nothing to draw");
    for (const HLine& h : f.hlines) {
        if (f.logy && h.y <= 0) continue;
        ymin = std::min(ymin, h.y);
        ymax = std::max(ymax, h.y);
    }
    double ylo, yhi, xlo, xhi;
    if (f.logy) {
        ylo = ymin / 1.6;
        yhi = ymax * 1.6;
    } else {
        const double span = ymax > ymin ? ymax - ymin : std::max(1.0, std::fabs(ymax));
        ylo = ymin - 0.06 * span;
        yhi = ymax + 0.08 * span;
        if (ymin >= 0 && ylo < 0) ylo = 0;
    }
    if (!f.xcategories.empty()) {
        xlo = -0.5;
        xhi = static_cast<double>(f.xcategories.size()) - 0.5;
        for (const auto& [x, l] : f.xcategories) {
            xlo = std::min(xlo, x - 0.5);
            xhi = std::max(xhi, x + 0.5);
        }
    } else if (f.logx) {
        xlo = xmin / 1.25;
        xhi = xmax * 1.25;
    } else {
        const double span = xmax > xmin ? xmax - xmin : std::max(1.0, std::fabs(xmax));
        xlo = xmin - 0.04 * span;
        xhi = xmax + 0.04 * span;
    }

    std::ostringstream o;
    o << "# imapsim plot: " << f.title << "\n"
      << "# Redraw or restyle: cd to this folder and run gnuplot on this file; another output:\n"
      << "#   gnuplot -e \"outfile='plot.svg'\" THIS.gp   (.png: pngcairo, .svg: svg)\n"
      << "if (!exists(\"datafile\")) datafile = " << quoted(data_name) << "\n"
      << "if (!exists(\"outfile\")) outfile = " << quoted(out_name) << "\n"
      << "if (strlen(outfile) > 4 && outfile[strlen(outfile)-3:] eq \".svg\") {\n"
      << "    set terminal svg size " << f.width << "," << f.height
      << " dynamic font \"sans,11\" background rgb \"white\"\n"
      << "} else {\n"
      << "    set terminal pngcairo size " << f.width << "," << f.height
      << " font \"sans,10\" background rgb \"white\"\n"
      << "}\n"
      << "set output outfile\n"
      << "set termoption noenhanced\n"
      << "set encoding utf8\n"
      << "set style textbox opaque noborder\n";
    o << "set title " << quoted(f.subtitle.empty() ? f.title : f.title + "\n" + f.subtitle) << "\n";
    o << "set xlabel " << quoted(f.xlabel) << "\n";
    o << "set ylabel " << quoted(f.ylabel) << "\n";
    o << "set grid xtics ytics mxtics mytics lc rgb \"#dddddd\" lt 1, lc rgb \"#eeeeee\" lt 1\n";
    o << "set border 3 lc rgb \"#444444\"\nset tics nomirror\n";
    if (f.logx) o << "set logscale x 2\n";
    if (f.logy) o << "set logscale y 10\n";
    o << "set xrange [" << num(xlo) << ":" << num(xhi) << "]\n";
    o << "set yrange [" << num(ylo) << ":" << num(yhi) << "]\n";
    if (!f.xcategories.empty()) {
        o << "set xtics (";
        for (size_t i = 0; i < f.xcategories.size(); ++i)
            o << (i ? ", " : "") << quoted(f.xcategories[i].second) << " "
              << num(f.xcategories[i].first);
        o << ")\n";
    } else if (!f.xticks.empty()) {
        o << "set xtics (";
        for (size_t i = 0; i < f.xticks.size(); ++i)
            o << (i ? ", " : "") << quoted(num(f.xticks[i])) << " " << num(f.xticks[i]);
        o << ")\n";
    }
    const bool labelled = std::any_of(f.series.begin(), f.series.end(),
                                      [](const Series& s) { return !s.label.empty(); });
    o << (!labelled             ? "unset key\n"
          : !f.key.empty()      ? "set key " + f.key + "\n"
          : f.series.size() > 5 ? "set key outside right top vertical\n"
                                : "set key top right box opaque samplen 2 width 1 height 0.5\n");
    int tag = 1;
    for (const HLine& h : f.hlines) {
        if (f.logy && h.y <= 0) continue;
        o << "set arrow " << tag << " from graph 0, first " << num(h.y) << " to graph 1, first "
          << num(h.y) << " nohead dt 2 lw 1.5 lc rgb \"#888888\"\n";
        o << "set label " << tag << " " << quoted(h.label) << " at graph 0.01, first " << num(h.y)
          << " left offset 0,0.7 textcolor rgb \"#666666\"\n";
        ++tag;
    }
    if (!f.note.empty())
        o << "set label " << tag++ << " " << quoted(f.note)
          << " at graph 0.01, graph 0.03 left front textcolor rgb \"#444444\"\n";
    for (const Annotation& a : f.annotations) {
        o << "set label " << tag++ << " " << quoted(a.text) << " at first " << num(a.x)
          << ", first " << num(a.y)
          << " left front point pt 6 ps 3 lw 2 lc rgb \"#d62728\" offset 1.5,1.5 "
             "textcolor rgb \"#b01010\"\n";
    }
    o << "plot ";
    for (size_t i = 0; i < f.series.size(); ++i) {
        const Series& s = f.series[i];
        const bool sized = s.scatter && !s.size.empty() && s.size.size() == s.x.size();
        o << (i ? ", \\\n     " : "") << "datafile index " << i << " using 1:2"
          << (sized ? ":3" : "") << " with ";
        if (s.scatter)
            o << "points pt 7 lt " << i + 1 << (sized ? " ps variable " : " ps 1.5 ");
        else if (s.bound_of >= 0)
            o << "lines lw 1.5 dt 2 lt " << s.bound_of + 1 << " ";
        else
            o << "linespoints lw 2 lt " << i + 1 << " pt "
              << (i % 4 == 0   ? 7
                  : i % 4 == 1 ? 5
                  : i % 4 == 2 ? 9
                               : 11)
              << " ps 1.3 ";
        o << (s.label.empty() ? std::string("notitle") : "title " + quoted(s.label));
    }
    o << "\n";
    return o.str();
}

void check_plot_path(const std::string& flag, const std::string& path) {
    if (path.empty()) return;
    const std::string e = lower_ext(path);
    if (e != ".png" && e != ".svg")
        throw Error(flag + " '" + path +
                    "': the plot is PNG (pngcairo) or SVG: use a name ending in "
                    ".png or .svg");
    if (!on_path("gnuplot"))
        throw Error(flag + " '" + path +
                    "': gnuplot is not on PATH (Debian package gnuplot-nox, installed by "
                    "scripts/install-deps.sh)");
}

void write_plot(const Figure& f, const std::string& path) {
    check_plot_path("plot", path);
    const fs::path p(path);
    const fs::path gp = script_path(path), dat = data_path(path);
    std::string script;
    try {
        script = script_text(f, dat.filename().string(), p.filename().string());
    } catch (const std::invalid_argument& e) {
        throw Error(path + ": " + e.what(), kExitInternal);
    }
    write_file_atomic(dat, data_text(f));
    write_file_atomic(gp, script);
    const fs::path tmp = p.parent_path() / ("." + p.stem().string() + ".tmp-" +
                                            std::to_string(::getpid()) + p.extension().string());
    std::error_code ec;
    const std::string abs_dat = fs::absolute(dat, ec).string();
    const std::string abs_tmp = fs::absolute(tmp, ec).string();
    const Captured c = run_capture(
        {"gnuplot", "-e", "datafile='" + abs_dat + "'; outfile='" + abs_tmp + "'", gp.string()},
        120);
    if (c.exit_code != 0 || !fs::exists(tmp, ec) || fs::file_size(tmp, ec) == 0) {
        fs::remove(tmp, ec);
        std::string msg = c.output;
        while (!msg.empty() && (msg.back() == '\n' || msg.back() == ' ')) msg.pop_back();
        if (msg.size() > 400) msg = msg.substr(msg.size() - 400);
        throw Error("gnuplot could not draw " + path + " (script " + gp.string() +
                        "): " + (msg.empty() ? "exit " + std::to_string(c.exit_code) : msg),
                    kExitInternal);
    }
    fs::rename(tmp, p, ec);
    if (ec) {
        fs::remove(tmp, ec);
        throw Error("cannot move the plot into place at " + path + ": " + ec.message());
    }
}

}  // namespace imap::engine::plot
