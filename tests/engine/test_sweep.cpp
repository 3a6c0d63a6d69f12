// The sweep engine without running a model: value lists and ranges, axes,
// planning points in-process (answers and jobs), the plan in the run
// folder, knees and their explanation, CSV / JSON columns (dominant phase,
// area when reported), the figure.
#define BOOST_TEST_MODULE engine_sweep
#include <algorithm>
#include <boost/test/unit_test.hpp>
#include <cmath>

#include "engine_test_util.hpp"
#include "imap/engine/error.hpp"
#include "imap/engine/sweep.hpp"
#include "imap/engine/values.hpp"

namespace eng = imap::engine;
namespace sw = imap::engine::sweep;

using enginetest::Cleanup;
BOOST_TEST_GLOBAL_FIXTURE(Cleanup);

namespace {

using V = std::vector<std::string>;

// A ran row with modeled time `ms` (40 MHz) and the given phases.
sw::Row ran_row(const V& values, double ms, std::vector<std::pair<std::string, uint64_t>> phases) {
    sw::Row r;
    r.values = values;
    r.status = sw::Status::Ok;
    eng::RunResult rr;
    rr.model = "core";
    rr.outcome = eng::Outcome::Ok;
    rr.exit_code = 0;
    rr.has_report = true;
    rr.bit_exact = true;
    rr.modeled_ms = ms;
    rr.cycles = static_cast<uint64_t>(ms * 40000);
    rr.phases = std::move(phases);
    r.run = rr;
    return r;
}

sw::Plan pes_plan(const V& pes) {
    sw::Plan p;
    p.swept = {sw::make_axis("pes", "--pes", [&] {
        std::string s;
        for (const auto& v : pes) s += (s.empty() ? "" : ",") + v;
        return s;
    }())};
    return p;
}

}  // namespace

BOOST_AUTO_TEST_CASE(value_lists_and_ranges) {
    using eng::ValueType;
    BOOST_TEST(
        (eng::parse_value_list("--pes", "8..64*2", ValueType::Int) == V{"8", "16", "32", "64"}));
    BOOST_TEST((eng::parse_value_list("--pes", "8..60*2", ValueType::Int) == V{"8", "16", "32"}));
    BOOST_TEST(
        (eng::parse_value_list("--D", "1..7:3,20", ValueType::Int) == V{"1", "4", "7", "20"}));
    BOOST_TEST(
        (eng::parse_value_list("--c", "10..40:10", ValueType::Real) == V{"10", "20", "30", "40"}));
    BOOST_TEST((eng::parse_value_list("--c", "0.5..2*2", ValueType::Real) == V{"0.5", "1", "2"}));
    BOOST_TEST(
        (eng::parse_value_list("--mode", "single,bidir", ValueType::Text) == V{"single", "bidir"}));
    for (const char* bad :
         {"", "8..", "..8", "64..8", "8..64*1", "4,,8", "4,", "1.5", "a", "8,8", "1..20000"}) {
        BOOST_TEST_CONTEXT(bad) {
            try {
                eng::parse_value_list("--pes", bad, ValueType::Int);
                BOOST_ERROR("accepted");
            } catch (const eng::Error& e) {
                BOOST_TEST(std::string(e.what()).find("--pes") != std::string::npos);
                BOOST_TEST(e.code() == eng::kExitInput);
            }
        }
    }
    BOOST_CHECK_THROW(eng::parse_value_list("--mode", "a..b", ValueType::Text), eng::Error);
}

BOOST_AUTO_TEST_CASE(axes_check_their_values) {
    BOOST_TEST(sw::make_axis("clock_mhz", "--clock-mhz", "10..40:10").values.size() == 4u);
    BOOST_CHECK_THROW(sw::make_axis("D", "--D", "0,4"), eng::Error);
    BOOST_CHECK_THROW(sw::make_axis("roi_size", "--roi-size", "32y16"), eng::Error);
    BOOST_CHECK_THROW(sw::make_axis("mode", "--mode", "both"), eng::Error);
    BOOST_TEST(sw::make_axis("mode", "--mode", "single,bidir,joint").values.size() == 3u);
    BOOST_CHECK_THROW(sw::make_axis("nosuch", "--set nosuch", "1,2"), eng::Error);
    BOOST_CHECK_THROW(sw::make_axis("pes", "--pes", "1"), eng::Error);  // the machine says >= 2
    const sw::Axis a = sw::make_axis("pes", "--pes", "2..200");
    const sw::Axis b = sw::make_axis("D", "--D", "1..100");
    try {
        sw::product({a, b});
        BOOST_ERROR("accepted");
    } catch (const eng::Error& e) {
        BOOST_TEST(std::string(e.what()).find("19900 points") != std::string::npos);
    }
    BOOST_TEST(
        sw::product({sw::make_axis("pes", "--pes", "8,16"), sw::make_axis("D", "--D", "4,5,6")})
            .size() == 6u);
}

