// Fuzz targets of imap_isa: the assembler (text in) and the IMAPFW01 program
// loader (bytes in). Each has an oracle (check_*) and a mutator (mutate_*).
#pragma once

#include <string>
#include <vector>

#include "fuzz_common.hpp"

namespace imap::fuzz {

// Assembler oracle: assemble_string either returns a program or throws
// AsmError with one-line diagnostics; nothing else. A program that
// assembles disassembles, re-assembles to the same code words (and phase
// table and labels, when the disassembler can name them), and loads and
// runs on a small machine ending in halt or a Fault.
Result check_asm(const Bytes& text);
// Text mutations: byte edits, line deletes / inserts / swaps / splices,
// dictionary lines, duplicated tokens, huge numbers, deep expression and
// block nesting, other mnemonics and register numbers.
void mutate_asm(Rng& rng, Bytes& text, const std::vector<Bytes>& corpus);

// Loader oracle: deserialize either returns a program or throws
// FormatError. A program that parses serializes back to the same tables,
// disassembles and re-assembles to the same code, and on a small machine
// (P = 4, 64 bytes of memory, watchdog 20000 cycles) either fails to load
// with LoadError or runs to halt or a Fault, twice with the same result.
Result check_program(const Bytes& bytes);
// Byte mutations with the checksum repaired (most of the time), and
// structured ones on the parsed program (code words, phases, symbols,
// source map) written back with serialize().
void mutate_program(Rng& rng, Bytes& bytes, const std::vector<Bytes>& corpus);

}  // namespace imap::fuzz
