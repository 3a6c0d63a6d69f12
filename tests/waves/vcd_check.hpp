// A small VCD reader for the tests: checks that a file is well formed
// (declarations, every value change names a declared identifier with a value
// of the declared width, time stamps strictly increasing) and returns what it
// found. Not a general VCD parser: it reads what imap_waves writes.
#pragma once

#include <cstdint>
#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <string>
#include <vector>

namespace vcdcheck {

struct Var {
    int width = 0;
    std::string full;  // scope.name[w-1:0] as GTKWave names it
};

struct Parsed {
    std::string error;  // empty = well formed
    std::string timescale;
    std::map<std::string, Var> vars;  // by identifier code
    std::set<std::string> full_names;
    std::vector<uint64_t> times;
    size_t changes = 0;
    std::map<std::string, size_t> changes_by_name;
    // (time, value) of every change of each wire of at most 64 bits.
    std::map<std::string, std::vector<std::pair<uint64_t, uint64_t>>> history;
};

inline std::string read_all(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

inline Parsed parse(const std::string& text) {
    Parsed p;
    std::istringstream in(text);
    std::vector<std::string> scope;
    std::string tok;
    bool defs_done = false;
    auto fail = [&](const std::string& e) {
        if (p.error.empty()) p.error = e;
    };
    while (!defs_done && in >> tok) {
        if (tok == "$scope") {
            std::string kind, name, end;
            in >> kind >> name >> end;
            if (end != "$end") fail("bad $scope");
            scope.push_back(name);
        } else if (tok == "$upscope") {
            in >> tok;
            if (scope.empty())
                fail("$upscope without $scope");
            else
                scope.pop_back();
        } else if (tok == "$var") {
            std::string type, code, name, rest;
            int width = 0;
            in >> type >> width >> code >> name >> rest;
            std::string range;
            if (rest != "$end") {
                range = rest;
                in >> rest;
                if (rest != "$end") fail("bad $var");
            }
            std::string full;
            for (const auto& s : scope) full += s + ".";
            full += name;
            if (!range.empty()) full += range;
            if (p.vars.count(code)) fail("identifier declared twice: " + code);
            if (width < 1) fail("bad width");
            p.vars[code] = {width, full};
            p.full_names.insert(full);
        } else if (tok == "$timescale") {
            in >> p.timescale >> tok;
        } else if (tok == "$enddefinitions") {
            in >> tok;
            defs_done = true;
        } else if (tok[0] == '$') {
            while (in >> tok && tok != "$end") {
            }
        } else {
            fail("unexpected token in the header: " + tok);
        }
    }
    if (!defs_done) fail("no $enddefinitions");
    if (!scope.empty()) fail("unclosed scope");
    std::string line;
    bool in_comment = false;
    while (std::getline(in, line)) {
        if (line.empty()) continue;
        if (in_comment) {
            if (line == "$end") in_comment = false;
            continue;
        }
        if (line == "$comment") {
            in_comment = true;
            continue;
        }
        if (line == "$dumpvars" || line == "$end") continue;
        if (line[0] == '#') {
            const uint64_t t = std::stoull(line.substr(1));
            if (!p.times.empty() && t <= p.times.back())
                fail("time not increasing at #" + line.substr(1));
            p.times.push_back(t);
            continue;
        }
        if (p.times.empty()) fail("value change before the first time stamp");
        std::string code, value;
        if (line[0] == 'b') {
            const size_t sp = line.find(' ');
            if (sp == std::string::npos) {
                fail("bad vector change: " + line);
                continue;
            }
            value = line.substr(1, sp - 1);
            code = line.substr(sp + 1);
            for (const char c : value)
                if (c != '0' && c != '1') fail("bad bit in: " + line);
        } else if (line[0] == '0' || line[0] == '1') {
            value = line.substr(0, 1);
            code = line.substr(1);
        } else {
            fail("unexpected line: " + line);
            continue;
        }
        const auto v = p.vars.find(code);
        if (v == p.vars.end()) {
            fail("change of an undeclared identifier: " + line);
            continue;
        }
        if (static_cast<int>(value.size()) > v->second.width)
            fail("value wider than declared: " + line);
        if (v->second.width == 1 && line[0] == 'b') fail("vector change of a 1-bit wire: " + line);
        ++p.changes;
        ++p.changes_by_name[v->second.full];
        if (value.size() <= 64 && !p.times.empty())
            p.history[v->second.full].emplace_back(p.times.back(), std::stoull(value, nullptr, 2));
    }
    if (in_comment) fail("unterminated $comment");
    return p;
}

// Signal names referenced by a .gtkw file (lines that are not options,
// flags, comments or group rows).
// A combined vector of a .gtkw ("#{name} (bit)parent ..."): its name and
// its bits, most significant first.
struct GtkwVector {
    std::string name;
    std::vector<std::pair<int, std::string>> bits;
};
inline std::vector<GtkwVector> gtkw_vectors(const std::string& text) {
    std::vector<GtkwVector> out;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("#{", 0) != 0) continue;
        const size_t close = line.find('}');
        GtkwVector v;
        v.name = line.substr(2, close - 2);
        std::istringstream rest(line.substr(close + 1));
        std::string tok;
        while (rest >> tok) {
            const size_t rp = tok.find(')');
            if (tok.empty() || tok[0] != '(' || rp == std::string::npos) {
                v.bits.emplace_back(-1, tok);  // malformed: the test sees -1
                continue;
            }
            v.bits.emplace_back(std::stoi(tok.substr(1, rp - 1)), tok.substr(rp + 1));
        }
        out.push_back(v);
    }
    return out;
}

// The signals a .gtkw names (a combined vector's parents for "#{...}" lines).
inline std::vector<std::string> gtkw_signals(const std::string& text) {
    std::vector<std::string> out;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
        if (line.rfind("#{", 0) == 0) {
            for (const GtkwVector& v : gtkw_vectors(line + "\n"))
                for (const auto& b : v.bits) out.push_back(b.second);
            continue;
        }
        if (line.empty() || line[0] == '[' || line[0] == '@' || line[0] == '*' || line[0] == '-')
            continue;
        if (line[0] == '+') {
            const size_t sp = line.find("} ");
            if (sp != std::string::npos) line = line.substr(sp + 2);
        }
        out.push_back(line);
    }
    return out;
}

}  // namespace vcdcheck
