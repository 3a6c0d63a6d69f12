#include "imap/vision/scene.hpp"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <optional>
#include <sstream>

#include "imap/vision/image_io.hpp"

namespace imap::vision {

namespace fs = std::filesystem;
using nlohmann::json;

namespace {

struct SceneFiles {
    std::string left = "left.png", right = "right.png", gt = "gt.png";
    std::string nonocc = "nonocc.png", all = "all.png", disc = "disc.png";
};

struct Catalog {
    std::string path;  // scenes.json used, empty if none
    SceneFiles files;
    std::optional<double> gt_scale;
    std::optional<int> ndisp;
};

std::string folder_name(const std::string& dir) {
    fs::path p = fs::absolute(fs::path(dir)).lexically_normal();
    if (p.filename().empty()) p = p.parent_path();
    return p.filename().string();
}

// Reads the entry for `name` from the first scenes.json found in `dir` or its parent.
Catalog read_catalog(const std::string& dir, const std::string& name) {
    Catalog c;
    const fs::path here = fs::absolute(fs::path(dir)).lexically_normal();
    const fs::path folder = here.filename().empty() ? here.parent_path() : here;
    std::error_code ec;
    for (const fs::path& cand : {folder / "scenes.json", folder.parent_path() / "scenes.json"}) {
        if (!fs::is_regular_file(cand, ec)) continue;
        c.path = cand.string();
        std::ifstream in(cand);
        json j;
        try {
            if (!in) throw std::runtime_error("cannot open");
            in >> j;
            if (j.contains("files")) {
                const json& f = j.at("files");
                auto take = [](const json& o, const char* key, std::string& dst) {
                    if (o.contains(key)) dst = o.at(key).get<std::string>();
                };
                take(f, "left", c.files.left);
                take(f, "right", c.files.right);
                take(f, "gt", c.files.gt);
                if (f.contains("masks")) {
                    take(f.at("masks"), "nonocc", c.files.nonocc);
                    take(f.at("masks"), "all", c.files.all);
                    take(f.at("masks"), "disc", c.files.disc);
                }
            }
            if (j.contains("scenes") && j.at("scenes").contains(name)) {
                const json& e = j.at("scenes").at(name);
                if (e.contains("gt_scale")) c.gt_scale = e.at("gt_scale").get<double>();
                if (e.contains("ndisp")) c.ndisp = e.at("ndisp").get<int>();
            }
        } catch (const std::exception& e) {
            std::string what = e.what();
            if (const auto nl = what.find('\n'); nl != std::string::npos) what.resize(nl);
            throw InputError("scene catalog '" + c.path + "': malformed (" + what + ")");
        }
        break;
    }
    return c;
}

std::string size_text(const cv::Mat& m) {
    return std::to_string(m.cols) + "x" + std::to_string(m.rows);
}

}  // namespace

Scene load_scene(const std::string& dir, double gt_scale_override, int ndisp_override) {
    std::error_code ec;
    if (!fs::exists(dir, ec)) throw InputError("scene folder '" + dir + "': not found");
    if (!fs::is_directory(dir, ec)) throw InputError("scene folder '" + dir + "': not a folder");

    Scene sc;
    sc.dir = dir;
    sc.name = folder_name(dir);
    const Catalog cat = read_catalog(dir, sc.name);
    if (!fs::exists(fs::path(dir) / cat.files.left, ec)) {
        // A data folder given as a scene: name what is in it and the flag
        // that scores it, before asking for a scale or a disparity range.
        std::vector<std::string> scenes;
        try {
            for (const std::string& p : list_scene_dirs(dir)) scenes.push_back(folder_name(p));
        } catch (const InputError&) {
            // an unlistable folder: the plain message below
        }
        const int n = static_cast<int>(scenes.size());
        std::string inside;
        for (int i = 0; i < std::min(n, 4); ++i) inside += (i ? ", " : "") + scenes[size_t(i)];
        if (n > 0)
            throw InputError("scene folder '" + dir + "': not a scene folder (no " +
                             cat.files.left + "); it holds " + std::to_string(n) +
                             " scene folder(s) (" + inside + (n > 4 ? ", ..." : "") +
                             "): give one of them, e.g. '" + (fs::path(dir) / scenes[0]).string() +
                             "', or score them all with eval --all " + dir);
        throw InputError("scene folder '" + dir + "': not a scene folder (no " + cat.files.left +
                         " in it)");
    }
    const std::string where = cat.path.empty()
                                  ? std::string("no scenes.json in the folder or its parent")
                                  : "no entry for it in '" + cat.path + "'";

    if (gt_scale_override > 0)
        sc.gt_scale = gt_scale_override;
    else if (cat.gt_scale)
        sc.gt_scale = *cat.gt_scale;
    else
        throw InputError("scene folder '" + dir + "': ground-truth scale unknown (" + where +
                         "); give it explicitly with --gt-scale");
    if (!(sc.gt_scale > 0))
        throw InputError("scene folder '" + dir + "': gt_scale must be positive");
    if (ndisp_override > 0)
        sc.ndisp = ndisp_override;
    else if (cat.ndisp)
        sc.ndisp = *cat.ndisp;
    else
        throw InputError("scene folder '" + dir + "': number of disparities unknown (" + where +
                         "); give it explicitly with --D");
    if (sc.ndisp < 1) throw InputError("scene folder '" + dir + "': ndisp must be at least 1");

    const fs::path d(dir);
    const std::string tag = "scene '" + sc.name + "' ";
    auto load = [&](const std::string& file, const std::string& role) {
        return load_grey8((d / file).string(), tag + role);
    };
    sc.left = load(cat.files.left, "left image");
    sc.right = load(cat.files.right, "right image");
    sc.gt = load(cat.files.gt, "ground truth");

    const bool any_mask = fs::exists(d / cat.files.nonocc, ec) ||
                          fs::exists(d / cat.files.all, ec) || fs::exists(d / cat.files.disc, ec);
    if (any_mask) {
        sc.nonocc = load(cat.files.nonocc, "mask");
        sc.all = load(cat.files.all, "mask");
        sc.disc = load(cat.files.disc, "mask");
    } else {
        sc.default_masks = true;
        sc.nonocc = cv::Mat(sc.left.size(), CV_8UC1, cv::Scalar(255));
        sc.all = sc.nonocc.clone();
        sc.disc = sc.nonocc.clone();
    }

    const std::pair<const cv::Mat*, const std::string*> others[] = {{&sc.right, &cat.files.right},
                                                                    {&sc.gt, &cat.files.gt},
                                                                    {&sc.nonocc, &cat.files.nonocc},
                                                                    {&sc.all, &cat.files.all},
                                                                    {&sc.disc, &cat.files.disc}};
    for (const auto& [m, file] : others)
        if (m->size() != sc.left.size())
            throw InputError("scene folder '" + dir + "': " + *file + " is " + size_text(*m) +
                             " but " + cat.files.left + " is " + size_text(sc.left));
    return sc;
}

std::vector<std::string> list_scene_dirs(const std::string& data_dir) {
    std::error_code ec;
    if (!fs::is_directory(data_dir, ec))
        throw InputError("data folder '" + data_dir + "': not found or not a folder");
    std::vector<std::string> out;
    try {
        for (const auto& e : fs::directory_iterator(data_dir)) {
            const std::string n = e.path().filename().string();
            if (n.empty() || n[0] == '.' || !e.is_directory(ec)) continue;
            const Catalog cat = read_catalog(e.path().string(), n);
            if (fs::exists(e.path() / cat.files.left, ec)) out.push_back(e.path().string());
        }
    } catch (const fs::filesystem_error& e) {
        throw InputError("data folder '" + data_dir + "': cannot list (" + e.code().message() +
                         ")");
    }
    std::sort(out.begin(), out.end());
    return out;
}

}  // namespace imap::vision
