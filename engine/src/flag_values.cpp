// Flag values and machine settings (flag_values.hpp): strict parses whose
// errors name the flag and the allowed range, and the MachineConfig of the
// machine settings.
#include "imap/engine/flag_values.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <vector>

#include "imap/engine/error.hpp"

namespace imap::engine {

namespace g = imap::golden;

long long parse_int_flag(const std::string& flag, const std::string& text, long long lo,
                         long long hi) {
    std::ostringstream range;
    range << lo << ".." << hi;
    if (text.empty() || text.find_first_not_of("+-0123456789") != std::string::npos)
        throw Error("invalid value '" + text + "' for " + flag + ": expected an integer in " +
                    range.str());
    errno = 0;
    char* end = nullptr;
    const long long v = std::strtoll(text.c_str(), &end, 10);
    if (errno != 0 || end == text.c_str() || *end != '\0')
        throw Error("invalid value '" + text + "' for " + flag + ": expected an integer in " +
                    range.str());
    if (v < lo || v > hi)
        throw Error("value " + text + " for " + flag + " is out of range (allowed: " + range.str() +
                    ")");
    return v;
}

void parse_size_flag(const std::string& flag, const std::string& text, int lo, int hi, int* w,
                     int* h) {
    const auto x = text.find('x');
    if (x == std::string::npos || text.find('x', x + 1) != std::string::npos)
        throw Error("invalid value '" + text + "' for " + flag + ": expected WxH with W and H in " +
                    std::to_string(lo) + ".." + std::to_string(hi));
    *w = static_cast<int>(parse_int_flag(flag + " width", text.substr(0, x), lo, hi));
    *h = static_cast<int>(parse_int_flag(flag + " height", text.substr(x + 1), lo, hi));
}

double parse_real_flag(const std::string& flag, const std::string& text, double lo, double hi,
                       bool lo_open) {
    std::ostringstream range;
    range << (lo_open ? "> " : ">= ") << lo << " and <= " << hi;
    errno = 0;
    char* end = nullptr;
    const double v = text.empty() ? 0.0 : std::strtod(text.c_str(), &end);
    if (text.empty() || errno != 0 || end == text.c_str() || *end != '\0' || !std::isfinite(v))
        throw Error("invalid value '" + text + "' for " + flag + ": expected a number " +
                    range.str());
    if ((lo_open ? v <= lo : v < lo) || v > hi)
        throw Error("value " + text + " for " + flag + " is out of range (allowed: " + range.str() +
                    ")");
    return v;
}

// --camera: the pixel clock it names, in MHz (0 = ideal).
std::string camera_pixel_mhz(const std::string& v) {
    if (v == "ideal") return "0";
    if (v == "ntsc") return "12.2727";  // NTSC square pixels: 780 x 525 x 29.97 Hz
    const std::string pre = "pixel-clock:";
    if (v.compare(0, pre.size(), pre) == 0 && v.size() > pre.size()) {
        const std::string mhz = v.substr(pre.size());
        try {
            parse_real_flag("--camera", mhz, 0, 1e300, true);
            return mhz;
        } catch (const Error&) {
            // the message below names every allowed form
        }
    }
    throw Error("invalid value '" + v +
                "' for --camera: expected ideal, ntsc or pixel-clock:MHZ with MHZ > 0");
}

isa::MachineConfig machine_config(const MachineSettings& f) {
    isa::MachineConfig cfg;
    auto set = [&](const std::string& flag, const std::string& name, const std::string& value) {
        if (value.empty()) return;
        try {
            cfg.set(name, value);
        } catch (const std::exception& e) {
            throw Error(flag + ": " + e.what());
        }
    };
    set("--pes", "pes", f.pes);
    set("--clock-mhz", "clock_mhz", f.clock_mhz);
    set("--mem-bytes", "mem_bytes", f.mem_bytes);
    set("--ext-bytes", "ext_bytes", f.ext_bytes);
    if (!f.camera.empty()) set("--camera", "camera_pixel_mhz", camera_pixel_mhz(f.camera));
    for (const std::string& s : f.sets) {
        const size_t eq = s.find('=');
        if (eq == std::string::npos || eq == 0)
            throw Error("invalid value '" + s + "' for --set: expected NAME=VALUE");
        set("--set", s.substr(0, eq), s.substr(eq + 1));
    }
    try {
        cfg.validate();
    } catch (const std::exception& e) {
        throw Error(e.what());
    }
    return cfg;
}

g::Params algo_params(const AlgoSettings& f, g::Roi* roi, bool* has_roi) {
    g::Params p;
    if (!f.preset.empty()) {
        if (f.preset != "paper" && f.preset != "quality")
            throw Error("invalid value '" + f.preset + "' for --preset: expected " +
                        g::preset_names());
        p = g::preset(f.preset);
    }
    auto num = [](const std::string& flag, const std::string& text, long long lo, long long hi,
                  int& dst) {
        if (!text.empty()) dst = static_cast<int>(parse_int_flag(flag, text, lo, hi));
    };
    num("--D", f.D, 1, g::kMaxLevels, p.D);
    num("--km", f.km, 0, g::kMaxWeight, p.km);
    num("--kb", f.kb, 0, g::kMaxWeight, p.kb);
    num("--gb", f.gb, 0, 255, p.gb);
    num("--Wo", f.Wo, 0, g::kMaxWeight, p.Wo);
    num("--Wd", f.Wd, 0, g::kMaxWeight, p.Wd);
    num("--ad-max", f.ad_max, 0, 255, p.ad_max);
    num("--kc", f.kc, 0, g::kMaxWeight, p.kc);
    num("--census", f.census, 1, g::kMaxCensusRadius, p.census);
    num("--agg-rx", f.agg_rx, 0, g::kMaxAggRadius, p.agg_rx);
    num("--agg-ry", f.agg_ry, 0, g::kMaxAggRadius, p.agg_ry);
    if (f.dissim == "ad")
        p.dissim = g::Dissim::Ad;
    else if (f.dissim == "bt")
        p.dissim = g::Dissim::Bt;
    else if (!f.dissim.empty())
        throw Error("invalid value '" + f.dissim + "' for --dissim: expected ad or bt");

    // Flags with a text default override the preset when given or changed.
    auto set = [&f](const char* flag, const std::string& value, const char* def) {
        return f.given.count(flag) > 0 || value != def;
    };
    if (set("--mode", f.mode, "bidir")) {
        if (f.mode == "single")
            p.mode = g::Mode::Single;
        else if (f.mode == "bidir")
            p.mode = g::Mode::Bidir;
        else if (f.mode == "joint")
            p.mode = g::Mode::Joint;
        else
            throw Error("invalid value '" + f.mode +
                        "' for --mode: expected single, bidir or joint");
    }

    if (!set("--seed-col", f.seed_col, "balanced")) {
        // the preset's
    } else if (f.seed_col == "balanced")
        p.seed_col.kind = g::SeedColKind::Balanced;
    else if (f.seed_col == "center")
        p.seed_col.kind = g::SeedColKind::Center;
    else {
        p.seed_col.kind = g::SeedColKind::Fixed;
        p.seed_col.value = static_cast<int>(parse_int_flag(
            "--seed-col (balanced, center or a column)", f.seed_col, 1, g::kMaxWidth - 1));
    }

    if (!set("--seed-disp", f.seed_disp, "free")) {
        // the preset's
    } else if (f.seed_disp == "free") {
        p.seed_disp.free = true;
    } else {
        p.seed_disp.free = false;
        p.seed_disp.value = static_cast<int>(
            parse_int_flag("--seed-disp (free or a disparity)", f.seed_disp, 0, g::kMaxLevels - 1));
    }

    if (!set("--vote", f.vote, "on")) {
        // the preset's
    } else if (f.vote == "on")
        p.vote = true;
    else if (f.vote == "off")
        p.vote = false;
    else
        throw Error("invalid value '" + f.vote + "' for --vote: expected on or off");

    if (!set("--frame", f.frame, "cyc")) {
        // the preset's
    } else if (f.frame == "cyc" || f.frame == "cyclopean")
        p.frame = g::Frame::Cyclopean;
    else if (f.frame == "left")
        p.frame = g::Frame::Left;
    else if (f.frame == "right")
        p.frame = g::Frame::Right;
    else
        throw Error("invalid value '" + f.frame + "' for --frame: expected cyc, left or right");

    *has_roi = !f.roi.empty();
    if (*has_roi) {
        std::vector<std::string> parts;
        std::stringstream ss(f.roi);
        std::string item;
        while (std::getline(ss, item, ',')) parts.push_back(item);
        if (parts.size() != 4 || f.roi.back() == ',')
            throw Error("invalid value '" + f.roi + "' for --roi: expected x0,y0,w,h");
        roi->x0 = static_cast<int>(parse_int_flag("--roi x0", parts[0], 0, 1 << 20));
        roi->y0 = static_cast<int>(parse_int_flag("--roi y0", parts[1], 0, 1 << 20));
        roi->w = static_cast<int>(parse_int_flag("--roi w", parts[2], 1, 1 << 20));
        roi->h = static_cast<int>(parse_int_flag("--roi h", parts[3], 1, 1 << 20));
    }
    try {
        g::validate_params(p);
    } catch (const g::ParamError& e) {
        throw Error(e.what());
    }
    return p;
}

}  // namespace imap::engine
