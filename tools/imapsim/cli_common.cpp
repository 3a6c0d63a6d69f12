#include "cli_common.hpp"

#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>
#include <sstream>

namespace imapsim {

namespace g = imap::golden;

long long parse_int_flag(const std::string& flag, const std::string& text, long long lo,
                         long long hi) {
    std::ostringstream range;
    range << lo << ".." << hi;
    if (text.empty() || text.find_first_not_of("+-0123456789") != std::string::npos)
        throw UserError("invalid value '" + text + "' for " + flag + ": expected an integer in " +
                        range.str());
    errno = 0;
    char* end = nullptr;
    const long long v = std::strtoll(text.c_str(), &end, 10);
    if (errno != 0 || end == text.c_str() || *end != '\0')
        throw UserError("invalid value '" + text + "' for " + flag + ": expected an integer in " +
                        range.str());
    if (v < lo || v > hi)
        throw UserError("value " + text + " for " + flag +
                        " is out of range (allowed: " + range.str() + ")");
    return v;
}

void parse_size_flag(const std::string& flag, const std::string& text, int lo, int hi, int* w,
                     int* h) {
    const auto x = text.find('x');
    if (x == std::string::npos || text.find('x', x + 1) != std::string::npos)
        throw UserError("invalid value '" + text + "' for " + flag +
                        ": expected WxH with W and H in " + std::to_string(lo) + ".." +
                        std::to_string(hi));
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
        throw UserError("invalid value '" + text + "' for " + flag + ": expected a number " +
                        range.str());
    if ((lo_open ? v <= lo : v < lo) || v > hi)
        throw UserError("value " + text + " for " + flag +
                        " is out of range (allowed: " + range.str() + ")");
    return v;
}

namespace {

// The folder a folder name lives in: "out/" and "out" are the same folder
// (a trailing '/', as shell completion writes it, names no new level).
std::filesystem::path parent_folder(const std::string& dir) {
    std::filesystem::path p(dir);
    while (!p.has_filename() && p.has_parent_path() && p != p.parent_path()) p = p.parent_path();
    return p.parent_path();
}

// Throws unless files can be created in `dir` (permissions, read-only file
// system): creates a uniquely named empty file there and removes it.
void require_creatable(const std::string& flag, const std::string& path,
                       const std::filesystem::path& dir) {
    const std::filesystem::path where = dir.empty() ? std::filesystem::path(".") : dir;
    std::string probe = (where / ".imapsim-write-check-XXXXXX").string();
    const int fd = ::mkstemp(probe.data());
    if (fd < 0)
        throw UserError(flag + " '" + path + "': cannot create files in folder '" + where.string() +
                        "' (" + std::strerror(errno) + ")");
    ::close(fd);
    ::unlink(probe.c_str());
}

}  // namespace

void check_same_size(const std::string& left, int lw, int lh, const std::string& right, int rw,
                     int rh) {
    if (lw == rw && lh == rh) return;
    throw UserError("left and right images differ in size: " + left + " is " + std::to_string(lw) +
                    "x" + std::to_string(lh) + ", " + right + " is " + std::to_string(rw) + "x" +
                    std::to_string(rh));
}

void validate_frame(const imap::golden::Params& p, const imap::golden::Roi& roi, int w, int h) {
    try {
        imap::golden::validate(p, roi, w, h);
    } catch (const imap::golden::ParamError& e) {
        throw UserError(e.what());
    }
}

void check_output_file(const std::string& flag, const std::string& path, bool image) {
    namespace fs = std::filesystem;
    if (path.empty()) return;
    const fs::path p(path);
    const fs::path dir = p.parent_path();
    std::error_code ec;
    if (!dir.empty() && !fs::is_directory(dir, ec))
        throw UserError(flag + " '" + path + "': cannot create it: " +
                        (fs::exists(dir, ec) ? "'" + dir.string() + "' is not a folder"
                                             : "folder '" + dir.string() + "' does not exist"));
    if (fs::is_directory(p, ec)) throw UserError(flag + " '" + path + "': is a folder");
    if (image && !cv::haveImageWriter(path))
        throw UserError(flag + " '" + path + "': cannot write this image type" +
                        (p.extension().empty() ? std::string(" (no extension)")
                                               : " ('" + p.extension().string() + "')") +
                        "; use e.g. .png");
    require_creatable(flag, path, dir);
}

void check_output_dir(const std::string& flag, const std::string& dir) {
    namespace fs = std::filesystem;
    if (dir.empty()) return;
    std::error_code ec;
    // The folder itself if it exists, else its parent, in which it will be
    // created: as for an output file, the folder it goes into must exist.
    const fs::path self(dir);
    if (fs::exists(self, ec)) {
        if (!fs::is_directory(self, ec))
            throw UserError(flag + " '" + dir + "': cannot create it: '" + dir +
                            "' is not a folder");
        require_creatable(flag, dir, self);
        return;
    }
    const fs::path up = parent_folder(dir);
    if (!up.empty() && !fs::is_directory(up, ec))
        throw UserError(flag + " '" + dir + "': cannot create it: " +
                        (fs::exists(up, ec) ? "'" + up.string() + "' is not a folder"
                                            : "folder '" + up.string() + "' does not exist"));
    require_creatable(flag, dir, up);
}

void create_output_dir(const std::string& flag, const std::string& dir) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
        throw UserError(flag + " '" + dir + "' exists and is not a folder");
    const fs::path up = parent_folder(dir);
    if (!fs::exists(dir, ec) && !up.empty() && !fs::is_directory(up, ec))
        throw UserError(flag + " '" + dir + "': cannot create it: " +
                        (fs::exists(up, ec) ? "'" + up.string() + "' is not a folder"
                                            : "folder '" + up.string() + "' does not exist"));
    fs::create_directory(dir, ec);
    if (ec) throw UserError(flag + " '" + dir + "': cannot create (" + ec.message() + ")");
}

