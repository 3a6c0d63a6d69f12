#include "imap/vision/calib.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/calib3d.hpp>
#include <opencv2/imgproc.hpp>
#include <tuple>
#include <vector>

namespace imap::vision {

namespace fs = std::filesystem;

namespace {

// Largest calibration file read (they are a few kB).
constexpr std::uintmax_t kMaxCalibBytes = 16u << 20;
// Largest image side of a calibration.
constexpr int kMaxCalibSide = 16384;
// Tolerance of the rotation check |R^T R - I|max.
constexpr double kRotationTol = 1e-3;

std::string num(double v) {
    if (std::isnan(v)) return "NaN";
    if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    return buf;
}

std::string dims(const cv::Mat& m) {
    return std::to_string(m.rows) + "x" + std::to_string(m.cols);
}

// Errors about one calibration: "<who>: <what>" on one line.
struct Ctx {
    std::string who;  // e.g. "calibration 'file.yml'"
    [[noreturn]] void fail(const std::string& what) const { throw InputError(who + ": " + what); }
    [[noreturn]] void fail_key(const std::string& key, const std::string& what) const {
        fail("key '" + key + "': " + what);
    }
};

// The readable part of an OpenCV exception: parse errors carry the line as
// "(N): message" in `func`; other errors their message in `err`. Line
// numbers are reduced by `added_lines` (lines the loader put in front).
std::string opencv_reason(const cv::Exception& e, int added_lines = 0) {
    std::string s = e.code == cv::Error::StsParseError && !e.func.empty() ? e.func : e.err;
    if (s.size() > 2 && s[0] == '(') {
        const auto close = s.find("): ");
        if (close != std::string::npos && close > 1 && close < 10 &&
            s.find_first_not_of("0123456789", 1) == close)
            s = "line " + std::to_string(std::stol(s.substr(1, close - 1)) - added_lines) + ": " +
                s.substr(close + 3);
    }
    for (char& c : s)
        if (c == '\n' || c == '\r') c = ' ';
    while (!s.empty() && s.back() == ' ') s.pop_back();
    return s.empty() ? "unknown OpenCV error" : s;
}

// Inputs that crash OpenCV 4.6's parsers instead of raising an error, found
// by feeding it damaged calibration files; the loader refuses them first.
// YAML: an unquoted empty key ("  : 3", "{ : 2}") inside a nested map makes
// the parser throw while unwinding (std::terminate). Returns its line (1 =
// first line of `text`), 0 if there is none.
int yaml_empty_key_line(const std::string& text) {
    char quote = 0, prev = '\n';
    bool comment = false;
    int line = 1;
    for (size_t i = 0; i < text.size(); ++i) {
        const char c = text[i];
        if (c == '\n') {
            ++line;
            comment = false;
            quote = 0;
            prev = '\n';
            continue;
        }
        if (comment) continue;
        if (quote != 0) {
            if (c == '\\' && quote == '"')
                ++i;
            else if (c == quote)
                quote = 0;
            prev = 'x';
            continue;
        }
        if (c == '"' || c == '\'') {
            quote = c;
            prev = 'x';
            continue;
        }
        if (c == '#') {
            comment = true;
            continue;
        }
        if (c == ' ' || c == '\t' || c == '\r') continue;
        if (c == ':' && (prev == '\n' || prev == '{' || prev == ',')) return line;
        prev = c;
    }
    return 0;
}

// XML: the end of the text right after "attribute=" dereferences a null
// pointer in the tag parser.
bool xml_ends_in_attribute(const std::string& text) {
    size_t e = text.size();
    while (e > 0 && std::isspace(static_cast<unsigned char>(text[e - 1]))) --e;
    return e > 0 && text[e - 1] == '=';
}

// Converts to a single-channel CV_64F matrix; every value finite.
cv::Mat as_double(const Ctx& cx, const std::string& key, const cv::Mat& m) {
    if (m.empty()) cx.fail_key(key, "empty matrix");
    if (m.dims != 2) cx.fail_key(key, "expected a 2-D matrix");
    if (m.channels() != 1)
        cx.fail_key(key, "expected a single-channel matrix, got " + std::to_string(m.channels()) +
                             " channels");
    cv::Mat d;
    m.convertTo(d, CV_64F);
    for (int r = 0; r < d.rows; ++r)
        for (int c = 0; c < d.cols; ++c) {
            const double v = d.at<double>(r, c);
            if (!std::isfinite(v))
                cx.fail_key(key, "value " + num(v) + " at (" + std::to_string(r) + "," +
                                     std::to_string(c) + ")");
        }
    return d;
}

cv::Mat check_camera_matrix(const Ctx& cx, const std::string& key, const cv::Mat& m) {
    if (m.rows != 3 || m.cols != 3) cx.fail_key(key, "expected a 3x3 matrix, got " + dims(m));
    const cv::Mat K = as_double(cx, key, m);
    const double fx = K.at<double>(0, 0), fy = K.at<double>(1, 1);
    if (!(fx > 0)) cx.fail_key(key, "focal length fx = " + num(fx) + " must be > 0");
    if (!(fy > 0)) cx.fail_key(key, "focal length fy = " + num(fy) + " must be > 0");
    if (std::abs(K.at<double>(1, 0)) > 1e-9 || std::abs(K.at<double>(2, 0)) > 1e-9 ||
        std::abs(K.at<double>(2, 1)) > 1e-9 || std::abs(K.at<double>(2, 2) - 1) > 1e-9)
        cx.fail_key(key, "not a camera matrix (expected the form [fx s cx; 0 fy cy; 0 0 1])");
    return K;
}

cv::Mat check_distortion(const Ctx& cx, const std::string& key, const cv::Mat& m) {
    const int n = static_cast<int>(m.total());
    const bool vec = m.rows == 1 || m.cols == 1;
    if (!vec || (n != 4 && n != 5 && n != 8 && n != 12 && n != 14))
        cx.fail_key(
            key, "expected 4, 5, 8, 12 or 14 distortion coefficients (1xN or Nx1), got " + dims(m));
    return as_double(cx, key, m).reshape(1, 1).clone();
}

cv::Mat check_rotation(const Ctx& cx, const std::string& key, const cv::Mat& m) {
    if (m.rows != 3 || m.cols != 3) cx.fail_key(key, "expected a 3x3 matrix, got " + dims(m));
    const cv::Mat R = as_double(cx, key, m);
    const cv::Mat E = R.t() * R - cv::Mat::eye(3, 3, CV_64F);
    double err = 0;
    cv::minMaxIdx(cv::abs(E), nullptr, &err);
    if (err > kRotationTol)
        cx.fail_key(key, "not a rotation matrix (max |R^T R - I| = " + num(err) + " > " +
                             num(kRotationTol) + ")");
    const double det = cv::determinant(R);
    if (!(det > 0))
        cx.fail_key(key, "not a rotation matrix (det(R) = " + num(det) + ", a reflection)");
    return R;
}

cv::Mat check_translation(const Ctx& cx, const std::string& key, const cv::Mat& m) {
    if (!((m.rows == 3 && m.cols == 1) || (m.rows == 1 && m.cols == 3)))
        cx.fail_key(key, "expected a 3x1 or 1x3 vector, got " + dims(m));
    const cv::Mat T = as_double(cx, key, m).reshape(1, 3).clone();
    if (!(cv::norm(T) > 0)) cx.fail_key(key, "zero baseline (|T| = 0)");
    return T;
}

// `what` names the key(s), e.g. "key 'image_size'".
void check_size(const Ctx& cx, const std::string& what, double w, double h) {
    for (const double v : {w, h})
        if (!(v >= 1 && v <= kMaxCalibSide) || v != std::floor(v))
            cx.fail(what + ": image size " + num(w) + "x" + num(h) + ": expected integers in 1.." +
                    std::to_string(kMaxCalibSide));
}

// Validates and normalises a calibration (CV_64F, D 1xN, T 3x1).
StereoCalib checked(const Ctx& cx, const StereoCalib& c) {
    StereoCalib o;
    o.K1 = check_camera_matrix(cx, "K1", c.K1);
    o.D1 = check_distortion(cx, "D1", c.D1);
    o.K2 = check_camera_matrix(cx, "K2", c.K2);
    o.D2 = check_distortion(cx, "D2", c.D2);
    o.R = check_rotation(cx, "R", c.R);
    o.T = check_translation(cx, "T", c.T);
    check_size(cx, "keys 'image_width' and 'image_height'", c.size.width, c.size.height);
    o.size = c.size;
    return o;
}

// ---------------------------------------------------------------------------
// Reading

// A matrix from a node: an opencv-matrix map, a sequence of numbers (1xN),
// a sequence of equally long sequences of numbers (rows), or a number (1x1).
cv::Mat read_matrix(const Ctx& cx, const std::string& key, const cv::FileNode& n) {
    const std::string expect = "expected a matrix (opencv-matrix, [a, b, ...] or [[a, b], [c, d]])";
    if (n.isMap()) {
        const cv::FileNode rows = n["rows"], cols = n["cols"];
        if (!rows.isInt() || !cols.isInt() || n["data"].empty())
            cx.fail_key(key, expect + ", got a map without integer rows, cols and data");
        const int r = static_cast<int>(rows), c = static_cast<int>(cols);
        if (r < 1 || c < 1 || r > 64 || c > 64)
            cx.fail_key(key, "matrix of " + std::to_string(r) + "x" + std::to_string(c) +
                                 " (unexpected size)");
        const cv::FileNode data = n["data"], dt = n["dt"];
        const bool one_channel =
            dt.isString() && !static_cast<std::string>(dt).empty() &&
            !std::isdigit(static_cast<unsigned char>(static_cast<std::string>(dt)[0]));
        if (one_channel && data.isSeq() && static_cast<int>(data.size()) != r * c)
            cx.fail_key(key, "malformed matrix (" + std::to_string(r) + "x" + std::to_string(c) +
                                 " with " + std::to_string(data.size()) + " data values)");
        cv::Mat m;
        try {
            n >> m;
        } catch (const cv::Exception& e) {
            cx.fail_key(key, "malformed matrix (" + opencv_reason(e) + ")");
        }
        if (m.empty()) cx.fail_key(key, "malformed matrix (no data)");
        return m;
    }
    auto number = [&](const cv::FileNode& v, double* out) {
        if (!v.isInt() && !v.isReal()) return false;
        *out = static_cast<double>(v);
        return true;
    };
    if (n.isInt() || n.isReal()) return cv::Mat(1, 1, CV_64F, cv::Scalar(static_cast<double>(n)));
    if (!n.isSeq()) cx.fail_key(key, expect + (n.isString() ? ", got text" : ""));
    const int rows = static_cast<int>(n.size());
    if (rows < 1 || rows > 64)
        cx.fail_key(key, expect + ", got " + std::to_string(rows) + " items");
    std::vector<std::vector<double>> vals;
    bool nested = n[0].isSeq();
    for (int r = 0; r < rows; ++r) {
        const cv::FileNode item = n[r];
        std::vector<double> row;
        if (nested) {
            if (!item.isSeq() || item.size() < 1 || item.size() > 64)
                cx.fail_key(key, expect + " (row " + std::to_string(r) + " is not a list)");
            for (size_t c = 0; c < item.size(); ++c) {
                double v = 0;
                if (!number(item[static_cast<int>(c)], &v))
                    cx.fail_key(key, expect + " (item " + std::to_string(r) + "," +
                                         std::to_string(c) + " is not a number)");
                row.push_back(v);
            }
            if (!vals.empty() && row.size() != vals[0].size())
                cx.fail_key(key, "rows of different lengths");
        } else {
            double v = 0;
            if (!number(item, &v))
                cx.fail_key(key, expect + " (item " + std::to_string(r) + " is not a number)");
            row.push_back(v);
        }
        vals.push_back(std::move(row));
    }
    cv::Mat m;
    if (nested) {
        m.create(rows, static_cast<int>(vals[0].size()), CV_64F);
        for (int r = 0; r < m.rows; ++r)
            for (int c = 0; c < m.cols; ++c) m.at<double>(r, c) = vals[r][c];
    } else {
        m.create(1, rows, CV_64F);
        for (int c = 0; c < rows; ++c) m.at<double>(0, c) = vals[c][0];
    }
    return m;
}

// The node of the first key present in `keys`; fails naming all of them.
cv::FileNode find_key(const Ctx& cx, const cv::FileNode& root, const std::vector<std::string>& keys,
                      std::string* used) {
    for (const std::string& k : keys) {
        const cv::FileNode n = root[k];
        if (!n.empty() && !n.isNone()) {
            *used = k;
            return n;
        }
    }
    std::string msg = "missing key '" + keys[0] + "'";
    if (keys.size() > 1) {
        msg += " (also accepted: ";
        for (size_t i = 1; i < keys.size(); ++i) msg += (i > 1 ? ", " : "") + keys[i];
        msg += ")";
    }
    cx.fail(msg);
}

// True when OpenCV's YAML parser cannot get past the text's first
// document: nothing but blank and comment lines after a "..." end marker or
// a second "---", and no line indented less than the first key (the root
// map would end there). OpenCV 4.6's YAMLParser::parse() loops forever when,
// looking for a second document, it meets a "-" that does not start "---".
bool yaml_single_document(const std::string& text) {
    int root = -1;
    bool started = false, ended = false;
    size_t b = 0;
    while (b < text.size()) {
        size_t e = text.find('\n', b);
        if (e == std::string::npos) e = text.size();
        std::string l = text.substr(b, e - b);
        b = e + 1;
        if (!l.empty() && l.back() == '\r') l.pop_back();
        const size_t p = l.find_first_not_of(" \t");
        if (p == std::string::npos || l[p] == '#') continue;
        if (l[0] == '%') {
            if (root >= 0 || started) return false;
            continue;
        }
        if (ended) return false;
        if (l.compare(0, 3, "...") == 0) {
            ended = true;
            continue;
        }
        size_t q = p;
        if (l.compare(0, 3, "---") == 0) {
            if (started || root >= 0) return false;
            started = true;
            q = l.find_first_not_of(" \t", 3);
            if (q == std::string::npos || l[q] == '#') continue;
        }
        if (root < 0)
            root = static_cast<int>(q);
        else if (static_cast<int>(q) < root)
            return false;
    }
    return true;
}

// The calibration's text, with a "%YAML:1.0" first line added to YAML that
// lacks it (OpenCV requires it; *added_lines = 1 then); XML and JSON are
// recognised by content. Refuses what OpenCV's parsers cannot survive.
std::string read_text(const Ctx& cx, const std::string& path, int* added_lines) {
    std::error_code ec;
    const fs::path p(path);
    if (fs::is_directory(p, ec)) cx.fail("is a directory, not a calibration file");
    if (!fs::exists(p, ec)) cx.fail("cannot read (no such file)");
    const std::uintmax_t size = fs::file_size(p, ec);
    if (!ec && size > kMaxCalibBytes) cx.fail("too large for a calibration file");
    std::ifstream in(path, std::ios::binary);
    if (!in) cx.fail("cannot read (unreadable)");
    std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    if (in.bad()) cx.fail("cannot read (read error)");
    size_t b = text.compare(0, 3, "\xEF\xBB\xBF") == 0 ? 3 : 0;  // UTF-8 BOM
    // Leading blank lines are dropped; count them so that line numbers stay right.
    int dropped = 0;
    while (b < text.size() && std::isspace(static_cast<unsigned char>(text[b])))
        if (text[b++] == '\n') ++dropped;
    if (b == text.size()) cx.fail("empty file, not a calibration file");
    if (text.find('\0') != std::string::npos)
        cx.fail("not a calibration file (binary data, expected YAML, XML or JSON text)");
    text.erase(0, b);
    *added_lines = -dropped;
    const bool xml = text.compare(0, 5, "<?xml") == 0, json = text[0] == '{';
    if (!xml && !json && text.compare(0, 5, "%YAML") != 0) {
        text = "%YAML:1.0\n" + text;
        *added_lines += 1;
    }
    if (xml && xml_ends_in_attribute(text))
        cx.fail("not a calibration file (cannot parse: file ends inside a tag)");
    if (!xml && !json && !yaml_single_document(text))
        cx.fail(
            "not a calibration file (cannot parse: a second YAML document, or a line "
            "indented less than the first key)");
    if (!xml && !json) {
        const int line = yaml_empty_key_line(text);
        if (line > 0)
            cx.fail("not a calibration file (cannot parse: line " +
                    std::to_string(line - *added_lines) + ": empty key)");
    }
    return text;
}

// ---------------------------------------------------------------------------

std::string size_text(const cv::Size& s) {
    return std::to_string(s.width) + "x" + std::to_string(s.height);
}

}  // namespace

StereoCalib load_stereo_calib(const std::string& path) {
    const Ctx cx{"calibration '" + path + "'"};
    int added_lines = 0;
    const std::string text = read_text(cx, path, &added_lines);
    cv::FileStorage fs;
    try {
        fs.open(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
    } catch (const cv::Exception& e) {
        cx.fail("not a calibration file (cannot parse: " + opencv_reason(e, added_lines) + ")");
    }
    if (!fs.isOpened()) cx.fail("not a calibration file (cannot parse)");
    const cv::FileNode root = fs.root();
    if (!root.isMap() || root.size() == 0)
        cx.fail("not a calibration file (expected a map of keys K1, D1, K2, D2, R, T, image size)");

    StereoCalib c;
    try {
        std::string key;
        cv::FileNode n = find_key(cx, root, {"K1", "M1", "camera_matrix_left"}, &key);
        c.K1 = check_camera_matrix(cx, key, read_matrix(cx, key, n));
        n = find_key(cx, root, {"D1", "dist_left"}, &key);
        c.D1 = check_distortion(cx, key, read_matrix(cx, key, n));
        n = find_key(cx, root, {"K2", "M2", "camera_matrix_right"}, &key);
        c.K2 = check_camera_matrix(cx, key, read_matrix(cx, key, n));
        n = find_key(cx, root, {"D2", "dist_right"}, &key);
        c.D2 = check_distortion(cx, key, read_matrix(cx, key, n));
        n = find_key(cx, root, {"R"}, &key);
        c.R = check_rotation(cx, key, read_matrix(cx, key, n));
        n = find_key(cx, root, {"T"}, &key);
        c.T = check_translation(cx, key, read_matrix(cx, key, n));

        const cv::FileNode is = root["image_size"];
        if (!is.empty() && !is.isNone()) {
            const cv::Mat m = read_matrix(cx, "image_size", is);
            if (m.total() != 2 || (m.rows != 1 && m.cols != 1))
                cx.fail_key("image_size", "expected [width, height], got " + dims(m));
            const cv::Mat d = as_double(cx, "image_size", m);
            const double w = d.at<double>(0), h = d.at<double>(1);
            check_size(cx, "key 'image_size'", w, h);
            c.size = cv::Size(static_cast<int>(w), static_cast<int>(h));
        } else {
            const cv::FileNode wn = root["image_width"], hn = root["image_height"];
            const bool hw = !wn.empty() && !wn.isNone(), hh = !hn.empty() && !hn.isNone();
            if (!hw && !hh)
                cx.fail(
                    "missing image size (key 'image_size' [width, height], or keys "
                    "'image_width' and 'image_height')");
            if (!hw) cx.fail("missing key 'image_width' (image_height is given)");
            if (!hh) cx.fail("missing key 'image_height' (image_width is given)");
            double w = 0, h = 0;
            for (const auto& [node, name, out] :
                 {std::tuple{wn, "image_width", &w}, std::tuple{hn, "image_height", &h}}) {
                if (!node.isInt() && !node.isReal())
                    cx.fail_key(name, "expected a number, got " +
                                          std::string(node.isString() ? "text" : "a collection"));
                *out = static_cast<double>(node);
            }
            check_size(cx, "keys 'image_width' and 'image_height'", w, h);
            c.size = cv::Size(static_cast<int>(w), static_cast<int>(h));
        }
    } catch (const cv::Exception& e) {  // anything OpenCV did not like in a node
        cx.fail("not a calibration file (cannot read: " + opencv_reason(e) + ")");
    }
    return c;
}

void write_stereo_calib(const std::string& path, const StereoCalib& c) {
    const Ctx cx{"calibration '" + path + "'"};
    const std::string ext = [&] {
        std::string e = fs::path(path).extension().string();
        for (char& ch : e) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
        return e;
    }();
    int fmt = 0;
    if (ext == ".yml" || ext == ".yaml")
        fmt = cv::FileStorage::FORMAT_YAML;
    else if (ext == ".xml")
        fmt = cv::FileStorage::FORMAT_XML;
    else if (ext == ".json")
        fmt = cv::FileStorage::FORMAT_JSON;
    else
        cx.fail("cannot write this file type" +
                (ext.empty() ? std::string(" (no extension)") : " ('" + ext + "')") +
                "; use .yml, .yaml, .xml or .json");
    const StereoCalib v = checked(cx, c);
    std::string text;
    try {
        cv::FileStorage fs(ext, cv::FileStorage::WRITE | cv::FileStorage::MEMORY | fmt);
        if (fmt != cv::FileStorage::FORMAT_JSON)
            fs.writeComment(
                "Stereo calibration: K camera matrices, D distortion (k1 k2 p1 p2 [k3 ...]),\n"
                "R and T map left-camera to right-camera coordinates (docs/calibration.md).");
        fs << "image_width" << v.size.width << "image_height" << v.size.height;
        fs << "K1" << v.K1 << "D1" << v.D1 << "K2" << v.K2 << "D2" << v.D2;
        fs << "R" << v.R << "T" << v.T;
        text = fs.releaseAndGetString();
    } catch (const cv::Exception& e) {
        cx.fail("cannot encode (" + opencv_reason(e) + ")");
    }
    write_text_atomic(path, text);
}

Rectifier::Rectifier(const StereoCalib& c) {
    const Ctx cx{"calibration"};
    c_ = checked(cx, c);
    const double tx = c_.T.at<double>(0), ty = c_.T.at<double>(1);
    if (!(std::abs(tx) > std::abs(ty)))
        cx.fail("key 'T': baseline is not horizontal (|T_x| = " + num(std::abs(tx)) +
                " <= |T_y| = " + num(std::abs(ty)) + "); the matcher needs a side-by-side pair");
    if (!(tx < 0))
        cx.fail("key 'T': T_x = " + num(tx) +
                " must be < 0 (right camera to the right of the left camera); are the left and "
                "right cameras swapped?");
    try {
        cv::stereoRectify(c_.K1, c_.D1, c_.K2, c_.D2, c_.size, c_.R, c_.T, R1_, R2_, P1_, P2_, Q_,
                          cv::CALIB_ZERO_DISPARITY, kRectifyAlpha, c_.size);
        for (const cv::Mat* m : {&R1_, &R2_, &P1_, &P2_})
            if (m->empty() || !cv::checkRange(*m))
                cx.fail("rectification failed (degenerate calibration: non-finite result)");
        if (!(P1_.at<double>(0, 0) > 0) || !(P2_.at<double>(0, 0) > 0))
            cx.fail("rectification failed (degenerate calibration: focal length <= 0)");
        cv::initUndistortRectifyMap(c_.K1, c_.D1, R1_, P1_, c_.size, CV_16SC2, map1l_, map2l_);
        cv::initUndistortRectifyMap(c_.K2, c_.D2, R2_, P2_, c_.size, CV_16SC2, map1r_, map2r_);
    } catch (const cv::Exception& e) {
        cx.fail("rectification failed (" + opencv_reason(e) + ")");
    }
}

void Rectifier::rectify(const cv::Mat& left_raw, const cv::Mat& right_raw, cv::Mat* left,
                        cv::Mat* right) const {
    for (const auto& [img, what] : {std::pair{&left_raw, "left"}, std::pair{&right_raw, "right"}}) {
        if (img->type() != CV_8UC1)
            throw InputError(std::string(what) + " frame: expected 8-bit grey (CV_8UC1) for " +
                             "rectification");
        if (img->size() != c_.size)
            throw InputError(std::string(what) + " frame size " + size_text(img->size()) +
                             " differs from the calibration's image size " + size_text(c_.size));
    }
    cv::Mat l, r;  // remap cannot work in place (the outputs may alias the inputs)
    cv::remap(left_raw, l, map1l_, map2l_, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(0));
    cv::remap(right_raw, r, map1r_, map2r_, cv::INTER_LINEAR, cv::BORDER_CONSTANT, cv::Scalar(0));
    *left = l;
    *right = r;
}

}  // namespace imap::vision
