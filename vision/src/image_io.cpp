#include "imap/vision/image_io.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <vector>

namespace imap::vision {

namespace fs = std::filesystem;

namespace {

std::string quoted(const std::string& what, const std::string& path) {
    return what + " '" + path + "'";
}

// First line of an OpenCV exception text (they span several lines).
std::string first_line(const std::string& s) {
    const auto nl = s.find('\n');
    return nl == std::string::npos ? s : s.substr(0, nl);
}

// Temporary name next to the target: ".<stem>.tmp-<pid><ext>".
fs::path temp_path_for(const fs::path& target) {
    const std::string name = "." + target.stem().string() + ".tmp-" +
                             std::to_string(static_cast<long>(::getpid())) +
                             target.extension().string();
    return target.parent_path() / name;
}

// Writes `size` bytes to a temporary file next to `path`, flushes it to disk
// and renames it over `path`. Nothing is left behind on failure.
void write_bytes_atomic(const std::string& path, const void* bytes, size_t size) {
    const std::string who = quoted("output file", path);
    if (path.empty()) throw InputError("output file name is empty");
    const fs::path target(path);
    std::error_code ec;
    if (fs::is_directory(target, ec)) throw InputError(who + ": is a directory");
    const fs::path tmp = temp_path_for(target);

    auto fail = [&](const std::string& why, bool remove_tmp) {
        if (remove_tmp) ::unlink(tmp.c_str());
        throw InputError(who + ": cannot write (" + why + ")");
    };

    const int fd = ::open(tmp.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0666);
    if (fd < 0) fail(std::strerror(errno), false);
    const auto* p = static_cast<const char*>(bytes);
    size_t left = size;
    while (left > 0) {
        const ssize_t n = ::write(fd, p, left);
        if (n < 0) {
            if (errno == EINTR) continue;
            const int err = errno;
            ::close(fd);
            fail(std::strerror(err), true);
        }
        p += n;
        left -= static_cast<size_t>(n);
    }
    if (::fsync(fd) != 0 && errno != EINVAL && errno != EROFS) {
        const int err = errno;
        ::close(fd);
        fail(std::strerror(err), true);
    }
    if (::close(fd) != 0) fail(std::strerror(errno), true);
    if (std::rename(tmp.c_str(), target.c_str()) != 0) fail(std::strerror(errno), true);
}

// PNG files are checked chunk by chunk before decoding, so that a corrupt or
// truncated file gets one clear error instead of libpng's messages on
// stderr, and the iCCP (colour profile) chunks are dropped: OpenCV ignores
// them anyway, and libpng warns on stderr about some common profiles.
// Returns false for a PNG whose chunk structure is broken; other formats
// are left to the decoder.
bool check_png(std::vector<uint8_t>& b) {
    static const uint8_t sig[8] = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
    if (b.size() < 8 || std::memcmp(b.data(), sig, 8) != 0) return true;
    std::vector<uint8_t> out(b.begin(), b.begin() + 8);
    size_t pos = 8;
    bool dropped = false, ended = false;
    while (!ended && pos + 12 <= b.size()) {
        const size_t len = (size_t{b[pos]} << 24) | (size_t{b[pos + 1]} << 16) |
                           (size_t{b[pos + 2]} << 8) | size_t{b[pos + 3]};
        if (len > b.size() - pos - 12) return false;
        const uint8_t* type = &b[pos + 4];
        for (int k = 0; k < 4; ++k)
            if (!std::isalpha(type[k])) return false;
        if (pos == 8 && std::memcmp(type, "IHDR", 4) != 0) return false;
        ended = std::memcmp(type, "IEND", 4) == 0;
        if (std::memcmp(type, "iCCP", 4) == 0)
            dropped = true;
        else
            out.insert(out.end(), b.begin() + static_cast<std::ptrdiff_t>(pos),
                       b.begin() + static_cast<std::ptrdiff_t>(pos + 12 + len));
        pos += 12 + len;
    }
    if (!ended) return false;
    if (dropped) b.swap(out);
    return true;
}

// Formats whose OpenCV decoder reads from a file only: imdecode copies the
// bytes to a temporary file and, when the decoder throws (a bad header, a
// size past its limits), leaves that file behind. They are float formats
// this loader refuses anyway (PFM, Radiance HDR, OpenEXR); named here so
// no input reaches imdecode through a temporary file.
const char* file_only_format(const std::vector<uint8_t>& b) {
    auto starts = [&](const char* m, size_t n) {
        return b.size() >= n && std::memcmp(b.data(), m, n) == 0;
    };
    if (starts("Pf", 2) || starts("PF", 2)) return "PFM";
    if (starts("#?", 2)) return "Radiance HDR";
    if (starts("\x76\x2f\x31\x01", 4)) return "OpenEXR";
    return nullptr;
}

}  // namespace

cv::Mat load_grey8(const std::string& path, const std::string& what) {
    const std::string who = quoted(what, path);
    std::error_code ec;
    if (fs::is_directory(path, ec)) throw InputError(who + ": is a directory, not an image");

    // Read the bytes ourselves: exact errors, no OpenCV warnings on stderr.
    std::ifstream in(path, std::ios::binary);
    if (!in) {
        // say which of the three it is
        if (!fs::exists(path, ec)) throw InputError(who + ": cannot read (no such file)");
        throw InputError(who + ": cannot read (" + std::strerror(errno) +
                         "; check its permissions)");
    }
    std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)),
                               std::istreambuf_iterator<char>());
    if (in.bad()) throw InputError(who + ": cannot read (read error)");
    if (bytes.empty()) throw InputError(who + ": cannot read (empty file, not an image)");

    if (!check_png(bytes)) throw InputError(who + ": cannot read (corrupt or truncated PNG)");
    if (const char* fmt = file_only_format(bytes))
        throw InputError(who + ": cannot read (a " + fmt +
                         " float image; this tool reads 8-bit images: use PNG)");
    cv::Mat m;
    try {
        m = cv::imdecode(bytes, cv::IMREAD_UNCHANGED);
    } catch (const cv::Exception&) {
        m.release();
    }
    if (m.data == nullptr)
        throw InputError(who + ": cannot read (not an image: no decoder accepts it; use PNG)");
    if (m.dims != 2 || m.rows <= 0 || m.cols <= 0) throw InputError(who + ": image has zero size");

    switch (m.depth()) {
        case CV_8U:
            break;
        case CV_16U:
        case CV_16S:
            throw InputError(who + ": 16-bit images are not supported (need 8-bit grey or colour)");
        case CV_32F:
        case CV_64F:
        case CV_16F:
            throw InputError(who +
                             ": floating-point images are not supported (need 8-bit grey or "
                             "colour)");
        default:
            throw InputError(who + ": unsupported pixel type (need 8-bit grey or colour)");
    }

    cv::Mat grey;
    switch (m.channels()) {
        case 1:
            grey = m;
            break;
        case 2:  // grey + alpha
            cv::extractChannel(m, grey, 0);
            break;
        case 3:
            cv::cvtColor(m, grey, cv::COLOR_BGR2GRAY);
            break;
        case 4:
            cv::cvtColor(m, grey, cv::COLOR_BGRA2GRAY);
            break;
        default:
            throw InputError(who + ": unsupported number of channels (" +
                             std::to_string(m.channels()) + ")");
    }
    if (!grey.isContinuous()) grey = grey.clone();
    return grey;
}

