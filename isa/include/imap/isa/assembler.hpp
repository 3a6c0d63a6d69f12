// The assembler (syntax in docs/isa.md) and the disassembler.
#pragma once

#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "imap/isa/program.hpp"

namespace imap::isa {

struct Diagnostic {
    std::string file;
    int line = 0;  // 1-based
    int col = 0;   // 1-based
    std::string message;
    // "file:line:col: error: message"
    std::string str() const;
};

// Assembly failed: every collected diagnostic (at most max_errors, then a
// final "too many errors" line). what() is all of them, one per line.
class AsmError : public std::runtime_error {
  public:
    explicit AsmError(std::vector<Diagnostic> d);
    const std::vector<Diagnostic>& diagnostics() const { return diags_; }

  private:
    std::vector<Diagnostic> diags_;
};

struct AsmOptions {
    std::map<std::string, int64_t> defines;  // -D NAME=VALUE, visible as constants
    int max_errors = 20;
    bool source_map = true;
    // Files held in memory, by path (not owned): an .include whose resolved
    // path is here reads this text instead of the disk (the firmware
    // compiled into the binary).
    const std::map<std::string, std::string>* files = nullptr;
};

// Assembles a file; .include paths are relative to the including file.
Program assemble_file(const std::string& path, const AsmOptions& opt = {});
// Assembles text; `name` is the file name used in diagnostics and the source
// map, and includes are resolved relative to its directory.
Program assemble_string(const std::string& text, const std::string& name = "<string>",
                        const AsmOptions& opt = {});

// Parses "NAME=VALUE" (VALUE: integer or constant expression) or "NAME"
// (= 1) as given to -D. Throws std::invalid_argument with a clear message.
std::pair<std::string, int64_t> parse_define(const std::string& text);

struct DisasmOptions {
    bool comments = true;  // "; pc  file:line" after each instruction
};

// Disassembles a program into text that re-assembles to identical code
// words. Words that are not valid instructions come out as `.word 0x...`.
std::string disassemble(const Program& p, const DisasmOptions& opt = {});
// One instruction; branch targets and phase ids as numbers. Throws
// std::invalid_argument for an invalid word.
std::string disassemble_word(uint64_t w);

}  // namespace imap::isa
