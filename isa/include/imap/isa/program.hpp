// An assembled program and its binary file format ("IMAPFW01", docs/isa.md).
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

namespace imap::isa {

// A bad, truncated or unreadable program file.
class FormatError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

struct SourceLoc {
    uint32_t file = 0;  // index into Program::files
    uint32_t line = 0;  // 1-based; 0 = unknown
};

struct Program {
    std::vector<uint64_t> code;               // instruction words, PC = index
    std::vector<std::string> phases;          // phase id -> name; [0] = "default"
    std::map<std::string, uint32_t> symbols;  // label -> PC
    std::vector<std::string> files;           // source files of the source map
    std::vector<SourceLoc> source_map;        // PC -> location; empty or code.size()

    // "file:line" of a PC, or "" when unknown (control characters in the
    // file name shown as '?', so that the text stays on one line).
    std::string location(uint32_t pc) const;
    // Phase name, or "#id" when the id has no name.
    std::string phase_name(uint32_t id) const;

    bool operator==(const Program& o) const {
        return code == o.code && phases == o.phases && symbols == o.symbols && files == o.files &&
               source_map.size() == o.source_map.size() && same_map(o);
    }

  private:
    bool same_map(const Program& o) const;
};

inline constexpr char kProgramMagic[9] = "IMAPFW01";
inline constexpr uint32_t kProgramVersion = 1;

// Binary image of a program (little-endian, FNV-1a checksum at the end).
std::vector<uint8_t> serialize(const Program& p, bool with_source_map = true);
// Parses an image; `name` is used in error messages. Throws FormatError.
Program deserialize(const std::vector<uint8_t>& bytes, const std::string& name);
// File I/O. save_program writes a temporary file and renames it, so a
// failure never leaves a half-written output. Both throw FormatError.
void save_program(const Program& p, const std::string& path, bool with_source_map = true);
Program load_program(const std::string& path);

}  // namespace imap::isa