BOOST_AUTO_TEST_CASE(planning_gives_answers_and_jobs) {
    sw::Spec s;
    s.model = "core";
    s.swept = {sw::make_axis("mem_bytes", "--mem-bytes", "1024,60"),
               sw::make_axis("D", "--D", "8,40")};
    s.fixed = {sw::make_axis("roi_size", "--roi-size", "32x16")};
    s.base_args = {"--vote", "on"};
    const sw::Plan p = sw::plan(s);
    BOOST_REQUIRE_EQUAL(p.rows.size(), 4u);
    // 1024 B, D=8: runs; 60 B: does not fit (with the bytes it needs); D=40 > 32: cannot run.
    BOOST_TEST(p.rows[0].status == sw::Status::Planned);
    BOOST_TEST(p.rows[0].job == 0);
    BOOST_TEST(p.rows[1].status == sw::Status::CannotRun);
    BOOST_TEST(p.rows[2].status == sw::Status::DoesNotFit);
    BOOST_TEST(p.rows[2].message.find("have 60") != std::string::npos);
    BOOST_TEST(p.rows[2].local_bytes > 60);
    BOOST_REQUIRE_EQUAL(p.jobs.size(), 1u);
    const V& a = p.jobs[0].args;
    BOOST_TEST((V(a.begin(), a.begin() + 3) == V{"run", "--model", "core"}));
    for (const char* want : {"--mem-bytes", "--D", "--vote", "--size", "--roi"})
        BOOST_TEST((std::find(a.begin(), a.end(), want) != a.end()), want);
    BOOST_TEST(!p.phase_names.empty());
    // A joint point's child runs in joint mode (its --mode from the options).
    {
        sw::Spec j = s;
        j.swept = {sw::make_axis("mode", "--mode", "bidir,joint")};
        j.fixed.push_back(sw::make_axis("D", "--D", "8"));
        const sw::Plan jp = sw::plan(j);
        BOOST_REQUIRE_EQUAL(jp.jobs.size(), 2u);
        const V& b = jp.jobs[0].args;
        const V& c = jp.jobs[1].args;
        const auto mode_of = [](const V& args) {
            const auto it = std::find(args.begin(), args.end(), std::string("--mode"));
            return it == args.end() || it + 1 == args.end() ? std::string() : *(it + 1);
        };
        BOOST_TEST(mode_of(b) == "bidir");
        BOOST_TEST(mode_of(c) == "joint");
    }
    // The plan survives the run folder.
    const sw::Plan back = sw::plan_from_json(sw::to_json(p));
    BOOST_TEST(sw::to_json(back) == sw::to_json(p));
    BOOST_CHECK_THROW(sw::plan_from_json({{"kind", "regress-plan"}}), eng::Error);
    // Dry run: nothing to run, the answer says it fits.
    s.dry_run = true;
    const sw::Plan d = sw::plan(s);
    BOOST_TEST(d.jobs.empty());
    BOOST_TEST(d.rows[0].message.find("fits:") == 0u);
}

