// Assembling a user's source from the command line (imapsim asm, exec): -D
// definitions and compiler-style diagnostics, shared so both say the same.
#pragma once

#include <string>
#include <vector>

#include "imap/isa/assembler.hpp"
#include "imap/isa/program.hpp"

namespace imapsim {

// Assembler options from -D NAME=VALUE flags (UserError on a bad or repeated
// definition).
imap::isa::AsmOptions asm_options(const std::vector<std::string>& defines);

// Assembles `src`; on errors prints one diagnostic per line (file:line:col)
// to stderr and throws UserError "<src> does not assemble (N errors); <outcome>".
imap::isa::Program assemble_or_report(const std::string& src, const imap::isa::AsmOptions& opt,
                                      const std::string& outcome);

}  // namespace imapsim
