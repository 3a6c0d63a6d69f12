#include "progress.hpp"

#include <unistd.h>

#include <cstdio>

namespace imapsim {

Progress::Progress(std::string unit, size_t total, int tty)
    : unit_(std::move(unit)),
      total_(total),
      tty_(tty < 0 ? ::isatty(STDOUT_FILENO) != 0 : tty != 0),
      start_(std::chrono::steady_clock::now()),
      last_draw_(start_ - std::chrono::seconds(1)) {
    draw_bar(true);
}

Progress::~Progress() {
    finish();
}

double Progress::elapsed_s() const {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

void Progress::clear_bar() {
    if (!bar_shown_) return;
    std::fputs("\r\033[2K", stdout);
    bar_shown_ = false;
}

void Progress::draw_bar(bool force) {
    if (!tty_ || done_ >= total_) return;
    const auto now = std::chrono::steady_clock::now();
    if (!force && now - last_draw_ < std::chrono::milliseconds(100)) return;
    last_draw_ = now;
    constexpr int kWidth = 30;
    const int filled = total_ ? static_cast<int>(kWidth * done_ / total_) : 0;
    std::string bar(static_cast<size_t>(filled), '#');
    bar.append(static_cast<size_t>(kWidth - filled), '.');
    const double t = elapsed_s();
    const double rate = t > 0 ? static_cast<double>(done_) / t : 0;
    char eta[32] = "--:--";
    if (rate > 0) {
        const long s = static_cast<long>(static_cast<double>(total_ - done_) / rate + 0.5);
        std::snprintf(eta, sizeof eta, "%ld:%02ld", s / 60, s % 60);
    }
    clear_bar();
    std::printf("[%s] %zu/%zu %s  %.2f %s/s  ETA %s%s%s", bar.c_str(), done_, total_, unit_.c_str(),
                rate, unit_.c_str(), eta, status_.empty() ? "" : "  | ", status_.c_str());
    std::fflush(stdout);
    bar_shown_ = true;
}

void Progress::note(const std::string& line) {
    clear_bar();
    if (!line.empty()) std::printf("%s\n", line.c_str());
    std::fflush(stdout);
    draw_bar(true);
}

void Progress::step(const std::string& line) {
    ++done_;
    note(line);
}

void Progress::set_status(const std::string& s) {
    if (s == status_) return;
    status_ = s;
    draw_bar(false);
}

void Progress::finish() {
    clear_bar();
    std::fflush(stdout);
    total_ = done_;  // no more bars
}

}  // namespace imapsim