BOOST_AUTO_TEST_CASE(a_knee_is_found_where_the_slope_turns) {
    // Time halves per doubling up to 64 PEs (forward shrinks), then grows
    // (relayout grows): one knee, at 64, explained by both phases.
    const V pes = {"16", "32", "64", "128", "256"};
    const sw::Plan p = pes_plan(pes);
    std::vector<sw::Row> rows;
    const double fwd[] = {800, 400, 200, 100, 50}, rel[] = {10, 20, 40, 200, 600};
    for (size_t i = 0; i < pes.size(); ++i)
        rows.push_back(ran_row({pes[i]}, (fwd[i] + rel[i]) / 40.0,
                               {{"relayout_in", static_cast<uint64_t>(rel[i] * 1000)},
                                {"forward", static_cast<uint64_t>(fwd[i] * 1000)}}));
    const auto knees = sw::find_knees(p, rows, 0);
    BOOST_REQUIRE_EQUAL(knees.size(), 1u);
    const sw::Knee& k = knees[0];
    BOOST_TEST(k.x == "64");
    BOOST_TEST(k.phase_before == "forward");
    BOOST_TEST(k.phase_after == "relayout_in");
    BOOST_TEST(k.slope_before < -0.5);
    BOOST_TEST(k.slope_after > -0.5);
    BOOST_TEST(k.explanation.find("knee at pes=64") == 0u);
    BOOST_TEST(k.explanation.find("relayout_in +400%") != std::string::npos, k.explanation);
    BOOST_TEST(k.explanation.find("dominant phase forward -> relayout_in") != std::string::npos,
               k.explanation);
    // The figure marks it.
    sw::Result r;
    r.rows = rows;
    r.x_axis = "pes";
    r.knees = knees;
    eng::plot::Figure f;
    BOOST_REQUIRE(sw::make_figure(p, r, 0, &f));
    BOOST_REQUIRE_EQUAL(f.annotations.size(), 1u);
    BOOST_TEST(f.annotations[0].x == 64.0);
    BOOST_TEST(f.logx);
    // ... with a label in words (issue 32 item 15): 6 ms at 64 PEs, 7.5 ms at 128
    BOOST_TEST(k.label ==
                   "beyond 64 PEs the time grows 25%, relayout_in grows 400% (relayout_in "
                   "dominates)",
               k.label);
}

BOOST_AUTO_TEST_CASE(a_flat_knee_says_flat) {
    // Time falls to 256 PEs, then stays (one batch holds every line).
    const V pes = {"64", "128", "256", "512", "1024"};
    const sw::Plan p = pes_plan(pes);
    std::vector<sw::Row> rows;
    const double ms[] = {16, 8, 4, 4, 4};
    for (size_t i = 0; i < pes.size(); ++i)
        rows.push_back(
            ran_row({pes[i]}, ms[i], {{"forward", static_cast<uint64_t>(ms[i] * 1000)}}));
    const auto knees = sw::find_knees(p, rows, 0);
    BOOST_REQUIRE_EQUAL(knees.size(), 1u);
    BOOST_TEST(knees[0].label == "flat beyond 256 PEs", knees[0].label);
}

BOOST_AUTO_TEST_CASE(roi_sizes_that_differ_in_both_sides_get_a_tick_each) {
    // 64x32 and 32x64 have the same pixel count: they must not share an x.
    sw::Plan p;
    p.swept = {sw::make_axis("roi_size", "--roi-size", "64x32,32x64,48x48")};
    std::vector<sw::Row> rows = {ran_row({"64x32"}, 3, {{"forward", 1}}),
                                 ran_row({"32x64"}, 4, {{"forward", 1}}),
                                 ran_row({"48x48"}, 5, {{"forward", 1}})};
    sw::Result r;
    r.rows = rows;
    r.x_axis = "roi_size";
    eng::plot::Figure f;
    BOOST_REQUIRE(sw::make_figure(p, r, 0, &f));
    BOOST_REQUIRE_EQUAL(f.xcategories.size(), 3u);
    BOOST_TEST(f.xcategories[0].second == "64x32");
    BOOST_TEST(f.xcategories[1].second == "32x64");
    BOOST_TEST(f.xcategories[0].first != f.xcategories[1].first);
    BOOST_TEST(f.xlabel == "ROI size (W x H)");
}

BOOST_AUTO_TEST_CASE(no_knee_on_a_straight_scaling_curve) {
    const V pes = {"16", "32", "64", "128"};
    const sw::Plan p = pes_plan(pes);
    std::vector<sw::Row> rows;
    for (size_t i = 0; i < pes.size(); ++i)
        rows.push_back(ran_row({pes[i]}, 100.0 / std::pow(2.0, static_cast<double>(i)) + 0.0,
                               {{"forward", 1000u >> i}}));
    BOOST_TEST(sw::find_knees(p, rows, 0).empty());
    // Two points cannot have one; a categorical axis has none.
    rows.resize(2);
    BOOST_TEST(sw::find_knees(p, rows, 0).empty());
}

