// Progress output of the long-running subcommands (stream, sweep, synth
// --frames): on a terminal, a one-line bar redrawn in place (done/total,
// rate, ETA) with the per-item lines scrolling above it; otherwise plain
// lines only (logs, CI).
#pragma once

#include <chrono>
#include <cstddef>
#include <string>

namespace imapsim {

class Progress {
  public:
    // `unit` names the items ("frames", "points"). `tty` < 0: decide from
    // whether stdout is a terminal.
    Progress(std::string unit, size_t total, int tty = -1);
    ~Progress();
    Progress(const Progress&) = delete;
    Progress& operator=(const Progress&) = delete;

    // One item finished; `line` (may be empty) is printed on its own line.
    void step(const std::string& line);
    // Prints a line without counting an item (warnings, notes).
    void note(const std::string& line);
    // A short state shown at the end of the bar (e.g. the Slurm queue), terminal only.
    void set_status(const std::string& s);
    // Removes the bar (idempotent; the destructor calls it).
    void finish();

    size_t done() const { return done_; }
    double elapsed_s() const;
    bool tty() const { return tty_; }

  private:
    void clear_bar();
    void draw_bar(bool force);

    std::string unit_, status_;
    size_t total_ = 0, done_ = 0;
    bool tty_ = false, bar_shown_ = false;
    std::chrono::steady_clock::time_point start_, last_draw_;
};

}  // namespace imapsim
