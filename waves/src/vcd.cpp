#include "imap/waves/vcd.hpp"

#include <cerrno>
#include <cmath>
#include <cstring>
#include <iostream>
#include <sstream>

namespace imap::waves {

namespace {

std::string errno_text() {
    return std::strerror(errno);
}

// Identifier codes: printable ASCII '!'..'~' (94 symbols), shortest first.
std::string id_code(uint32_t n) {
    std::string s;
    do {
        s.push_back(static_cast<char>('!' + n % 94));
        n /= 94;
    } while (n-- > 0);
    return s;
}

bool valid_name(const std::string& n) {
    if (n.empty()) return false;
    for (const char c : n)
        if (c <= ' ' || c > '~') return false;
    return true;
}

// Binary digits of v without leading zeros ("0" for 0).
void bits_of(uint64_t v, std::string& s) {
    s.clear();
    if (v == 0) {
        s = "0";
        return;
    }
    int top = 63;
    while (((v >> top) & 1u) == 0) --top;
    for (int b = top; b >= 0; --b) s.push_back(((v >> b) & 1u) ? '1' : '0');
}

}  // namespace

ClockScale clock_scale(double clock_mhz) {
    if (!(clock_mhz > 0) || !std::isfinite(clock_mhz))
        throw WaveError("waves: invalid clock " + std::to_string(clock_mhz) + " MHz");
    const double ps = 1e6 / clock_mhz;
    const double rps = std::round(ps);
    if (rps < 1) throw WaveError("waves: clock period rounds to 0 ps");
    ClockScale c;
    const uint64_t p = static_cast<uint64_t>(rps);
    if (std::fabs(ps - rps) < 1e-6 && p % 1000 == 0) {
        c.timescale = "1ns";
        c.period = p / 1000;
        c.unit_ns = 1;
    } else {
        c.timescale = "1ps";
        c.period = p;
        c.unit_ns = 1e-3;
    }
    return c;
}

VcdWriter::VcdWriter(std::string path, VcdOptions opt)
    : path_(std::move(path)), tmp_(path_ + ".part"), opt_(std::move(opt)) {
    if (path_.empty()) throw WaveError("waves: empty VCD path");
}

VcdWriter::~VcdWriter() {
    if (!finished_) abandon();
}

void VcdWriter::abandon() {
    if (f_) {
        std::fclose(f_);
        f_ = nullptr;
    }
    if (begun_ && !finished_) std::remove(tmp_.c_str());
    finished_ = true;
}

void VcdWriter::fail(const std::string& what) {
    abandon();
    throw WaveError(what);
}

void VcdWriter::check_declaring(const char* what) const {
    if (begun_) throw WaveError(std::string("waves: ") + what + " after begin()");
}

void VcdWriter::check_running(const char* what) const {
    if (!begun_ || finished_)
        throw WaveError(std::string("waves: ") + what + " outside begin() .. finish()");
}

void VcdWriter::push_scope(const std::string& name) {
    check_declaring("push_scope");
    if (!valid_name(name)) throw WaveError("waves: invalid scope name '" + name + "'");
    scopes_.push_back({name, open_.empty() ? -1 : open_.back()});
    open_.push_back(static_cast<int>(scopes_.size()) - 1);
}

void VcdWriter::pop_scope() {
    check_declaring("pop_scope");
    if (open_.empty()) throw WaveError("waves: pop_scope without an open scope");
    open_.pop_back();
}

SignalId VcdWriter::add_signal(const std::string& name, int width, bool text) {
    check_declaring("add_wire");
    if (!valid_name(name) || name.find('[') != std::string::npos)
        throw WaveError("waves: invalid signal name '" + name + "'");
    Signal s;
    s.name = name;
    s.width = width;
    s.text = text;
    s.scope = open_.empty() ? -1 : open_.back();
    std::string full;
    for (int sc = s.scope; sc >= 0; sc = scopes_[sc].parent) full = scopes_[sc].name + "." + full;
    full += name;
    if (width > 1) full += "[" + std::to_string(width - 1) + ":0]";
    s.full = full;
    s.code = id_code(static_cast<uint32_t>(sigs_.size()));
    s.cur_s = s.next_s = "0";
    sigs_.push_back(std::move(s));
    return static_cast<SignalId>(sigs_.size() - 1);
}

SignalId VcdWriter::add_wire(const std::string& name, int width) {
    if (width < 1 || width > 64)
        throw WaveError("waves: width " + std::to_string(width) + " of '" + name +
                        "' outside 1..64");
    return add_signal(name, width, false);
}

SignalId VcdWriter::add_text(const std::string& name, int chars) {
    if (chars < 1 || chars > 256)
        throw WaveError("waves: text length " + std::to_string(chars) + " of '" + name +
                        "' outside 1..256");
    return add_signal(name, 8 * chars, true);
}

const std::string& VcdWriter::full_name(SignalId id) const {
    return sigs_.at(id).full;
}
int VcdWriter::width(SignalId id) const {
    return sigs_.at(id).width;
}
bool VcdWriter::is_text(SignalId id) const {
    return sigs_.at(id).text;
}

void VcdWriter::out(std::string_view s) {
    if (std::fwrite(s.data(), 1, s.size(), f_) != s.size())
        fail("waves: cannot write '" + tmp_ + "': " + errno_text());
    bytes_ += s.size();
}

void VcdWriter::begin() {
    check_declaring("begin");
    if (!open_.empty()) throw WaveError("waves: begin() with open scopes");
    if (finished_) throw WaveError("waves: begin() after finish()");
    f_ = std::fopen(tmp_.c_str(), "wb");
    if (!f_)
        throw WaveError("waves: cannot create '" + tmp_ + "' (for '" + path_ +
                        "'): " + errno_text());
    begun_ = true;
    std::setvbuf(f_, nullptr, _IOFBF, 1 << 20);
    std::string h;
    h += "$comment\n  " + opt_.comment + "\n$end\n";
    h += "$version imap_waves 1 $end\n";
    h += "$timescale " + opt_.timescale + " $end\n";
    // Scopes in declaration order, signals inside the scope they were declared
    // in: walk the scope tree depth-first.
    std::vector<std::vector<int>> kids(scopes_.size() + 1);
    std::vector<std::vector<SignalId>> vars(scopes_.size() + 1);
    for (size_t i = 0; i < scopes_.size(); ++i)
        kids[scopes_[i].parent + 1].push_back(static_cast<int>(i));
    for (SignalId i = 0; i < sigs_.size(); ++i) vars[sigs_[i].scope + 1].push_back(i);
    auto emit = [&](auto& self, int sc, int depth) -> void {
        const std::string ind(static_cast<size_t>(depth) * 2, ' ');
        for (const SignalId v : vars[sc + 1]) {
            const Signal& s = sigs_[v];
            h += ind + "$var wire " + std::to_string(s.width) + " " + s.code + " " + s.name;
            if (s.width > 1) h += " [" + std::to_string(s.width - 1) + ":0]";
            h += " $end\n";
        }
        for (const int k : kids[sc + 1]) {
            h += ind + "$scope module " + scopes_[k].name + " $end\n";
            self(self, k, depth + 1);
            h += ind + "$upscope $end\n";
        }
    };
    emit(emit, -1, 0);
    h += "$enddefinitions $end\n";
    out(h);
}

void VcdWriter::write_value(const Signal& s) {
    if (s.width == 1) {
        buf_.push_back((s.cur & 1u) ? '1' : '0');
        buf_ += s.code;
        buf_.push_back('\n');
        return;
    }
    buf_.push_back('b');
    if (s.text) {
        buf_ += s.cur_s;
    } else {
        std::string b;
        bits_of(s.cur, b);
        buf_ += b;
    }
    buf_.push_back(' ');
    buf_ += s.code;
    buf_.push_back('\n');
}

void VcdWriter::flush_time() {
    if (!have_time_ || stopped_) return;
    buf_.clear();
    if (!dumped_) {
        // The first time stamp dumps every signal.
        dumped_ = true;
        buf_ += "#" + std::to_string(now_) + "\n$dumpvars\n";
        for (Signal& s : sigs_) {
            s.cur = s.next;
            s.cur_s = s.next_s;
            s.dirty = false;
            write_value(s);
            ++changes_;
        }
        buf_ += "$end\n";
        dirty_.clear();
        out(buf_);
        return;
    }
    if (dirty_.empty()) return;
    bool any = false;
    for (const SignalId id : dirty_) {
        Signal& s = sigs_[id];
        s.dirty = false;
        const bool same = s.text ? s.next_s == s.cur_s : s.next == s.cur;
        if (same) continue;
        if (!any) {
            if (opt_.limit_bytes != 0 && bytes_ >= opt_.limit_bytes) {
                stopped_ = true;
                dirty_.clear();
                const std::string msg = "trace stopped at time " + std::to_string(now_) + " (" +
                                        opt_.timescale + " units): " + opt_.limit_name + " reached";
                out("$comment\n  " + msg + "\n$end\n");
                std::ostream* w =
                    opt_.warn ? opt_.warn : (opt_.warn_to_stderr ? &std::cerr : nullptr);
                if (w)
                    *w << "warning: " << path_ << ": " << msg
                       << "; the VCD is complete up to there\n";
                return;
            }
            buf_ += "#" + std::to_string(now_) + "\n";
            any = true;
        }
        s.cur = s.next;
        s.cur_s = s.next_s;
        write_value(s);
        ++changes_;
    }
    dirty_.clear();
    if (any) out(buf_);
}

void VcdWriter::set_time(uint64_t t) {
    check_running("set_time");
    if (have_time_ && t < now_)
        throw WaveError("waves: time goes back from " + std::to_string(now_) + " to " +
                        std::to_string(t));
    if (have_time_ && t == now_) return;
    flush_time();
    now_ = t;
    have_time_ = true;
}

void VcdWriter::change(SignalId id, uint64_t value) {
    Signal& s = sigs_[id];
    if (s.width < 64) value &= (uint64_t{1} << s.width) - 1;
    if (s.text) {
        std::string b;
        bits_of(value, b);
        if (b == s.next_s) return;
        s.next_s = std::move(b);
    } else {
        if (value == s.next) return;
        s.next = value;
    }
    if (!s.dirty) {
        s.dirty = true;
        dirty_.push_back(id);
    }
}

void VcdWriter::change_text(SignalId id, std::string_view text) {
    Signal& s = sigs_[id];
    if (!s.text) throw WaveError("waves: change_text on the wire '" + s.full + "'");
    const size_t n = std::min<size_t>(text.size(), static_cast<size_t>(s.width / 8));
    std::string b;
    b.reserve(n * 8);
    for (size_t i = 0; i < n; ++i) {
        unsigned char c = static_cast<unsigned char>(text[i]);
        if (c < ' ' || c > '~') c = '?';
        for (int k = 7; k >= 0; --k) b.push_back(((c >> k) & 1u) ? '1' : '0');
    }
    const size_t nz = b.find('1');
    b = nz == std::string::npos ? std::string("0") : b.substr(nz);
    if (b == s.next_s) return;
    s.next_s = std::move(b);
    if (!s.dirty) {
        s.dirty = true;
        dirty_.push_back(id);
    }
}

void VcdWriter::finish(uint64_t end_time) {
    check_running("finish");
    if (!have_time_) {
        now_ = 0;
        have_time_ = true;
    }
    flush_time();
    if (end_time > now_ && !stopped_) out("#" + std::to_string(end_time) + "\n");
    if (std::fflush(f_) != 0) fail("waves: cannot write '" + tmp_ + "': " + errno_text());
    const int rc = std::fclose(f_);
    f_ = nullptr;
    if (rc != 0) fail("waves: cannot write '" + tmp_ + "': " + errno_text());
    if (std::rename(tmp_.c_str(), path_.c_str()) != 0)
        fail("waves: cannot rename '" + tmp_ + "' to '" + path_ + "': " + errno_text());
    finished_ = true;
}

void write_text_atomic(const std::string& path, const std::string& text) {
    const std::string tmp = path + ".part";
    std::FILE* f = std::fopen(tmp.c_str(), "wb");
    if (!f)
        throw WaveError("waves: cannot create '" + tmp + "' (for '" + path + "'): " + errno_text());
    const bool ok = std::fwrite(text.data(), 1, text.size(), f) == text.size();
    const std::string err = errno_text();
    if (std::fclose(f) != 0 || !ok) {
        std::remove(tmp.c_str());
        throw WaveError("waves: cannot write '" + tmp + "': " + err);
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        const std::string e = errno_text();
        std::remove(tmp.c_str());
        throw WaveError("waves: cannot rename '" + tmp + "' to '" + path + "': " + e);
    }
}

}  // namespace imap::waves