golden::ImageView view_of(const cv::Mat& m) {
    if (m.dims != 2 || m.type() != CV_8UC1)
        throw std::invalid_argument("view_of: expected an 8-bit single-channel image");
    golden::ImageView v;
    v.data = m.data;
    v.width = m.cols;
    v.height = m.rows;
    v.stride = static_cast<std::ptrdiff_t>(m.step[0]);
    return v;
}

void write_image_atomic(const std::string& path, const cv::Mat& img) {
    const std::string who = quoted("output image", path);
    const std::string ext = fs::path(path).extension().string();
    if (ext.empty() || ext == "." || !cv::haveImageWriter(path))
        throw InputError(who + ": cannot write this file type" +
                         (ext.empty() ? std::string(" (no extension)") : " ('" + ext + "')") +
                         "; use e.g. .png");
    if (img.empty()) throw InputError(who + ": nothing to write (empty image)");
    std::vector<uint8_t> buf;
    bool ok = false;
    std::string why = "encoder failed";
    try {
        ok = cv::imencode(ext, img, buf);
    } catch (const cv::Exception& e) {
        why = first_line(e.what());
    }
    if (!ok) throw InputError(who + ": cannot encode (" + why + ")");
    write_bytes_atomic(path, buf.data(), buf.size());
}

void write_text_atomic(const std::string& path, const std::string& text) {
    write_bytes_atomic(path, text.data(), text.size());
}

}  // namespace imap::vision