BOOST_AUTO_TEST_CASE(csv_and_json_columns) {
    const sw::Plan p = pes_plan({"8", "16"});
    sw::Result r;
    r.total = 2;
    r.rows = {ran_row({"8"}, 2.0, {{"forward", 60000}, {"relayout_in", 20000}}),
              ran_row({"16"}, 1.0, {{"forward", 20000}, {"relayout_in", 20000}})};
    r.rows[1].run->area = eng::Area{4096, 262144};
    r.rows[0].run->bounds = {{"forward", 30000}, {"relayout_in", 10000}};
    r.rows[0].run->bound_cycles = 40000;
    eng::Energy en;
    en.total_uj = 12.5;
    en.dynamic_uj = 10;
    en.static_uj = 2.5;
    en.power_mw = 6.25;
    en.by_class = {{"alu", 10}, {"static_pe", 2.5}};
    en.events = {{"alu_lanes", 7}};
    en.events_source = "isa";
    r.rows[0].run->energy = en;
    r.phase_names = {"relayout_in", "forward"};
    const std::string csv = sw::to_csv(p, r);
    const std::string head = csv.substr(0, csv.find('\n'));
    BOOST_TEST(head.find("dominant_phase,dominant_share,area_cells,area_memory_bits,"
                         "phase_relayout_in,phase_forward") != std::string::npos);
    BOOST_TEST(csv.find("forward,0.7500,,,20000,60000") != std::string::npos, csv);
    BOOST_TEST(csv.find(",4096,262144,") != std::string::npos, csv);
    // The machine bound after the phases: the frame's, bound / cycles, then
    // the bounded phases in the phases' order; empty where a row has none.
    BOOST_TEST(head.find("phase_forward,bound_cycles,efficiency,bound_relayout_in,bound_forward") !=
               std::string::npos);
    // ... and the energy at the very end (docs/energy.md), empty without one.
    // energy x delay (uJ x ms) the last column, after power_mw
    BOOST_TEST(head.find("bound_forward,energy_uj,power_mw,edp") != std::string::npos, head);
    BOOST_TEST(head.substr(head.size() - 4) == ",edp", head);
    BOOST_TEST(csv.find(",20000,60000,40000,0.5000,10000,30000,12.500000,6.250000,25.000000\n") !=
                   std::string::npos,
               csv);
    BOOST_TEST(csv.find(",20000,20000,,,,,,,\n") != std::string::npos, csv);
    const auto j = sw::to_json(p, r);
    BOOST_TEST(j["rows"][0]["dominant_phase"] == "forward");
    BOOST_TEST(j["rows"][1]["area"]["cells"] == 4096);
    BOOST_TEST(!j["rows"][0].contains("area"));
    BOOST_TEST(j["rows"][0]["bounds"]["forward"] == 30000);
    BOOST_TEST(j["rows"][0]["efficiency"] == 0.5);
    BOOST_TEST(!j["rows"][1].contains("bounds"));
    BOOST_TEST(j["rows"][0]["energy"]["total_uj"] == 12.5);
    BOOST_TEST(j["rows"][0]["energy"]["by_class"]["static_pe"] == 2.5);
    BOOST_TEST(!j["rows"][1].contains("energy"));
    BOOST_TEST(j["rows"][0]["edp"] == 25.0);
    BOOST_TEST(!j["rows"][1].contains("edp"));
    BOOST_TEST(r.exit_code(false) == 0);
    // The exit code: nothing ran is 5, a failed row is 5, interrupted 130.
    sw::Result none;
    sw::Row nf;
    nf.values = {"8"};
    nf.status = sw::Status::DoesNotFit;
    none.rows = {nf};
    BOOST_TEST(none.exit_code(false) == 5);
    BOOST_TEST(none.exit_code(true) == 5);
    none.rows[0].status = sw::Status::Planned;
    BOOST_TEST(none.exit_code(true) == 0);
    none.interrupted = true;
    BOOST_TEST(none.exit_code(true) == 130);
}

namespace {
// A ran row with a time and an energy (uJ).
sw::Row energy_row(const std::string& pes, double ms, double uj) {
    sw::Row r = ran_row({pes}, ms, {{"forward", 1}});
    eng::Energy e;
    e.total_uj = uj;
    e.power_mw = uj / ms;
    r.run->energy = e;
    return r;
}
}  // namespace

