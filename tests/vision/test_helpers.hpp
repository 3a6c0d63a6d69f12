// Small helpers shared by the imap_vision tests.
#pragma once

#include <unistd.h>

#include <boost/test/unit_test.hpp>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <opencv2/core.hpp>
#include <string>

namespace vision_test {

// A fresh temporary folder, removed with everything in it at scope exit.
class TempDir {
  public:
    explicit TempDir(const std::string& tag) {
        static int counter = 0;
        path_ = std::filesystem::temp_directory_path() /
                ("imap_vision_" + tag + "_" + std::to_string(::getpid()) + "_" +
                 std::to_string(counter++));
        std::filesystem::remove_all(path_);
        std::filesystem::create_directories(path_);
    }
    ~TempDir() {
        std::error_code ec;
        std::filesystem::remove_all(path_, ec);
    }
    TempDir(const TempDir&) = delete;
    TempDir& operator=(const TempDir&) = delete;
    const std::filesystem::path& path() const { return path_; }
    std::string file(const std::string& name) const { return (path_ / name).string(); }

  private:
    std::filesystem::path path_;
};

inline void write_file(const std::string& path, const std::string& bytes) {
    std::ofstream out(path, std::ios::binary);
    out << bytes;
}

inline std::string read_file(const std::string& path) {
    std::ifstream in(path, std::ios::binary);
    return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

// Number of entries in `dir` (to spot temporary leftovers).
inline int count_entries(const std::filesystem::path& dir) {
    int n = 0;
    for (const auto& e : std::filesystem::directory_iterator(dir)) {
        (void)e;
        ++n;
    }
    return n;
}

// A rendered stereo pair against its left-view ground truth (left pixel x at
// disparity d pairs with right pixel x - d): every pixel surely visible in
// both views (no nearer surface at d2 > d covers right pixel x - d, i.e. left
// pixel x - d + d2 is not at disparity >= d2) agrees within 2 x noise; at
// least 80% of the pixels are checked; and the texture is rich: one pixel
// off, at least 60% of them disagree. Every d is <= max_disp and at least d
// from the left edge.
inline void check_views_match_ground_truth(const cv::Mat& left, const cv::Mat& right,
                                           const cv::Mat& gt, int max_disp, int noise) {
    const int W = gt.cols;
    long checked = 0, total = 0, wrong_shift_differs = 0;
    for (int y = 0; y < gt.rows; ++y) {
        const uint8_t* G = gt.ptr<uint8_t>(y);
        const uint8_t* L = left.ptr<uint8_t>(y);
        const uint8_t* R = right.ptr<uint8_t>(y);
        for (int x = 0; x < W; ++x) {
            ++total;
            const int d = G[x];
            BOOST_TEST(d <= max_disp);
            if (d > 0) BOOST_TEST(x >= d);
            const int xr = x - d;
            if (xr < 0) continue;
            bool visible = true;
            for (int d2 = d + 1; d2 <= max_disp && visible; ++d2)
                if (xr + d2 < W && G[xr + d2] >= d2) visible = false;
            if (!visible) continue;
            ++checked;
            BOOST_TEST(std::abs(L[x] - R[xr]) <= 2 * noise, "x=" << x << " y=" << y << " d=" << d);
            if (xr >= 1 && std::abs(L[x] - R[xr - 1]) > 2 * noise) ++wrong_shift_differs;
        }
    }
    BOOST_TEST(checked > total * 8 / 10);
    BOOST_TEST(wrong_shift_differs > checked * 6 / 10);
}

}  // namespace vision_test