std::string lower_extension(const std::string& path) {
    std::string ext = std::filesystem::path(path).extension().string();
    for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return ext;
}

std::string folder_of(const std::string& path) {
    const std::filesystem::path parent = std::filesystem::path(path).parent_path();
    return parent.empty() ? std::string(".") : parent.string();
}

bool file_in_folder(const std::string& path, const std::string& dir) {
    namespace fs = std::filesystem;
    if (path.empty() || dir.empty()) return false;
    const auto norm = [](const fs::path& q) { return (fs::absolute(q) / "").lexically_normal(); };
    return norm(folder_of(path)) == norm(dir);
}

std::string faster_assumptions_text(const imap::isa::MachineConfig& cfg) {
    std::string s;
    for (const imap::isa::ParamInfo& p : cfg.list()) {
        if (!p.faster) continue;
        if (!s.empty()) s += ", ";
        s += p.name + " " + p.value + (p.unit.empty() ? "" : " " + p.unit);
    }
    return s;
}

nlohmann::json algo_params_json(const g::Params& p) {
    nlohmann::json j = {{"D", p.D},
                        {"km", p.km},
                        {"kb", p.kb},
                        {"gb", p.gb},
                        {"Wo", p.Wo},
                        {"Wd", p.Wd},
                        {"mode", g::to_string(p.mode)},
                        {"seed_col", g::seed_col_string(p.seed_col)},
                        {"seed_disp", g::seed_disp_string(p.seed_disp)},
                        {"vote", p.vote},
                        {"frame", g::to_string(p.frame)}};
    if (g::uses_options(p)) {  // SPEC A.9 (absent for the paper's algorithm)
        j["dissim"] = g::to_string(p.dissim);
        j["ad_max"] = p.ad_max;
        j["kc"] = p.kc;
        j["census"] = p.census;
        j["agg_rx"] = p.agg_rx;
        j["agg_ry"] = p.agg_ry;
    }
    return j;
}