// Issue 29 item 3: the Pareto set by modeled time and energy, on rows made
// by hand; the expected set worked out here:
//   0 (1, 10)   optimal: nothing is both at most 1 ms and at most 10 uJ but 0
//   1 (2, 5)    optimal (3 is the same point: neither is better)
//   2 (3, 6)    dominated by 1 (faster and less energy)
//   3 (2, 5)    optimal (a tie with 1)
//   4 (0.5, 20) optimal: the fastest
//   5 (1, 12)   dominated by 0 (as fast, less energy)
//   6           does not fit: not a design point
//   7 (4, 1)    optimal: the least energy
//   8 (5, 1)    dominated by 7 (same energy, faster)
//   9 (0.2, -)  ran, no energy: not a design point
//  10 (0.1, 0.1) not bit-exact: not a design point (it would dominate all)
BOOST_AUTO_TEST_CASE(pareto_set_of_hand_made_rows) {
    std::vector<sw::Row> rows = {energy_row("0", 1, 10),   energy_row("1", 2, 5),
                                 energy_row("2", 3, 6),    energy_row("3", 2, 5),
                                 energy_row("4", 0.5, 20), energy_row("5", 1, 12)};
    sw::Row nf;
    nf.values = {"6"};
    nf.status = sw::Status::DoesNotFit;
    rows.push_back(nf);
    rows.push_back(energy_row("7", 4, 1));
    rows.push_back(energy_row("8", 5, 1));
    rows.push_back(ran_row({"9"}, 0.2, {{"forward", 1}}));
    sw::Row bad = energy_row("10", 0.1, 0.1);
    bad.status = sw::Status::Mismatch;
    bad.run->outcome = eng::Outcome::Mismatch;
    bad.run->bit_exact = false;
    rows.push_back(bad);
    BOOST_TEST((sw::pareto_rows(rows) == std::vector<size_t>{0, 1, 3, 4, 7}));
    // one point alone is optimal; none gives none
    BOOST_TEST((sw::pareto_rows({rows[2]}) == std::vector<size_t>{0}));
    BOOST_TEST(sw::pareto_rows({nf}).empty());

    // The listing names them fastest first; the figure circles them.
    sw::Plan p;
    sw::Axis ax;  // the row labels (not PE counts)
    ax.name = "pes";
    ax.kind = sw::AxisKind::Machine;
    for (int i = 0; i <= 10; ++i) ax.values.push_back(std::to_string(i));
    p.swept = {ax};
    sw::Result r;
    r.rows = rows;
    const auto lines = sw::pareto_lines(p, r);
    BOOST_REQUIRE_EQUAL(lines.size(), 6u);
    BOOST_TEST(lines[0].find("5 of 8 points") != std::string::npos, lines[0]);
    BOOST_TEST(lines[1].find("pes=4: 0.500 ms, 20.000 uJ") != std::string::npos, lines[1]);
    BOOST_TEST(lines[5].find("pes=7: 4.000 ms, 1.000 uJ") != std::string::npos, lines[5]);
    eng::plot::Figure f;
    BOOST_REQUIRE(sw::make_pareto_figure(p, r, &f));
    BOOST_REQUIRE_EQUAL(f.series.size(), 2u);
    BOOST_TEST(f.series[0].scatter);
    BOOST_TEST(f.series[0].x.size() == 8u);
    BOOST_TEST(f.series[0].size.empty());  // no area: one size, and a note says so
    BOOST_TEST(f.subtitle.find("no area") != std::string::npos, f.subtitle);
    BOOST_TEST((f.series[1].x == std::vector<double>{0.5, 1, 2, 2, 4}));
    BOOST_TEST(f.annotations.size() == 5u);
    // with an area on every point: sizes, the largest area the largest point
    for (sw::Row& row : r.rows)
        if (row.run) row.run->area = eng::Area{row.values[0] == "7" ? 4000u : 1000u, 0};
    eng::plot::Figure g;
    BOOST_REQUIRE(sw::make_pareto_figure(p, r, &g));
    BOOST_REQUIRE_EQUAL(g.series[0].size.size(), 8u);
    BOOST_TEST(*std::max_element(g.series[0].size.begin(), g.series[0].size.end()) == 4.0);
    BOOST_TEST(g.subtitle.find("point size: area") != std::string::npos, g.subtitle);
    const std::string script = eng::plot::script_text(g, "g.dat", "g.png");
    BOOST_TEST(script.find("ps variable") != std::string::npos);
}

