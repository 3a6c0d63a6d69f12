// imapsim synth: writes the built-in synthetic stereo scene (left, right and
// left-view ground truth) to a folder.
#include <cerrno>
#include <cstdio>
#include <cstdlib>
#include <filesystem>

#include "cli_common.hpp"
#include "imap/vision/image_io.hpp"
#include "imap/vision/synth.hpp"

namespace imapsim {

namespace v = imap::vision;
namespace fs = std::filesystem;

namespace {
struct SynthOptions {
    std::string seed = "1";
    std::string size = "160x128";
    std::string out_dir;
};

uint64_t parse_seed(const std::string& text) {
    const std::string err =
        "invalid value '" + text + "' for --seed: expected an integer in 0..18446744073709551615";
    if (text.empty() || text.size() > 20 ||
        text.find_first_not_of("0123456789") != std::string::npos)
        throw UserError(err);
    errno = 0;
    char* end = nullptr;
    const unsigned long long s = std::strtoull(text.c_str(), &end, 10);
    if (errno != 0 || *end != '\0') throw UserError(err);
    return static_cast<uint64_t>(s);
}

void parse_size(const std::string& text, int* w, int* h) {
    const auto x = text.find('x');
    if (x == std::string::npos || text.find('x', x + 1) != std::string::npos)
        throw UserError("invalid value '" + text +
                        "' for --size: expected WxH with W and H in 2..4096");
    *w = static_cast<int>(parse_int_flag("--size width", text.substr(0, x), 2, 4096));
    *h = static_cast<int>(parse_int_flag("--size height", text.substr(x + 1), 2, 4096));
}
}  // namespace

Subcommand register_synth(CLI::App& app) {
    auto o = std::make_shared<SynthOptions>();
    CLI::App* sub = app.add_subcommand(
        "synth", "Write the built-in synthetic stereo scene (left.png, right.png, gt.png)");
    sub->add_option("--seed", o->seed, "scene seed (0..2^64-1)")->capture_default_str();
    sub->add_option("--size", o->size, "image size WxH (2..4096 each)")->capture_default_str();
    sub->add_option("--out-dir", o->out_dir, "output folder (created if missing)")->required();

    return {sub, [o]() {
                const uint64_t seed = parse_seed(o->seed);
                int w = 0, h = 0;
                parse_size(o->size, &w, &h);
                std::error_code ec;
                if (fs::exists(o->out_dir, ec) && !fs::is_directory(o->out_dir, ec))
                    throw UserError("--out-dir '" + o->out_dir + "' exists and is not a folder");
                fs::create_directories(o->out_dir, ec);
                if (ec)
                    throw UserError("--out-dir '" + o->out_dir + "': cannot create (" +
                                    ec.message() + ")");
                const v::SynthScene sc = v::make_synth_scene(seed, w, h);
                const fs::path dir(o->out_dir);
                v::write_image_atomic((dir / "left.png").string(), sc.left);
                v::write_image_atomic((dir / "right.png").string(), sc.right);
                v::write_image_atomic((dir / "gt.png").string(), sc.gt);
                std::printf(
                    "synth: seed %llu, %dx%d, disparities 0..%d (gt scale 1, left view) -> "
                    "%s/{left,right,gt}.png\n",
                    static_cast<unsigned long long>(seed), w, h, sc.max_disp, o->out_dir.c_str());
                return static_cast<int>(kExitOk);
            }};
}

}  // namespace imapsim
