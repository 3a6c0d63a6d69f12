// Writes the seed images of corpus/image (tiny 8x6 files in every format
// the image fuzz target starts from). Run once; the bytes are committed:
//   cmake --build build --target fuzz_make_image_corpus
//   build/tests/fuzz/fuzz_make_image_corpus tests/fuzz/corpus/image
#include <iostream>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
int main(int argc, char** argv) {
    if (argc != 2) {
        std::cerr << "usage: fuzz_make_image_corpus DIR\n";
        return 2;
    }
    std::string d = argv[1];
    cv::Mat g(6, 8, CV_8UC1), c(6, 8, CV_8UC3), a(6, 8, CV_8UC4), g16(6, 8, CV_16UC1),
        f(6, 8, CV_32FC1);
    for (int y = 0; y < 6; ++y)
        for (int x = 0; x < 8; ++x) {
            g.at<uint8_t>(y, x) = uint8_t(x * 30 + y * 7);
            c.at<cv::Vec3b>(y, x) =
                cv::Vec3b(uint8_t(x * 30), uint8_t(y * 40), uint8_t(255 - x * 20));
            a.at<cv::Vec4b>(y, x) =
                cv::Vec4b(uint8_t(x * 30), uint8_t(y * 40), 90, uint8_t(255 - y * 30));
            g16.at<uint16_t>(y, x) = uint16_t(x * 3000 + y);
            f.at<float>(y, x) = x * 0.1f + y;
        }
    auto w = [&](const std::string& n, const cv::Mat& m, std::vector<int> p = {}) {
        if (!cv::imwrite(d + "/" + n, m, p)) std::cerr << "failed " << n << "\n";
    };
    w("grey.png", g, {cv::IMWRITE_PNG_COMPRESSION, 9});
    w("colour.png", c);
    w("alpha.png", a);
    w("grey16.png", g16);
    w("grey.pgm", g);
    w("grey_ascii.pgm", g, {cv::IMWRITE_PXM_BINARY, 0});
    w("colour.ppm", c);
    w("grey.pam", g);
    w("grey.bmp", g);
    w("colour.bmp", c);
    w("grey.jpg", g, {cv::IMWRITE_JPEG_QUALITY, 80});
    w("colour.jpg", c, {cv::IMWRITE_JPEG_QUALITY, 80});
    w("progressive.jpg", c, {cv::IMWRITE_JPEG_PROGRESSIVE, 1});
    w("grey.tif", g);
    w("colour.webp", c, {cv::IMWRITE_WEBP_QUALITY, 101});
    w("float.pfm", f);
}
