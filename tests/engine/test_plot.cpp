// gnuplot plots: the script and data the engine writes (its own text, so
// exact), and the pictures gnuplot draws from them, checked only for what
// does not depend on the gnuplot / cairo version: the file type and the
// picture size from the PNG header, SVG markup.
#define BOOST_TEST_MODULE engine_plot
#include <boost/test/unit_test.hpp>
#include <cmath>
#include <stdexcept>

#include "engine_test_util.hpp"
#include "imap/engine/error.hpp"
#include "imap/engine/plot.hpp"

namespace plot = imap::engine::plot;
namespace fs = std::filesystem;
using enginetest::slurp;
using enginetest::tmpdir;

using enginetest::Cleanup;
BOOST_TEST_GLOBAL_FIXTURE(Cleanup);

namespace {

plot::Figure figure() {
    plot::Figure f;
    f.title = "Modeled \"time\"";
    f.subtitle = "a_b";  // underscores stay literal (noenhanced)
    f.xlabel = "PEs";
    f.ylabel = "ms";
    f.logx = true;
    f.xticks = {16, 32, 64};
    f.series = {{"mem=1024", {16, 32, 64}, {4, 2, 1.5}}, {"", {16, 32}, {8, 4}}};
    f.hlines = {{40, "video rate"}};
    f.annotations = {{32, 2, "knee: beyond 32"}};
    f.note = "1 point not shown";
    f.width = 640;
    f.height = 480;
    return f;
}

// Width and height from a PNG's IHDR chunk (bytes 16..23, big endian).
std::pair<uint32_t, uint32_t> png_size(const std::string& b) {
    auto be = [&](size_t o) {
        return (static_cast<uint32_t>(static_cast<unsigned char>(b[o])) << 24) |
               (static_cast<uint32_t>(static_cast<unsigned char>(b[o + 1])) << 16) |
               (static_cast<uint32_t>(static_cast<unsigned char>(b[o + 2])) << 8) |
               static_cast<uint32_t>(static_cast<unsigned char>(b[o + 3]));
    };
    return {be(16), be(20)};
}

}  // namespace

BOOST_AUTO_TEST_CASE(script_and_data) {
    const plot::Figure f = figure();
    const std::string d = plot::data_text(f);
    BOOST_TEST(
        d.find(
            "# index 0: mem=1024\n16 4\n32 2\n64 1.5\n\n\n# index 1: (no label)\n16 8\n32 4\n") !=
            std::string::npos,
        d);
    const std::string s = plot::script_text(f, "x.dat", "x.png");
    for (const char* want :
         {"datafile = \"x.dat\"", "outfile = \"x.png\"", "set terminal pngcairo size 640,480",
          "set terminal svg size 640,480", "set termoption noenhanced", "set logscale x 2",
          "set title \"Modeled \\\"time\\\"\\na_b\"", "set xtics (\"16\" 16, \"32\" 32, \"64\" 64)",
          "\"video rate\"", "\"knee: beyond 32\" at first 32, first 2", "\"1 point not shown\"",
          "datafile index 0 using 1:2 with linespoints", "title \"mem=1024\"", "notitle"})
        BOOST_TEST(s.find(want) != std::string::npos, want);
    BOOST_TEST(s.find("set logscale y") == std::string::npos);

    plot::Figure empty;
    BOOST_CHECK_THROW(plot::script_text(empty, "a", "b"), std::invalid_argument);
    plot::Figure neg = f;
    neg.series[0].x[0] = 0;
    BOOST_CHECK_THROW(plot::script_text(neg, "a", "b"), std::invalid_argument);
}

BOOST_AUTO_TEST_CASE(png_and_svg_are_drawn) {
    const fs::path png = tmpdir() / "f.png", svg = tmpdir() / "f.svg";
    plot::write_plot(figure(), png.string());
    const std::string b = slurp(png);
    BOOST_REQUIRE(b.size() > 24);
    BOOST_TEST(b.substr(1, 3) == "PNG");
    BOOST_TEST(png_size(b).first == 640u);
    BOOST_TEST(png_size(b).second == 480u);
    BOOST_TEST(fs::exists(tmpdir() / "f.gp"));
    BOOST_TEST(fs::exists(tmpdir() / "f.dat"));
    plot::write_plot(figure(), svg.string());
    const std::string x = slurp(svg);
    BOOST_TEST(x.find("<svg") != std::string::npos);
    BOOST_TEST(x.find("viewBox=\"0 0 640 480\"") != std::string::npos);
    // No temporary picture is left behind.
    for (const auto& e : fs::directory_iterator(tmpdir()))
        BOOST_TEST(e.path().filename().string().find(".tmp-") == std::string::npos);
}

BOOST_AUTO_TEST_CASE(bad_names_are_refused_before_the_work) {
    BOOST_CHECK_THROW(plot::check_plot_path("--plot", "a.jpg"), imap::engine::Error);
    BOOST_CHECK_THROW(plot::check_plot_path("--plot", "noext"), imap::engine::Error);
    BOOST_CHECK_NO_THROW(plot::check_plot_path("--plot", "A.PNG"));
    BOOST_CHECK_NO_THROW(plot::check_plot_path("--plot", "a.svg"));
}
