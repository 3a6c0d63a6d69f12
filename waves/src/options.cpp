#include <algorithm>
#include <cmath>
#include <sstream>

#include "imap/waves/isa_trace.hpp"

namespace imap::waves {

namespace {

[[noreturn]] void bad(const std::string& value, const std::string& opt, const std::string& want) {
    throw WaveError("invalid value '" + value + "' for " + opt + ": expected " + want);
}

bool parse_uint(const std::string& s, uint64_t& v) {
    if (s.empty() || s.size() > 19) return false;
    v = 0;
    for (const char c : s) {
        if (c < '0' || c > '9') return false;
        v = v * 10 + static_cast<uint64_t>(c - '0');
    }
    return true;
}

std::vector<std::string> split(const std::string& s, char sep) {
    std::vector<std::string> out;
    std::string cur;
    std::istringstream in(s);
    while (std::getline(in, cur, sep)) out.push_back(cur);
    if (!s.empty() && s.back() == sep) out.emplace_back();
    return out;
}

// A window bound: cycles, or a number with ns / us / ms.
bool parse_bound(const std::string& s, double clock_mhz, uint64_t& cycles) {
    if (parse_uint(s, cycles)) return true;
    double scale = 0;  // ns per unit
    std::string num;
    auto ends = [&](const char* suf) {
        const size_t n = std::char_traits<char>::length(suf);
        return s.size() > n && s.compare(s.size() - n, n, suf) == 0;
    };
    if (ends("ns"))
        scale = 1, num = s.substr(0, s.size() - 2);
    else if (ends("us"))
        scale = 1e3, num = s.substr(0, s.size() - 2);
    else if (ends("ms"))
        scale = 1e6, num = s.substr(0, s.size() - 2);
    else
        return false;
    char* end = nullptr;
    const double v = std::strtod(num.c_str(), &end);
    if (num.empty() || end != num.c_str() + num.size() || !(v >= 0) || !std::isfinite(v))
        return false;
    const double c = std::floor(v * scale * clock_mhz / 1e3 + 1e-9);
    if (c > 1e18) return false;
    cycles = static_cast<uint64_t>(c);
    return true;
}

}  // namespace

TraceSelection parse_trace_selection(const std::string& pes, const std::string& window,
                                     const std::string& signals, double limit_mb,
                                     const isa::MachineConfig& cfg) {
    TraceSelection sel;
    const int P = cfg.pes;
    const std::string pe_want =
        "PEs as a:b (inclusive) or a list 1,5,9 with PEs in 0.." + std::to_string(P - 1);
    const std::string ps = pes.empty() ? std::string("0:3") : pes;
    for (const std::string& item : split(ps, ',')) {
        const size_t colon = item.find(':');
        uint64_t a = 0, b = 0;
        if (colon == std::string::npos) {
            if (!parse_uint(item, a)) bad(ps, "--trace-pes", pe_want);
            b = a;
        } else if (!parse_uint(item.substr(0, colon), a) ||
                   !parse_uint(item.substr(colon + 1), b) || b < a) {
            bad(ps, "--trace-pes", pe_want);
        }
        if (b >= static_cast<uint64_t>(P)) bad(ps, "--trace-pes", pe_want);
        for (uint64_t p = a; p <= b; ++p) sel.pes.push_back(static_cast<int>(p));
    }
    std::sort(sel.pes.begin(), sel.pes.end());
    sel.pes.erase(std::unique(sel.pes.begin(), sel.pes.end()), sel.pes.end());
    if (sel.pes.size() > 256)
        bad(ps, "--trace-pes", "at most 256 PEs (the waves would be unreadable)");

    if (!window.empty()) {
        const std::string want =
            "t0:t1 in cycles or with a ns/us/ms unit (e.g. 100000:101000 or 2.5us:3us), "
            "t0 < t1, either side may be empty";
        const size_t colon = window.find(':');
        if (colon == std::string::npos) bad(window, "--trace-window", want);
        const std::string a = window.substr(0, colon), b = window.substr(colon + 1);
        if (!a.empty() && !parse_bound(a, cfg.clock_mhz, sel.t0))
            bad(window, "--trace-window", want);
        if (!b.empty() && !parse_bound(b, cfg.clock_mhz, sel.t1))
            bad(window, "--trace-window", want);
        if (sel.t1 <= sel.t0) bad(window, "--trace-window", want);
    }

    if (!signals.empty() && signals != "all") {
        sel.cp = sel.ring = sel.mask = sel.mem = sel.regs = false;
        const std::string want = "a comma list of cp, ring, mask, mem, regs (or all)";
        for (const std::string& g : split(signals, ',')) {
            if (g == "cp")
                sel.cp = true;
            else if (g == "ring")
                sel.ring = true;
            else if (g == "mask")
                sel.mask = true;
            else if (g == "mem")
                sel.mem = true;
            else if (g == "regs")
                sel.regs = true;
            else if (g == "all")
                sel.cp = sel.ring = sel.mask = sel.mem = sel.regs = true;
            else
                bad(signals, "--trace-signals", want);
        }
    }

    if (!(limit_mb > 0) || !std::isfinite(limit_mb) || limit_mb > 1e7) {
        std::ostringstream v;
        v << limit_mb;
        bad(v.str(), "--trace-limit-mb", "a size in MB > 0");
    }
    sel.limit_bytes = static_cast<uint64_t>(limit_mb * 1048576.0);
    std::ostringstream n;
    n << "--trace-limit-mb " << limit_mb;
    sel.limit_name = n.str();
    return sel;
}

}  // namespace imap::waves
