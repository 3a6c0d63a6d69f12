// A deterministic Value Change Dump (IEEE 1364-1995 VCD) writer, shared by the
// ISA-level tracer (TLM and core models) and the RTL model (docs/waves.md).
//
//   VcdWriter w("run.vcd", {"1ns"});
//   w.push_scope("top");
//   SignalId pc = w.add_wire("pc", 16);
//   SignalId txt = w.add_text("instr", 32);   // 32 ASCII characters
//   w.pop_scope();
//   w.begin();                                 // header; no more declarations
//   w.set_time(0);  w.change(pc, 5);  w.change_text(txt, "nop");
//   w.set_time(25); ...
//   w.finish(50);                              // renames the temporary file
//
// Determinism: the file holds no date, host or wall-clock value; identifiers
// are given in declaration order; two identical call sequences give identical
// bytes. Only real value changes are written: a signal set several times at
// one time stamp is written once with its last value, and not at all when
// that equals the value already in the file.
//
// Text signals: VCD 1995 has no strings, so a text of up to N characters is a
// wire of 8*N bits holding the ASCII codes, first character in the most
// significant used byte, right-justified (leading NUL bytes, which GTKWave's
// ASCII format does not draw). The .gtkw file (gtkw.hpp) marks them with
// GTKWave's "Data Format > ASCII".
//
// Atomic output: everything goes to "<path>.part" and is renamed to <path> by
// finish(); an error (WaveError) or a writer destroyed before finish() removes
// the temporary file, so no half-written VCD is ever left under <path>.
//
// Size control: with a byte limit, the writer stops at the first time stamp
// that would start beyond the limit, writes a $comment saying so, warns once
// on the warning stream, ignores every later change and still finishes the
// file cleanly (limit_reached() tells).
#pragma once

#include <cstdint>
#include <cstdio>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace imap::waves {

// Any failure of the wave output (bad path, disk full, misuse of the API).
class WaveError : public std::runtime_error {
  public:
    using std::runtime_error::runtime_error;
};

using SignalId = uint32_t;

struct VcdOptions {
    // The $timescale: "1ns", "1ps", "10ns", ... (number 1/10/100, unit s..fs).
    std::string timescale = "1ns";
    // Stop writing value changes once the file has this many bytes (0 = no
    // limit). See "Size control" above.
    uint64_t limit_bytes = 0;
    // What to call the limit in the warning (e.g. "--trace-limit-mb 200").
    std::string limit_name = "the trace size limit";
    // Warnings go here (nullptr = silent). Default: std::cerr.
    std::ostream* warn = nullptr;
    bool warn_to_stderr = true;
    // Free text for the $comment of the header (no dates, please).
    std::string comment = "imap-vision waves";
};

// The timescale and the length of one clock cycle in it for a clock in MHz:
// 1 ns units when the period is a whole number of ns (40 MHz -> 25 ns),
// otherwise 1 ps units (rounded to the nearest ps). Throws WaveError for a
// clock that is not > 0 or a period that rounds to 0 ps.
struct ClockScale {
    std::string timescale;
    uint64_t period = 1;  // time units per cycle
    double unit_ns = 1;   // one time unit in ns
};
ClockScale clock_scale(double clock_mhz);

class VcdWriter {
  public:
    VcdWriter(std::string path, VcdOptions opt = {});
    ~VcdWriter();  // removes the temporary file unless finish() succeeded
    VcdWriter(const VcdWriter&) = delete;
    VcdWriter& operator=(const VcdWriter&) = delete;

    // ---- declarations (before begin) ----
    // Scopes nest; names must be non-empty and free of white space.
    void push_scope(const std::string& name);
    void pop_scope();
    // A wire of 1..64 bits (the value is masked to the width). Declared as
    // "name [w-1:0]" for w > 1, so GTKWave calls it "scope.name[w-1:0]".
    SignalId add_wire(const std::string& name, int width);
    // A text of up to `chars` ASCII characters (1..256), 8*chars bits.
    SignalId add_text(const std::string& name, int chars);

    // Full hierarchical name as GTKWave shows it ("top.pe3.r0[7:0]").
    const std::string& full_name(SignalId id) const;
    int width(SignalId id) const;
    bool is_text(SignalId id) const;
    size_t signal_count() const { return sigs_.size(); }

    // Writes the header (to the temporary file; WaveError when it cannot be
    // created). Scopes must be closed.
    void begin();

    // ---- value changes (after begin) ----
    // Time stamps never go back (WaveError). Changes are collected per time
    // stamp and written when the time advances or at finish.
    void set_time(uint64_t t);
    uint64_t time() const { return now_; }
    void change(SignalId id, uint64_t value);
    void change_text(SignalId id, std::string_view text);

    // Writes the pending changes, a final time stamp `end_time` (when later
    // than the last one) so the last values have a length, closes the file
    // and renames it to the path. WaveError on any I/O failure (the temporary
    // file is removed).
    void finish(uint64_t end_time);
    // Removes the temporary file without producing the output.
    void abandon();

    bool limit_reached() const { return stopped_; }
    uint64_t bytes_written() const { return bytes_; }
    uint64_t value_changes() const { return changes_; }
    const std::string& path() const { return path_; }

  private:
    struct Scope {
        std::string name;
        int parent = -1;
    };
    struct Signal {
        std::string name, full, code;
        int width = 1, scope = -1;
        bool text = false;
        bool dirty = false;
        uint64_t cur = 0, next = 0;  // wires
        std::string cur_s, next_s;   // texts: the bits as '0'/'1' without leading zeros
    };

    void out(std::string_view s);
    void flush_time();
    void write_value(const Signal& s);
    void check_declaring(const char* what) const;
    void check_running(const char* what) const;
    SignalId add_signal(const std::string& name, int width, bool text);
    void fail(const std::string& what);

    std::string path_, tmp_;
    VcdOptions opt_;
    std::FILE* f_ = nullptr;
    bool begun_ = false, finished_ = false, stopped_ = false, dumped_ = false;
    std::vector<Scope> scopes_;
    std::vector<int> open_;  // stack of open scopes
    std::vector<Signal> sigs_;
    std::vector<SignalId> dirty_;
    uint64_t now_ = 0;
    bool have_time_ = false;
    uint64_t bytes_ = 0, changes_ = 0;
    std::string buf_;
};

// Writes `text` to `path` through a temporary file and a rename (WaveError
// naming the path on failure; nothing is left behind).
void write_text_atomic(const std::string& path, const std::string& text);

}  // namespace imap::waves
