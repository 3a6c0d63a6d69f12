// imapsim exec's checks before the run, from the flags as given (Request):
// machine, model, parameters, PE dump, outputs and the video inputs.
#include "imap/engine/exec_request.hpp"

#include <cstdio>

#include "imap/engine/error.hpp"
#include "imap/engine/output_files.hpp"
#include "imap/firmware/run.hpp"
#include "imap/vision/image_io.hpp"

namespace imap::engine::exec {

namespace {

isa::ImageVideoPort::Image read_input(const std::string& path, const char* what) {
    if (path.empty()) return {};
    const cv::Mat m = vision::load_grey8(path, what);
    return firmware::to_video_image(vision::view_of(m));
}

}  // namespace

Checked check(const Request& r, const std::function<void()>& check_waves) {
    Checked c;
    c.cfg = machine_config(r.machine);
    check_model(r.model);
    Inputs& in = c.in;
    in.name = r.program;
    in.params = parse_params(r.params);
    if (!r.dump_pes.empty()) c.dump_pes = parse_pe_list(r.dump_pes, c.cfg.pes);
    if (!r.dump_mem.empty() && c.dump_pes.empty())
        throw Error("--dump-mem needs --dump-pes (whose memory to print)");
    if (!r.dump_mem.empty()) c.mem_range = parse_mem_range(r.dump_mem, c.cfg.mem_bytes);
    check_output_file("--out-left", r.out_left, true);
    check_output_file("--report", r.report, false);
    check_waves();
    in.left = read_input(r.left, "left image");
    in.right = read_input(r.right, "right image");
    if (!r.left.empty() && !r.right.empty())
        check_same_size(r.left, in.left.width, in.left.height, r.right, in.right.width,
                        in.right.height);
    const isa::ImageVideoPort::Image& shape = r.left.empty() ? in.right : in.left;
    in.out_w = shape.width;
    in.out_h = shape.height;
    if (!r.out_size.empty()) {
        int w = 0, h = 0;
        char x = 0;
        if (std::sscanf(r.out_size.c_str(), "%d%c%d", &w, &x, &h) != 3 || x != 'x' || w < 1 ||
            h < 1 || w > 65536 || h > 65536)
            throw Error("invalid value '" + r.out_size +
                        "' for --out-size: expected WxH with W and H in 1..65536");
        in.out_w = w;
        in.out_h = h;
    }
    if (!r.out_left.empty() && in.out_w == 0)
        throw Error(
            "--out-left needs an input image (--left or --right) or --out-size: the output "
            "image has the size of the inputs");
    return c;
}

}  // namespace imap::engine::exec
