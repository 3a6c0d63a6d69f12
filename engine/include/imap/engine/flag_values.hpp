// Strict parsing of flag values (integers, WxH sizes, real numbers) and of
// the machine settings (--pes, --clock-mhz, --camera, --set NAME=VALUE ...)
// into an isa::MachineConfig, and of the algorithm settings into golden::Params. No command-line
// library: the text comes from imapsim's flags, a parameter-set file or a test; errors are
// engine::Error naming the flag, the value and the allowed range.
#pragma once

#include <set>
#include <string>
#include <vector>

#include "imap/golden/params.hpp"
#include "imap/isa/config.hpp"

namespace imap::engine {

// Strict integer parse of a flag value; error names the flag and the range.
long long parse_int_flag(const std::string& flag, const std::string& text, long long lo,
                         long long hi);

// Strict WxH parse of a size flag (one 'x', both parts integers in lo..hi);
// the error names the flag and the range.
void parse_size_flag(const std::string& flag, const std::string& text, int lo, int hi, int* w,
                     int* h);

// Strict real-number parse of a flag value (finite, lo < v <= hi when
// lo_open, else lo <= v <= hi); the error names the flag and the range.
double parse_real_flag(const std::string& flag, const std::string& text, double lo, double hi,
                       bool lo_open);

// The machine's settings as text (empty = not given): --pes --clock-mhz
// --mem-bytes --ext-bytes --camera and --set NAME=VALUE (docs/isa.md).
struct MachineSettings {
    std::string pes, clock_mhz, mem_bytes, ext_bytes;
    std::string camera;  // ideal | ntsc | pixel-clock:MHZ (camera_pixel_mhz)
    std::vector<std::string> sets;
};
// The machine they describe, validated; Error naming the flag otherwise.
isa::MachineConfig machine_config(const MachineSettings& s);

// The algorithm settings as text, parsed so that errors name the flag, the
// value and the allowed range. `preset` (paper or quality,
// empty = paper) gives the starting values; every flag given overrides its
// preset value (an empty string = not given; mode, seed-col, seed-disp,
// vote and frame count as given when on the command line (`given`) or
// different from their paper default).
struct AlgoSettings {
    std::string preset;
    std::string D, km, kb, gb, Wo, Wd;
    std::string dissim, ad_max, kc, census, agg_rx, agg_ry;  // SPEC A.9 options
    std::string mode = "bidir";
    std::string seed_col = "balanced";
    std::string seed_disp = "free";
    std::string vote = "on";
    std::string roi;  // empty = whole image
    std::string frame = "cyc";
    bool fill = false;
    std::set<std::string> given;  // flags seen on the command line (imapsim: filled by CLI11)
};

// The golden parameters they give (Error naming the flag); the ROI
// separately: `has_roi` false means "whole image".
golden::Params algo_params(const AlgoSettings& f, golden::Roi* roi, bool* has_roi);

// --camera's value (ideal | ntsc | pixel-clock:MHZ) as camera_pixel_mhz
// ("0" = ideal); Error naming the allowed values.
std::string camera_pixel_mhz(const std::string& v);

}  // namespace imap::engine
