// The firmware sources compiled into the library: where the assembler finds
// them (firmware_dir()), the table by path, and a program with their
// .include lines replaced by their text (docs/firmware.md, section 7).
#include <sstream>

#include "embedded.hpp"
#include "imap/firmware/plan.hpp"

namespace imap::firmware {

std::string firmware_dir() {
    return "firmware/asm";
}

const std::map<std::string, std::string>& firmware_sources() {
    static const std::map<std::string, std::string> files = [] {
        std::map<std::string, std::string> m;
        for (const auto& [name, text] : detail::embedded_sources())
            m.emplace(firmware_dir() + "/" + name, text);
        return m;
    }();
    return files;
}

namespace {

// The file an `.include "NAME"` line names, or "" for any other line.
std::string include_target(const std::string& line) {
    size_t i = line.find_first_not_of(" \t");
    if (i == std::string::npos || line.compare(i, 8, ".include") != 0) return "";
    i = line.find('"', i + 8);
    const size_t e = i == std::string::npos ? i : line.find('"', i + 1);
    return e == std::string::npos ? "" : line.substr(i + 1, e - i - 1);
}

void inline_into(std::ostringstream& out, const std::string& text, int depth) {
    std::istringstream in(text);
    const std::string dir = firmware_dir() + "/";
    for (std::string line; std::getline(in, line);) {
        std::string name = include_target(line);
        if (!name.empty() && name.compare(0, dir.size(), dir) == 0) name = name.substr(dir.size());
        const auto it =
            name.empty() ? firmware_sources().end() : firmware_sources().find(dir + name);
        if (it == firmware_sources().end() || depth > 32) {
            out << line << "\n";
            continue;
        }
        out << "; ---- " << name << " (inlined from " << it->first << ")\n";
        inline_into(out, it->second, depth + 1);
        out << "; ---- end of " << name << "\n";
    }
}

}  // namespace

std::string inline_firmware_includes(const std::string& text) {
    std::ostringstream out;
    inline_into(out, text, 0);
    return out.str();
}

}  // namespace imap::firmware
