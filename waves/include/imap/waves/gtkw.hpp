// GTKWave save files (.gtkw): which signals GTKWave shows, in which groups
// and data formats, the zoom and the named markers. Written next to a VCD so
// that `gtkwave run.vcd run.gtkw` opens with a readable view. Deterministic
// (no dates, no absolute paths unless given).
#pragma once

#include <cstdint>
#include <string>
#include <utility>
#include <vector>

namespace imap::waves {

// GTKWave trace flags (the "@hex" lines of a save file).
enum class Format : uint32_t {
    Hex = 0x22,        // right-justified hexadecimal
    Dec = 0x24,        // right-justified decimal
    Bin = 0x28,        // right-justified binary (also used for 1-bit wires)
    Ascii = 0x820,     // "Data Format > ASCII": 8-bit groups as characters
    SignedDec = 0x424  // right-justified signed decimal
};

class GtkwSave {
  public:
    // `dumpfile` is written as given (use the VCD's file name so the pair can
    // be moved together). Times are in the VCD's time units.
    explicit GtkwSave(std::string dumpfile) : dumpfile_(std::move(dumpfile)) {}

    // The visible window at start: [start, start + span) time units.
    void set_view(uint64_t start, uint64_t span) {
        start_ = start;
        span_ = span;
    }
    // Named markers A..Z (at most 26 are kept), e.g. phase starts.
    void add_marker(uint64_t time, const std::string& name);
    // A collapsible group (GTKWave "Edit > Create Group"); groups nest.
    void begin_group(const std::string& name, bool closed = false);
    void end_group();
    // A signal by its full name (VcdWriter::full_name), with a data format
    // and an optional alias shown instead of the name.
    void add_signal(const std::string& full_name, Format fmt, const std::string& alias = "");
    // A vector GTKWave combines from bits of other signals ("Edit > Combine
    // Down"), shown as one value: `bits` lists (bit index, full name of the
    // vector it belongs to), most significant first; GTKWave numbers the
    // bits of a vector "x[7:0]" from 0 = bit 7 to 7 = bit 0.
    void add_vector(const std::string& name, const std::vector<std::pair<int, std::string>>& bits,
                    Format fmt);
    // An empty separator row / a comment row.
    void add_blank();
    void add_comment(const std::string& text);

    // The full names used by add_signal, in order (for tests).
    const std::vector<std::string>& signals() const { return names_; }
    const std::vector<std::pair<uint64_t, std::string>>& markers() const { return markers_; }

    std::string text() const;
    // Atomic write (WaveError on failure).
    void write(const std::string& path) const;

  private:
    std::string dumpfile_;
    uint64_t start_ = 0, span_ = 0;
    std::vector<std::pair<uint64_t, std::string>> markers_;
    std::vector<std::string> lines_;  // body lines
    std::vector<std::string> names_;
    std::vector<std::string> groups_;  // open groups
    std::vector<bool> closed_;         // ... and whether each is closed
    int closed_depth_ = 0;             // open groups inside a closed one (incl.)
    uint32_t last_flags_ = 0xFFFFFFFFu;
    void flags(uint32_t f);
};

}  // namespace imap::waves
