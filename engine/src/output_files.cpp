// Output checks made before the work (output_files.hpp): folders exist,
// files can be created, images agree in size, the frame fits its parameters.
#include "imap/engine/output_files.hpp"

#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <opencv2/imgcodecs.hpp>

#include "imap/engine/error.hpp"
#include "imap/golden/stereo.hpp"

namespace imap::engine {

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
        throw Error(flag + " '" + path + "': cannot create files in folder '" + where.string() +
                    "' (" + std::strerror(errno) + ")");
    ::close(fd);
    ::unlink(probe.c_str());
}

}  // namespace

void check_same_size(const std::string& left, int lw, int lh, const std::string& right, int rw,
                     int rh) {
    if (lw == rw && lh == rh) return;
    throw Error("left and right images differ in size: " + left + " is " + std::to_string(lw) +
                "x" + std::to_string(lh) + ", " + right + " is " + std::to_string(rw) + "x" +
                std::to_string(rh));
}

void validate_frame(const golden::Params& p, const golden::Roi& roi, int w, int h) {
    try {
        golden::validate(p, roi, w, h);
    } catch (const golden::ParamError& e) {
        throw Error(e.what());
    }
}

void check_output_file(const std::string& flag, const std::string& path, bool image) {
    namespace fs = std::filesystem;
    if (path.empty()) return;
    const fs::path p(path);
    const fs::path dir = p.parent_path();
    std::error_code ec;
    if (!dir.empty() && !fs::is_directory(dir, ec))
        throw Error(flag + " '" + path + "': cannot create it: " +
                    (fs::exists(dir, ec) ? "'" + dir.string() + "' is not a folder"
                                         : "folder '" + dir.string() + "' does not exist"));
    if (fs::is_directory(p, ec)) throw Error(flag + " '" + path + "': is a folder");
    if (image && !cv::haveImageWriter(path))
        throw Error(flag + " '" + path + "': cannot write this image type" +
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
            throw Error(flag + " '" + dir + "': cannot create it: '" + dir + "' is not a folder");
        require_creatable(flag, dir, self);
        return;
    }
    const fs::path up = parent_folder(dir);
    if (!up.empty() && !fs::is_directory(up, ec))
        throw Error(flag + " '" + dir + "': cannot create it: " +
                    (fs::exists(up, ec) ? "'" + up.string() + "' is not a folder"
                                        : "folder '" + up.string() + "' does not exist"));
    require_creatable(flag, dir, up);
}

void create_output_dir(const std::string& flag, const std::string& dir) {
    namespace fs = std::filesystem;
    std::error_code ec;
    if (fs::exists(dir, ec) && !fs::is_directory(dir, ec))
        throw Error(flag + " '" + dir + "' exists and is not a folder");
    const fs::path up = parent_folder(dir);
    if (!fs::exists(dir, ec) && !up.empty() && !fs::is_directory(up, ec))
        throw Error(flag + " '" + dir + "': cannot create it: " +
                    (fs::exists(up, ec) ? "'" + up.string() + "' is not a folder"
                                        : "folder '" + up.string() + "' does not exist"));
    fs::create_directory(dir, ec);
    if (ec) throw Error(flag + " '" + dir + "': cannot create (" + ec.message() + ")");
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

// Two output flags naming one file would overwrite each other.
void check_distinct_outputs(const std::vector<std::pair<std::string, std::string>>& outs) {
    namespace fs = std::filesystem;
    for (size_t i = 0; i < outs.size(); ++i)
        for (size_t k = i + 1; k < outs.size(); ++k) {
            if (outs[i].second.empty() || outs[k].second.empty()) continue;
            const fs::path a = fs::absolute(outs[i].second).lexically_normal();
            const fs::path b = fs::absolute(outs[k].second).lexically_normal();
            if (a == b)
                throw Error(outs[i].first + " and " + outs[k].first + " name the same file '" +
                            outs[i].second + "'");
        }
}

}  // namespace imap::engine
