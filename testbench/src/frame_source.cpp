#include "imap/testbench/frame_source.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <opencv2/core/utils/logger.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>
#include <utility>
#include <vector>

#include "imap/vision/image_io.hpp"
#include "imap/vision/sequence.hpp"

namespace imap::testbench {

namespace v = imap::vision;

namespace {

std::string size_text(cv::Size s) {
    return std::to_string(s.width) + "x" + std::to_string(s.height);
}

// Ground truth beside a left frame: the same name with "left" replaced by
// "gt" (left_0007.png -> gt_0007.png), if that file exists.
std::string gt_path_for(const std::string& left) {
    namespace fs = std::filesystem;
    const fs::path p(left);
    std::string name = p.filename().string(), low = name;
    std::transform(low.begin(), low.end(), low.begin(),
                   [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    const auto at = low.find("left");
    if (at == std::string::npos) return {};
    name.replace(at, 4, "gt");
    const fs::path g = p.parent_path() / name;
    std::error_code ec;
    return fs::is_regular_file(g, ec) ? g.string() : std::string();
}

class FolderSource : public FrameSource {
  public:
    explicit FolderSource(const std::string& dir) : dir_(dir), pairs_(v::list_frame_pairs(dir)) {}
    bool next(SourceFrame& f) override {
        if (i_ >= pairs_.size()) return false;
        const v::FramePair& p = pairs_[i_];
        f = SourceFrame{};
        f.index = static_cast<int>(i_++);
        f.name = p.name;
        f.error = p.error;
        if (f.error.empty()) {
            try {
                f.left = v::load_grey8(p.left, "left frame");
                f.right = v::load_grey8(p.right, "right frame");
                const std::string gt = gt_path_for(p.left);
                if (!gt.empty()) f.gt = v::load_grey8(gt, "ground truth");
            } catch (const v::InputError& e) {
                f.left.release();
                f.right.release();
                f.gt.release();
                f.error = e.what();
            }
        }
        return true;
    }
    int count() const override { return static_cast<int>(pairs_.size()); }
    std::string describe() const override {
        return "folder " + dir_ + " (" + std::to_string(pairs_.size()) + " pairs)";
    }

  private:
    std::string dir_;
    std::vector<v::FramePair> pairs_;
    size_t i_ = 0;
};

cv::Mat to_grey(const cv::Mat& m) {
    if (m.channels() == 1) return m.depth() == CV_8U ? m.clone() : cv::Mat();
    if (m.depth() != CV_8U) return {};
    cv::Mat g;
    cv::cvtColor(m, g, m.channels() == 4 ? cv::COLOR_BGRA2GRAY : cv::COLOR_BGR2GRAY);
    return g;
}

class VideoSource : public FrameSource {
  public:
    VideoSource(const std::string& left, const std::string& right) : lname_(left), rname_(right) {
        open(cap_[0], left, "left video");
        open(cap_[1], right, "right video");
        const double n0 = cap_[0].get(cv::CAP_PROP_FRAME_COUNT);
        const double n1 = cap_[1].get(cv::CAP_PROP_FRAME_COUNT);
        if (n0 > 0 && n1 > 0) count_ = static_cast<int>(std::min(n0, n1));
    }
    bool next(SourceFrame& f) override {
        if (ended_) return false;
        cv::Mat raw[2];
        const bool ok0 = cap_[0].read(raw[0]);
        const bool ok1 = cap_[1].read(raw[1]);
        if (!ok0 && !ok1) return false;
        f = SourceFrame{};
        f.index = i_++;
        f.name = "frame " + std::to_string(f.index);
        if (ok0 != ok1) {
            // One video is longer: the stream ends here, with the reason.
            ended_ = true;
            f.error = std::string(ok0 ? "right" : "left") + " video '" + (ok0 ? rname_ : lname_) +
                      "' ended at frame " + std::to_string(f.index) + " while the other goes on";
            return true;
        }
        f.left = to_grey(raw[0]);
        f.right = to_grey(raw[1]);
        if (f.left.empty() || f.right.empty()) {
            f.left.release();
            f.right.release();
            f.error = "frame " + std::to_string(f.index) + ": not an 8-bit image";
        }
        return true;
    }
    int count() const override { return count_; }
    std::string describe() const override { return "videos " + lname_ + " + " + rname_; }

  private:
    static void open(cv::VideoCapture& c, const std::string& path, const std::string& what) {
        std::error_code ec;
        if (!std::filesystem::is_regular_file(path, ec))
            throw v::InputError(what + " '" + path + "': no such file");
        // OpenCV logs its own warnings for files it cannot decode: the one
        // line below says it.
        const auto level = cv::utils::logging::setLogLevel(cv::utils::logging::LOG_LEVEL_SILENT);
        bool ok = false;
        try {
            ok = c.open(path);
        } catch (const cv::Exception&) {
            ok = false;
        }
        cv::utils::logging::setLogLevel(level);
        if (!ok || !c.isOpened())
            throw v::InputError(what + " '" + path +
                                "': cannot open (missing, unreadable or no decoder for it)");
    }
    std::string lname_, rname_;
    cv::VideoCapture cap_[2];
    int count_ = -1, i_ = 0;
    bool ended_ = false;
};

class SyntheticSource : public FrameSource {
  public:
    SyntheticSource(uint64_t seed, int w, int h, int n)
        : seed_(seed), w_(w), h_(h), n_(n), gen_(seed, w, h, n) {}
    bool next(SourceFrame& f) override {
        if (k_ >= n_) return false;
        const v::SequenceFrame s = gen_.frame(k_);
        f = SourceFrame{};
        f.index = k_;
        f.name = "synthetic " + std::to_string(k_);
        f.left = s.left;
        f.right = s.right;
        f.gt = s.gt;
        ++k_;
        return true;
    }
    int count() const override { return n_; }
    std::string describe() const override {
        return "synthetic sequence seed " + std::to_string(seed_) + " " + std::to_string(w_) + "x" +
               std::to_string(h_) + ", " + std::to_string(n_) + " frames";
    }

  private:
    uint64_t seed_;
    int w_, h_, n_, k_ = 0;
    v::SequenceGenerator gen_;
};

class Rectified : public FrameSource {
  public:
    Rectified(std::unique_ptr<FrameSource> src, const v::StereoCalib& c)
        : src_(std::move(src)), rect_(c) {}
    bool next(SourceFrame& f) override {
        if (!src_->next(f)) return false;
        if (!f.error.empty()) return true;
        try {
            cv::Mat l, r;
            rect_.rectify(f.left, f.right, &l, &r);
            f.left = l;
            f.right = r;
        } catch (const v::InputError& e) {
            f.left.release();
            f.right.release();
            f.error = e.what();
        }
        return true;
    }
    int count() const override { return src_->count(); }
    std::string describe() const override {
        return src_->describe() + ", rectified " + size_text(rect_.size());
    }

  private:
    std::unique_ptr<FrameSource> src_;
    v::Rectifier rect_;
};

class SizeChecked : public FrameSource {
  public:
    SizeChecked(std::unique_ptr<FrameSource> src, cv::Size size)
        : src_(std::move(src)), size_(size) {}
    bool next(SourceFrame& f) override {
        if (!src_->next(f)) return false;
        if (!f.error.empty()) return true;
        std::string err;
        if (f.left.size() != f.right.size())
            err = "left and right differ in size: " + size_text(f.left.size()) + " vs " +
                  size_text(f.right.size());
        else if (f.left.size() != size_)
            err = "frame size " + size_text(f.left.size()) + " differs from the stream's " +
                  size_text(size_);
        if (!err.empty()) {
            f.left.release();
            f.right.release();
            f.gt.release();
            f.error = err;
        }
        return true;
    }
    int count() const override { return src_->count(); }
    std::string describe() const override { return src_->describe(); }

  private:
    std::unique_ptr<FrameSource> src_;
    cv::Size size_;
};

}  // namespace

std::unique_ptr<FrameSource> open_folder(const std::string& dir) {
    return std::make_unique<FolderSource>(dir);
}

std::unique_ptr<FrameSource> open_videos(const std::string& left, const std::string& right) {
    return std::make_unique<VideoSource>(left, right);
}

std::unique_ptr<FrameSource> open_synthetic(uint64_t seed, int width, int height, int frames) {
    return std::make_unique<SyntheticSource>(seed, width, height, frames);
}

std::unique_ptr<FrameSource> rectified(std::unique_ptr<FrameSource> src,
                                       const vision::StereoCalib& calib) {
    return std::make_unique<Rectified>(std::move(src), calib);
}

std::unique_ptr<FrameSource> size_checked(std::unique_ptr<FrameSource> src, cv::Size size) {
    return std::make_unique<SizeChecked>(std::move(src), size);
}

}  // namespace imap::testbench
