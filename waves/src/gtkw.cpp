#include "imap/waves/gtkw.hpp"

#include <cmath>
#include <cstdio>

#include "imap/waves/vcd.hpp"

namespace imap::waves {

namespace {
std::string hex_flags(uint32_t f) {
    char b[16];
    std::snprintf(b, sizeof b, "@%x", f);
    return b;
}
constexpr uint32_t kBlank = 0x200, kCollapsed = 0x1000, kClosed = 0x400000, kGrpBegin = 0x800000,
                   kGrpEnd = 0x1000000;
}  // namespace

void GtkwSave::add_marker(uint64_t time, const std::string& name) {
    if (markers_.size() < 26) markers_.emplace_back(time, name);
}

void GtkwSave::flags(uint32_t f) {
    if (f == last_flags_) return;
    lines_.push_back(hex_flags(f));
    last_flags_ = f;
}

void GtkwSave::begin_group(const std::string& name, bool closed) {
    flags(kGrpBegin | kBlank | (closed ? kClosed : 0) | (closed_depth_ > 0 ? kCollapsed : 0));
    lines_.push_back("-" + name);
    groups_.push_back(name);
    closed_.push_back(closed);
    if (closed || closed_depth_ > 0) ++closed_depth_;
    last_flags_ = 0xFFFFFFFFu;
}

void GtkwSave::end_group() {
    if (groups_.empty()) throw WaveError("gtkw: end_group without begin_group");
    const bool closed = closed_.back();
    flags(kGrpEnd | kBlank | (closed_depth_ > 0 ? kCollapsed | (closed ? kClosed : 0) : 0));
    lines_.push_back("-" + groups_.back());
    groups_.pop_back();
    closed_.pop_back();
    if (closed_depth_ > 0) --closed_depth_;
    last_flags_ = 0xFFFFFFFFu;
}

void GtkwSave::add_signal(const std::string& full_name, Format fmt, const std::string& alias) {
    // Members of a closed group are collapsed (hidden until it is opened).
    flags(static_cast<uint32_t>(fmt) | (closed_depth_ > 0 ? kCollapsed : 0));
    lines_.push_back(alias.empty() ? full_name : "+{" + alias + "} " + full_name);
    names_.push_back(full_name);
}

void GtkwSave::add_vector(const std::string& name,
                          const std::vector<std::pair<int, std::string>>& bits, Format fmt) {
    if (bits.empty()) throw WaveError("gtkw: vector '" + name + "' without bits");
    flags(static_cast<uint32_t>(fmt) | (closed_depth_ > 0 ? kCollapsed : 0));
    std::string l = "#{" + name + "}";
    for (const auto& [bit, parent] : bits) l += " (" + std::to_string(bit) + ")" + parent;
    lines_.push_back(l);
    names_.push_back(name);
}

void GtkwSave::add_blank() {
    flags(kBlank);
    lines_.push_back("-");
}

void GtkwSave::add_comment(const std::string& text) {
    flags(kBlank);
    lines_.push_back("-" + text);
}

std::string GtkwSave::text() const {
    if (!groups_.empty()) throw WaveError("gtkw: group '" + groups_.back() + "' not closed");
    std::string t;
    t += "[*] GTKWave save file written by imap_waves (docs/waves.md)\n";
    t += "[dumpfile] \"" + dumpfile_ + "\"\n";
    t += "[timestart] " + std::to_string(start_) + "\n";
    t += "[size] 1600 900\n";
    t += "[pos] -1 -1\n";
    // Zoom: GTKWave 3.3 (measured with 3.3.118 at [size] 1600 900) shows
    // 2^-zoom / 200 time units per pixel over a wave area of about 950
    // pixels: fit the span into it.
    double zoom = 0;
    if (span_ > 0) zoom = -std::log2(static_cast<double>(span_) * 200.0 / 950.0);
    zoom = std::round(zoom * 1000.0) / 1000.0;
    char zb[64];
    std::snprintf(zb, sizeof zb, "*%.6f %lld", zoom,
                  markers_.empty() ? -1LL : static_cast<long long>(markers_[0].first));
    t += zb;
    for (size_t i = 0; i < 26; ++i)
        t += " " + (i < markers_.size() ? std::to_string(markers_[i].first) : std::string("-1"));
    t += "\n";
    for (size_t i = 0; i < markers_.size(); ++i)
        t += "[markername] " + std::string(1, static_cast<char>('A' + i)) + markers_[i].second +
             "\n";
    t += "[treeopen] top.\n";
    t += "[sst_width] 220\n";
    t += "[signals_width] 260\n";
    t += "[sst_expanded] 1\n";
    t += "[sst_vpaned_height] 200\n";
    for (const std::string& l : lines_) t += l + "\n";
    t += "[pattern_trace] 1\n[pattern_trace] 0\n";
    return t;
}

void GtkwSave::write(const std::string& path) const {
    write_text_atomic(path, text());
}

}  // namespace imap::waves
