#include "imap/vision/sequence.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <set>
#include <stdexcept>

#include "imap/vision/image_io.hpp"
#include "synth_internal.hpp"

namespace imap::vision {

namespace fs = std::filesystem;
using detail::Object;
using detail::Rng;

namespace {

// ---------------------------------------------------------------------------
// Synthetic sequence

// An object and its straight path: top-left corner (xs, ys) at frame 0,
// (xs + tx, ys + ty) at the last frame.
struct MovingObject {
    Object o;
    int xs = 0, ys = 0;
    int64_t tx = 0, ty = 0;
};

// Everything about a sequence that does not change from frame to frame.
struct SequenceModel {
    int width = 0, height = 0, frames = 0;
    uint64_t noise_seed = 0;
    int max_disp = 0;
    cv::Mat bg;
    std::vector<MovingObject> objs;  // sorted by increasing disparity
};

// n / den rounded to the nearest integer, halves away from zero (den > 0).
int64_t div_round(int64_t n, int64_t den) {
    return n >= 0 ? (2 * n + den) / (2 * den) : -((-2 * n + den) / (2 * den));
}

void check_sequence_args(int width, int height, int k, int frames) {
    if (width < 16 || height < 16 || width > 65536 || height > 65536)
        throw std::invalid_argument("synthetic sequence: size " + std::to_string(width) + "x" +
                                    std::to_string(height) + " outside 16..65536");
    if (frames < 1)
        throw std::invalid_argument("synthetic sequence: frames " + std::to_string(frames) +
                                    " < 1");
    if (k < 0 || k >= frames)
        throw std::invalid_argument("synthetic sequence: frame " + std::to_string(k) +
                                    " outside 0.." + std::to_string(frames - 1));
}

SequenceModel build_model(uint64_t seed, int W, int H, int frames) {
    check_sequence_args(W, H, 0, frames);
    SequenceModel m;
    m.width = W;
    m.height = H;
    m.frames = frames;
    Rng rng(seed ^ 0x5EC0E4CE5A5EED01ull);
    m.noise_seed = rng.next();
    m.max_disp = std::min(kSequenceMaxDisp, W / 4);  // >= 4 for W >= 16
    m.bg = detail::make_texture(rng, W, H, 30, 150);

    const int n = rng.range(3, 5);
    const int64_t F1 = frames - 1;
    for (int k = 0; k < n; ++k) {
        MovingObject mo;
        Object& o = mo.o;
        // Disparities spread over 1..max_disp, jittered, the last one = max_disp
        // (the others stay below it: base + jit < max_disp).
        const int base = (m.max_disp * (k + 1) + n / 2) / n;
        const int jit = m.max_disp / (3 * n);
        o.d = k == n - 1 ? m.max_disp : std::clamp(base + rng.range(-jit, jit), 1, m.max_disp - 1);
        // Smaller than the single scene's objects, so that they have room to move.
        o.w = rng.range(std::max(2, W / 8), std::max(2, W / 4));
        o.h = rng.range(std::max(2, H / 6), std::max(2, H / 3));
        // Left edge in x_lo..x_hi for every frame: x >= d always, x >= 2d + 2
        // where it fits (see make_synth_scene), and inside the view.
        const int x_min = 2 * o.d + 2;
        o.w = std::max(1, std::min(o.w, W - x_min));
        const int x_lo = std::max(o.d, std::min(x_min, W - o.w)), x_hi = W - o.w;
        const int y_lo = 0, y_hi = H - o.h;
        o.disc = rng.range(0, 1) != 0;
        o.tex = detail::make_texture(rng, o.w, o.h, 80, 160);

        // Velocity in pixels per frame; the path over the whole sequence is
        // shortened (same direction) if it does not fit into the view.
        int vx = rng.range(-kSequenceMaxSpeedX, kSequenceMaxSpeedX);
        const int vy = rng.range(-kSequenceMaxSpeedY, kSequenceMaxSpeedY);
        if (vx == 0 && vy == 0) vx = 1;
        const int64_t tx = vx * F1, ty = vy * F1;
        const int64_t rx = x_hi - x_lo, ry = y_hi - y_lo;
        // Scale factor num / den = min(1, rx / |tx|, ry / |ty|).
        int64_t num = 1, den = 1;
        if (std::llabs(tx) > rx && rx * den < num * std::llabs(tx)) num = rx, den = std::llabs(tx);
        if (std::llabs(ty) > ry && ry * den < num * std::llabs(ty)) num = ry, den = std::llabs(ty);
        mo.tx = tx * num / den;  // truncates towards zero: stays within the range
        mo.ty = ty * num / den;
        mo.xs = rng.range(x_lo + static_cast<int>(std::max<int64_t>(0, -mo.tx)),
                          x_hi - static_cast<int>(std::max<int64_t>(0, mo.tx)));
        mo.ys = rng.range(y_lo + static_cast<int>(std::max<int64_t>(0, -mo.ty)),
                          y_hi - static_cast<int>(std::max<int64_t>(0, mo.ty)));
        m.objs.push_back(std::move(mo));
    }
    // Nearer (larger disparity) objects are drawn later, on top.
    std::stable_sort(m.objs.begin(), m.objs.end(),
                     [](const MovingObject& a, const MovingObject& b) { return a.o.d < b.o.d; });
    return m;
}

SequenceFrame render_frame(const SequenceModel& m, int k) {
    check_sequence_args(m.width, m.height, k, m.frames);
    const int64_t F1 = m.frames - 1;
    std::vector<Object> objs;
    objs.reserve(m.objs.size());
    for (const MovingObject& mo : m.objs) {
        Object o = mo.o;  // shares the texture
        o.x0 = mo.xs + static_cast<int>(F1 == 0 ? 0 : div_round(mo.tx * k, F1));
        o.y0 = mo.ys + static_cast<int>(F1 == 0 ? 0 : div_round(mo.ty * k, F1));
        objs.push_back(std::move(o));
    }
    // Per-frame noise, independent of the other frames.
    Rng noise(m.noise_seed ^ (static_cast<uint64_t>(k) * 0xD1B54A32D192ED03ull));
    SequenceFrame f;
    detail::render_views(m.bg, objs, noise, &f.left, &f.right, &f.gt);
    f.max_disp = m.max_disp;
    return f;
}

// ---------------------------------------------------------------------------
// Frame pairs in a folder

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

bool is_image_name(const std::string& name) {
    static const char* const kExt[] = {".png",  ".pgm",  ".ppm",  ".pnm", ".pbm",
                                       ".bmp",  ".jpg",  ".jpeg", ".jpe", ".tif",
                                       ".tiff", ".webp", ".jp2",  ".sr",  ".ras"};
    if (name.empty() || name[0] == '.') return false;
    const std::string ext = lower(fs::path(name).extension().string());
    return std::find(std::begin(kExt), std::end(kExt), ext) != std::end(kExt);
}

// "right" in the case style of the 4 characters `left` ("left", "Left", "LEFT").
std::string right_like(const std::string& left) {
    if (std::all_of(left.begin(), left.end(),
                    [](char c) { return std::isupper(static_cast<unsigned char>(c)); }))
        return "RIGHT";
    if (std::isupper(static_cast<unsigned char>(left[0]))) return "Right";
    return "right";
}

// The last run of digits in the file stem, without leading zeros ("" if none).
std::string last_number(const std::string& name) {
    const std::string stem = fs::path(name).stem().string();
    size_t end = stem.size();
    while (end > 0 && !std::isdigit(static_cast<unsigned char>(stem[end - 1]))) --end;
    if (end == 0) return "";
    size_t begin = end;
    while (begin > 0 && std::isdigit(static_cast<unsigned char>(stem[begin - 1]))) --begin;
    std::string num = stem.substr(begin, end - begin);
    const size_t nz = num.find_first_not_of('0');
    return nz == std::string::npos ? "0" : num.substr(nz);
}

bool pair_before(const FramePair& a, const FramePair& b) {
    const std::string na = last_number(a.name), nb = last_number(b.name);
    if (na.empty() != nb.empty()) return na.empty();
    if (na.size() != nb.size()) return na.size() < nb.size();
    if (na != nb) return na < nb;
    return a.name < b.name;
}

bool is_dir(const fs::path& p) {
    std::error_code ec;
    return fs::is_directory(p, ec);
}

bool is_file(const fs::path& p) {
    std::error_code ec;
    return fs::is_regular_file(p, ec);
}

// Sorted names of the non-hidden image files in `dir`.
std::vector<std::string> image_files(const fs::path& dir, const std::string& who) {
    std::vector<std::string> names;
    std::error_code ec;
    fs::directory_iterator it(dir, ec), end;
    if (ec) throw InputError(who + ": cannot list (" + ec.message() + ")");
    for (; it != end; it.increment(ec)) {
        if (ec) throw InputError(who + ": cannot list (" + ec.message() + ")");
        const std::string name = it->path().filename().string();
        if (is_image_name(name) && is_file(it->path())) names.push_back(name);
    }
    std::sort(names.begin(), names.end());
    return names;
}

// Subfolder of `dir` named `want` in any case ("left", "Left", ...), empty if none.
fs::path find_subdir(const fs::path& dir, const std::string& want) {
    std::error_code ec;
    fs::directory_iterator it(dir, ec), end;
    std::vector<std::string> hits;
    for (; !ec && it != end; it.increment(ec))
        if (lower(it->path().filename().string()) == want && is_dir(it->path()))
            hits.push_back(it->path().filename().string());
    if (hits.empty()) return {};
    std::sort(hits.begin(), hits.end());  // deterministic if several spellings exist
    return dir / hits.front();
}

}  // namespace

// ---------------------------------------------------------------------------

struct SequenceGenerator::Model : SequenceModel {
    explicit Model(SequenceModel m) : SequenceModel(std::move(m)) {}
};

SequenceGenerator::SequenceGenerator(uint64_t seed, int width, int height, int frames)
    : m_(std::make_shared<const Model>(build_model(seed, width, height, frames))) {}

int SequenceGenerator::frames() const {
    return m_->frames;
}

int SequenceGenerator::max_disp() const {
    return m_->max_disp;
}

SequenceFrame SequenceGenerator::frame(int k) const {
    return render_frame(*m_, k);
}

SequenceFrame make_sequence_frame(uint64_t seed, int width, int height, int k, int frames) {
    check_sequence_args(width, height, k, frames);
    return SequenceGenerator(seed, width, height, frames).frame(k);
}

StereoCalib make_synth_calib(cv::Size size) {
    if (size.width < 1 || size.height < 1 || size.width > 16384 || size.height > 16384)
        throw std::invalid_argument("make_synth_calib: size " + std::to_string(size.width) + "x" +
                                    std::to_string(size.height) + " outside 1..16384");
    const double W = size.width, H = size.height;
    const double f = 0.9 * W;  // horizontal field of view about 58 degrees
    StereoCalib c;
    c.size = size;
    c.K1 = (cv::Mat_<double>(3, 3) << f, 0, 0.5 * (W - 1) + 0.010 * W, 0, f,
            0.5 * (H - 1) - 0.008 * H, 0, 0, 1);
    c.K2 = (cv::Mat_<double>(3, 3) << f, 0, 0.5 * (W - 1) - 0.006 * W, 0, f,
            0.5 * (H - 1) + 0.005 * H, 0, 0, 1);
    // k1 k2 p1 p2 k3
    c.D1 = (cv::Mat_<double>(1, 5) << -0.05, 0.01, 0.001, -0.001, 0.0);
    c.D2 = (cv::Mat_<double>(1, 5) << -0.04, 0.008, -0.0008, 0.0012, 0.0);
    const double deg = CV_PI / 180.0;
    const cv::Mat rvec = (cv::Mat_<double>(3, 1) << 0.0, 0.5 * deg, 0.3 * deg);
    cv::Rodrigues(rvec, c.R);
    c.T = (cv::Mat_<double>(3, 1) << -0.1, 0.001, 0.002);
    return c;
}

namespace {

// For every raw pixel of one camera, its position in the rectified view
// (CV_32FC1 x and y maps for cv::remap).
struct RawToRect {
    cv::Mat x, y;
};

RawToRect raw_to_rect(cv::Size size, const cv::Mat& K, const cv::Mat& D, const cv::Mat& Rn,
                      const cv::Mat& Pn) {
    std::vector<cv::Point2f> pts;
    pts.reserve(static_cast<size_t>(size.area()));
    for (int v = 0; v < size.height; ++v)
        for (int u = 0; u < size.width; ++u)
            pts.emplace_back(static_cast<float>(u), static_cast<float>(v));
    std::vector<cv::Point2f> rp;
    // Iterate to convergence (the default is a fixed 5 iterations).
    cv::undistortPoints(
        pts, rp, K, D, Rn, Pn,
        cv::TermCriteria(cv::TermCriteria::COUNT | cv::TermCriteria::EPS, 50, 1e-9));
    RawToRect m{cv::Mat(size, CV_32FC1), cv::Mat(size, CV_32FC1)};
    for (int v = 0; v < size.height; ++v) {
        float* X = m.x.ptr<float>(v);
        float* Y = m.y.ptr<float>(v);
        for (int u = 0; u < size.width; ++u) {
            const cv::Point2f& p = rp[static_cast<size_t>(v) * size.width + u];
            X[u] = p.x;
            Y[u] = p.y;
        }
    }
    return m;
}

// Both cameras' maps of a rectifier, computed once per sequence.
struct UnrectifyMaps {
    RawToRect left, right;
    explicit UnrectifyMaps(const Rectifier& r)
        : left(raw_to_rect(r.size(), r.calib().K1, r.calib().D1, r.R1(), r.P1())),
          right(raw_to_rect(r.size(), r.calib().K2, r.calib().D2, r.R2(), r.P2())) {}
};

void apply_unrectify(const Rectifier& r, const UnrectifyMaps& maps, const cv::Mat& left_rect,
                     const cv::Mat& right_rect, cv::Mat* left_raw, cv::Mat* right_raw) {
    const cv::Size size = r.size();
    for (const auto& [rect, what] :
         {std::pair{&left_rect, "left"}, std::pair{&right_rect, "right"}}) {
        if (rect->type() != CV_8UC1 || rect->size() != size)
            throw InputError(std::string("unrectify: ") + what + " rectified image " +
                             std::to_string(rect->cols) + "x" + std::to_string(rect->rows) +
                             (rect->type() != CV_8UC1 ? " (not 8-bit grey)" : "") +
                             ": expected 8-bit grey " + std::to_string(size.width) + "x" +
                             std::to_string(size.height));
    }
    cv::Mat l, rr;  // remap cannot work in place (the outputs may alias the inputs)
    cv::remap(left_rect, l, maps.left.x, maps.left.y, cv::INTER_LINEAR, cv::BORDER_CONSTANT,
              cv::Scalar(0));
    cv::remap(right_rect, rr, maps.right.x, maps.right.y, cv::INTER_LINEAR, cv::BORDER_CONSTANT,
              cv::Scalar(0));
    *left_raw = l;
    *right_raw = rr;
}

}  // namespace

void unrectify(const Rectifier& r, const cv::Mat& left_rect, const cv::Mat& right_rect,
               cv::Mat* left_raw, cv::Mat* right_raw) {
    apply_unrectify(r, UnrectifyMaps(r), left_rect, right_rect, left_raw, right_raw);
}

std::vector<FramePair> list_frame_pairs(const std::string& dir) {
    const std::string who = "frame folder '" + dir + "'";
    const fs::path root(dir);
    if (!is_dir(root)) throw InputError(who + ": not a folder (missing or not a directory)");
    std::vector<FramePair> pairs;

    const fs::path ldir = find_subdir(root, "left"), rdir = find_subdir(root, "right");
    const bool subfolders = !ldir.empty() && !rdir.empty();
    if (subfolders) {
        // left/ and right/ subfolders: equal file names.
        for (const std::string& name : image_files(ldir, who)) {
            FramePair p;
            p.name = name;
            p.left = (ldir / name).string();
            const fs::path rp = rdir / name;
            if (is_file(rp))
                p.right = rp.string();
            else
                p.error = "no right frame '" + rp.string() + "' for left frame '" + p.left + "'";
            pairs.push_back(std::move(p));
        }
    } else {
        for (const std::string& name : image_files(root, who)) {
            const std::string low = lower(name);
            size_t pos = low.find("left");
            if (pos == std::string::npos) continue;
            FramePair p;
            p.name = name;
            p.left = (root / name).string();
            std::string first_candidate;
            for (; pos != std::string::npos; pos = low.find("left", pos + 1)) {
                const std::string rname =
                    name.substr(0, pos) + right_like(name.substr(pos, 4)) + name.substr(pos + 4);
                const fs::path rp = root / rname;
                if (first_candidate.empty()) first_candidate = rp.string();
                if (is_file(rp)) {
                    p.right = rp.string();
                    break;
                }
            }
            if (p.right.empty())
                p.error =
                    "no right frame '" + first_candidate + "' for left frame '" + p.left + "'";
            pairs.push_back(std::move(p));
        }
    }
    // A file that is the right frame of another pair is not a left frame
    // itself (e.g. "cleft_right_4.png", partner of "cleft_left_4.png").
    std::set<std::string> rights;
    for (const FramePair& p : pairs)
        if (!p.right.empty()) rights.insert(p.right);
    pairs.erase(std::remove_if(pairs.begin(), pairs.end(),
                               [&](const FramePair& p) { return rights.count(p.left) != 0; }),
                pairs.end());
    if (pairs.empty())
        throw InputError(who + (subfolders ? ": no image files in '" + ldir.string() +
                                                 "' (need left/ and right/ frames with equal "
                                                 "names)"
                                           : std::string(": no frame pairs (need image files "
                                                         "named like left_0000.png and "
                                                         "right_0000.png, or left/ and right/ "
                                                         "subfolders)")));
    std::sort(pairs.begin(), pairs.end(), pair_before);
    return pairs;
}

int write_sequence(const std::string& dir, uint64_t seed, int width, int height, int frames,
                   const std::string& calib_file, const std::function<void(int)>& on_frame) {
    const SequenceGenerator gen(seed, width, height, frames);
    std::error_code ec;
    const fs::path out(dir);
    if (fs::exists(out, ec) && !is_dir(out))
        throw InputError("output folder '" + dir + "': exists and is not a folder");
    fs::create_directories(out, ec);
    if (ec) throw InputError("output folder '" + dir + "': cannot create (" + ec.message() + ")");

    std::unique_ptr<Rectifier> rect;
    std::unique_ptr<UnrectifyMaps> maps;
    if (!calib_file.empty()) {
        const StereoCalib c = make_synth_calib(cv::Size(width, height));
        write_stereo_calib(calib_file, c);
        rect = std::make_unique<Rectifier>(c);
        maps = std::make_unique<UnrectifyMaps>(*rect);
    }
    for (int k = 0; k < frames; ++k) {
        const SequenceFrame f = gen.frame(k);
        char num[16];
        std::snprintf(num, sizeof num, "%04d", k);
        cv::Mat left = f.left, right = f.right;
        if (rect) apply_unrectify(*rect, *maps, f.left, f.right, &left, &right);
        write_image_atomic((out / ("left_" + std::string(num) + ".png")).string(), left);
        write_image_atomic((out / ("right_" + std::string(num) + ".png")).string(), right);
        write_image_atomic((out / ("gt_" + std::string(num) + ".png")).string(), f.gt);
        if (on_frame) on_frame(k + 1);
    }
    return gen.max_disp();
}

}  // namespace imap::vision
