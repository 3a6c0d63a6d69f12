// A stereo scene with ground truth and evaluation masks, laid out like the
// shared Middlebury data (shared/data/middlebury/README.md).
#pragma once

#include <opencv2/core.hpp>
#include <string>
#include <vector>

namespace imap::vision {

struct Scene {
    std::string name;            // folder name, the key in scenes.json
    std::string dir;             // folder as given
    cv::Mat left, right, gt;     // CV_8UC1 (colour inputs converted to grey); gt = d * gt_scale
    cv::Mat nonocc, all, disc;   // CV_8UC1 masks, 255 = evaluated
    double gt_scale = 0;         // gt value / gt_scale = disparity
    int ndisp = 0;               // disparities to search (0..ndisp-1)
    bool default_masks = false;  // no mask files: every pixel is evaluated in all three masks
};

// Reads a scene folder: left.png, right.png, gt.png and the masks nonocc.png,
// all.png, disc.png (names overridable by "files" in scenes.json). gt_scale
// and ndisp come from the "scenes" entry keyed by the folder name in a
// scenes.json found in the folder or its parent; a positive override wins.
// If none of the three mask files exists, every pixel is evaluated (e.g. a
// folder written by `imapsim synth`, with gt_scale 1). Throws InputError
// naming the folder or file on any problem (missing files, sizes that differ,
// unknown gt_scale or ndisp, malformed scenes.json).
Scene load_scene(const std::string& dir, double gt_scale_override = 0, int ndisp_override = 0);

// Scene folders under a data folder: every subfolder (not hidden) holding a
// left image, sorted by name. Throws InputError if `data_dir` is not a folder.
std::vector<std::string> list_scene_dirs(const std::string& data_dir);

}  // namespace imap::vision
