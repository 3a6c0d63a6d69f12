// engine.bench: the benchmark through the library (bench.hpp) on a tiny
// configuration (imapsim run --size 32x8 --D 8 --pes 8 on the core model,
// one run, no stream): its cycles against a library model run of the same
// frame, the derived figures and the JSON; the median and spread on
// hand-made values.
#define BOOST_TEST_MODULE engine_bench
#include <boost/test/unit_test.hpp>

#include "imap/engine/bench.hpp"
#include "imap/engine/flag_values.hpp"
#include "imap/engine/models.hpp"
#include "imap/vision/image_io.hpp"
#include "imap/vision/synth.hpp"

namespace b = imap::engine::bench;
namespace e = imap::engine;
namespace g = imap::golden;
namespace v = imap::vision;

BOOST_AUTO_TEST_CASE(median_and_spread) {
    BOOST_TEST(b::median({3, 1, 2}) == 2.0);
    BOOST_TEST(b::median({4, 1, 2, 3}) == 2.5);
    BOOST_TEST(b::median({}) == 0.0);
    BOOST_TEST(b::spread({3, 1, 2}, "%.1f") == "2.0  (1.0 .. 3.0)");
}

BOOST_AUTO_TEST_CASE(a_tiny_bench) {
    b::Config c;
    c.exe = IMAPSIM_EXE;
    c.model = "core";
    c.runs = 1;
    c.stream_frames = 0;
    c.run_args = {"--size", "32x8", "--D", "8", "--pes", "8"};
    const b::Figures f = b::run(c);

    const v::SynthScene sc = v::make_synth_scene(1, 32, 8);
    g::Params p;
    p.D = 8;
    e::MachineSettings m;
    m.pes = "8";
    const e::ModelRun run = e::run_model("core", p, {0, 0, 32, 8}, v::view_of(sc.left),
                                         v::view_of(sc.right), e::machine_config(m));
    BOOST_REQUIRE(f.model.available);
    BOOST_TEST(!f.rtl.available);
    BOOST_TEST(!f.stream.available);
    BOOST_TEST(f.model.cycles == run.result.cycles);
    BOOST_TEST(f.model.modeled_ms == run.result.modeled_ms);
    BOOST_TEST(f.model.wall_s.size() == 1u);
    BOOST_TEST(f.model.bound_cycles == static_cast<uint64_t>(run.bounds.total()));
    BOOST_TEST(f.wall == f.model.wall_s[0]);
    BOOST_TEST(f.realtime == f.model.modeled_ms / 1e3 / f.wall);
    BOOST_TEST(f.golden_ms > 0);
    // The headline frame's DP nodes: the valid levels of its 128 columns
    // (D = 64) on each of its 128 lines.
    int64_t nodes = 0;
    for (int i = 0; i < 128; ++i) nodes += g::levels_at(i, 128, 64);
    BOOST_TEST(f.nodes == nodes * 128);
    BOOST_TEST(f.per_pe == static_cast<double>(f.nodes) / 256.0);
    const nlohmann::json j = b::to_json(f, 1);
    BOOST_TEST(j.at("cycles").get<uint64_t>() == run.result.cycles);
    BOOST_TEST(j.at("runs").get<int>() == 1);
    BOOST_TEST(j.at("rtl_cycles_per_s").is_null());
    BOOST_TEST(!j.contains("stream"));
}