void add_algo_flags(CLI::App* app, AlgoFlags& f) {
    const g::Params d;
    const g::Params q = g::preset("quality");
    AlgoFlags* fp = &f;
    auto opt = [&](const char* name, std::string& dst, const std::string& help,
                   const std::string& def, const char* group = "Algorithm (SPEC A.1)") {
        const std::string flag = name;
        app->add_option(name, dst, help + " [default: " + def + "]")
            ->group(group)
            ->each([fp, flag](const std::string&) { fp->given.insert(flag); });
    };
    opt("--preset", f.preset,
        "starting values of all algorithm flags: paper (SPEC A.1-A.7) or quality (SPEC A.9 "
        "options, docs/golden.md); flags given override them",
        "paper");
    opt("--D", f.D, "disparity levels 0..D-1 (1..min(ROI width, 255))", std::to_string(d.D));
    opt("--km", f.km, "match weight on |R - L| (0..1000000)", std::to_string(d.km));
    opt("--kb", f.kb, "match weight on gb - min(R, L) (0..1000000)", std::to_string(d.kb));
    opt("--gb", f.gb, "intensity upper bound (0..255)", std::to_string(d.gb));
    opt("--Wo", f.Wo, "occlusion cost (Wd..1000000)", std::to_string(d.Wo));
    opt("--Wd", f.Wd, "discontinuity cost (0..Wo)", std::to_string(d.Wd));
    opt("--mode", f.mode,
        "single (one wavefront per line), bidir (two) or joint (two, meeting exactly; SPEC A.9)",
        "bidir");
    opt("--seed-col", f.seed_col, "bidir/joint seed column: balanced, center or 1..N-1",
        "balanced");
    opt("--seed-disp", f.seed_disp, "bidir/joint seed disparity: free or 0..D-1 (s + ds < N)",
        "free");
    opt("--vote", f.vote, "inter-scanline majority vote: on or off", "on");
    opt("--roi", f.roi, "region of interest x0,y0,w,h", "whole image");
    opt("--frame", f.frame, "output frame: cyc (cyclopean), left or right", "cyc");
    app->add_flag("--fill", f.fill, "replace occluded pixels (255) by the background fill")
        ->group("Algorithm (SPEC A.1)");
    const char* a9 = "Quality options (SPEC A.9, docs/golden.md)";
    const std::string qd = " (quality: ";
    opt("--dissim", f.dissim,
        "pixel dissimilarity of the km term: ad (|R - L|) or bt (Birchfield-Tomasi)",
        std::string(g::to_string(d.dissim)) + qd + g::to_string(q.dissim) + ")", a9);
    opt("--ad-max", f.ad_max, "truncation of the km term's dissimilarity (0..255; 255 = none)",
        std::to_string(d.ad_max) + qd + std::to_string(q.ad_max) + ")", a9);
    opt("--kc", f.kc, "match weight on the census Hamming distance (0..1000000; 0 = off)",
        std::to_string(d.kc) + qd + std::to_string(q.kc) + ")", a9);
    opt("--census", f.census, "census neighbour distance: 1 (3x3) or 2 (5x5)",
        std::to_string(d.census) + qd + std::to_string(q.census) + ")", a9);
    opt("--agg-rx", f.agg_rx, "match cost summed over sites i-rx..i+rx (0..7)",
        std::to_string(d.agg_rx) + qd + std::to_string(q.agg_rx) + ")", a9);
    opt("--agg-ry", f.agg_ry, "... and over ROI lines y-ry..y+ry (0..7)",
        std::to_string(d.agg_ry) + qd + std::to_string(q.agg_ry) + ")", a9);
}

g::Params parse_algo_flags(const AlgoFlags& f, g::Roi* roi, bool* has_roi) {
    g::Params p;
    if (!f.preset.empty()) {
        if (f.preset != "paper" && f.preset != "quality")
            throw UserError("invalid value '" + f.preset + "' for --preset: expected " +
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
        throw UserError("invalid value '" + f.dissim + "' for --dissim: expected ad or bt");

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
            throw UserError("invalid value '" + f.mode +
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
        throw UserError("invalid value '" + f.vote + "' for --vote: expected on or off");

    if (!set("--frame", f.frame, "cyc")) {
        // the preset's
    } else if (f.frame == "cyc" || f.frame == "cyclopean")
        p.frame = g::Frame::Cyclopean;
    else if (f.frame == "left")
        p.frame = g::Frame::Left;
    else if (f.frame == "right")
        p.frame = g::Frame::Right;
    else
        throw UserError("invalid value '" + f.frame + "' for --frame: expected cyc, left or right");

    *has_roi = !f.roi.empty();
    if (*has_roi) {
        std::vector<std::string> parts;
        std::stringstream ss(f.roi);
        std::string item;
        while (std::getline(ss, item, ',')) parts.push_back(item);
        if (parts.size() != 4 || f.roi.back() == ',')
            throw UserError("invalid value '" + f.roi + "' for --roi: expected x0,y0,w,h");
        roi->x0 = static_cast<int>(parse_int_flag("--roi x0", parts[0], 0, 1 << 20));
        roi->y0 = static_cast<int>(parse_int_flag("--roi y0", parts[1], 0, 1 << 20));
        roi->w = static_cast<int>(parse_int_flag("--roi w", parts[2], 1, 1 << 20));
        roi->h = static_cast<int>(parse_int_flag("--roi h", parts[3], 1, 1 << 20));
    }
    try {
        g::validate_params(p);
    } catch (const g::ParamError& e) {
        throw UserError(e.what());
    }
    return p;
}

}  // namespace imapsim