// --y: the metric's column in the table, the least point in the summary,
// the plot's y; time leaves the table as it was.
BOOST_AUTO_TEST_CASE(y_metric_column_summary_and_plot) {
    BOOST_TEST(sw::metric_from_name("edp").has_value());
    BOOST_TEST(!sw::metric_from_name("speed").has_value());
    sw::Plan p = pes_plan({"8", "16"});
    p.rows = {energy_row("8", 2.0, 12.5), energy_row("16", 1.0, 20.0)};
    BOOST_TEST(sw::metric_value(p.rows[0], sw::Metric::Edp) == 25.0);
    BOOST_TEST(sw::metric_value(p.rows[1], sw::Metric::Power) == 20.0);
    BOOST_TEST(std::isnan(sw::metric_value(p.rows[0], sw::Metric::Area)));
    const std::string h_time = sw::header_lines(p, nullptr).back();
    const std::string r_time = sw::row_line(p, p.rows[0]);
    BOOST_TEST(h_time.find("energy") == std::string::npos);
    p.y = sw::Metric::Edp;
    const std::string h = sw::header_lines(p, nullptr).back();
    BOOST_TEST(h.find("modeled ms  EDP uJ*ms") != std::string::npos, h);
    BOOST_TEST(sw::row_line(p, p.rows[0]).find("2.000     25.000") != std::string::npos,
               sw::row_line(p, p.rows[0]));
    sw::Result r;
    r.total = 2;
    r.rows = p.rows;
    const auto sum = sw::summary_lines(p, r);
    BOOST_TEST(sum.back() == "  least edp: pes=16, 20.000 uJ*ms (1.000 ms)", sum.back());
    eng::plot::Figure f;
    BOOST_REQUIRE(sw::make_figure(p, r, 0, &f));
    BOOST_TEST((f.series[0].y == std::vector<double>{25.0, 20.0}));
    BOOST_TEST(f.hlines.empty());  // the real-time lines are for time
    BOOST_TEST(f.ylabel.find("energy x delay") != std::string::npos, f.ylabel);
    p.y = sw::Metric::Time;
    BOOST_TEST(sw::header_lines(p, nullptr).back() == h_time);
    BOOST_TEST(sw::row_line(p, p.rows[0]) == r_time);
}

// The design's Fmax (docs/rtl.md, "Place and route (iCE40)"): a child's
// report carries "design_fmax"; a point whose clock is above it is marked in
// the table and counted in the summary, a point below it is not; the run
// folder keeps it.
BOOST_AUTO_TEST_CASE(a_clock_above_the_design_fmax_is_marked) {
    sw::Plan p;
    p.swept = {sw::make_axis("clock_mhz", "--clock-mhz", "20,80")};
    p.rows = {ran_row({"20"}, 2.0, {{"forward", 1000}}), ran_row({"80"}, 0.5, {{"forward", 1000}})};
    for (sw::Row& row : p.rows) {
        const double clock = std::stod(row.values[0]);
        const nlohmann::json rep = {{"cycles", 80000},
                                    {"modeled_ms", 80000 / (clock * 1e3)},
                                    {"phases", {{"forward", 80000}}},
                                    {"design_fmax",
                                     {{"mhz", 45.5},
                                      {"technology", "iCE40 HX8K"},
                                      {"clock_mhz", clock},
                                      {"clock_above", clock > 45.5}}}};
        BOOST_REQUIRE(eng::read_report(rep, *row.run));
        BOOST_REQUIRE(row.run->design_fmax);
    }
    BOOST_TEST(!sw::clock_above_fmax(p.rows[0]));
    BOOST_TEST(sw::clock_above_fmax(p.rows[1]));
    const std::string below = sw::row_line(p, p.rows[0]);
    const std::string above = sw::row_line(p, p.rows[1]);
    BOOST_TEST(below.find("Fmax") == std::string::npos, below);
    BOOST_TEST(above.find("ok, bit-exact [clock > design Fmax 45.5 MHz]") != std::string::npos,
               above);
    sw::Result r;
    r.total = 2;
    r.rows = p.rows;
    const auto sum = sw::summary_lines(p, r);
    BOOST_REQUIRE_GE(sum.size(), 2u);
    BOOST_TEST(sum[1].find("1 point with the clock above the design's Fmax (45.5 MHz on iCE40 "
                           "HX8K") != std::string::npos,
               sum[1]);
    // the run folder's copy of a result keeps the mark
    const eng::RunResult back = eng::result_from_json(eng::to_json(*p.rows[1].run));
    BOOST_REQUIRE(back.design_fmax);
    BOOST_TEST(back.design_fmax->clock_above);
    BOOST_TEST(back.design_fmax->mhz == 45.5);
    // no design_fmax in the report: nothing marked
    r.rows[1].run->design_fmax.reset();
    BOOST_TEST(!sw::clock_above_fmax(r.rows[1]));
    BOOST_TEST(sw::summary_lines(p, r).size() == 1u);
}
