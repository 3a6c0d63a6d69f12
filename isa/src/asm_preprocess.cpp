// The assembler's source processing: splitting a text into lines, the
// conditionals (.if/.ifdef/.ifndef/.elif/.else/.endif), .rept and .macro
// blocks, macro expansion (parameters, \\@), .include (relative to the
// including file, or from AsmOptions::files) and the expansion budget that
// stops a runaway. Each processed line goes to Assembler::statement.
#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include "asm_internal.hpp"

namespace imap::isa::asm_detail {

namespace {

std::string first_word(const std::string& s) {
    size_t i = 0;
    while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
    size_t j = i;
    while (j < s.size() && ident_char(s[j])) ++j;
    return lower(s.substr(i, j - i));
}

std::vector<std::pair<std::string, int>> split_args(const std::string& s, int col0) {
    std::vector<std::pair<std::string, int>> out;
    const size_t end = std::min(comment_start(s), s.size());
    int depth = 0;
    bool in_str = false;
    size_t start = 0;
    auto push = [&](size_t b, size_t e) {
        while (b < e && (s[b] == ' ' || s[b] == '\t')) ++b;
        while (e > b && (s[e - 1] == ' ' || s[e - 1] == '\t' || s[e - 1] == '\r')) --e;
        out.push_back({s.substr(b, e - b), col0 + static_cast<int>(b)});
    };
    for (size_t i = 0; i < end; ++i) {
        const char c = s[i];
        if (string_char(s, &i, &in_str)) continue;
        if (c == '(' || c == '[') {
            ++depth;
        } else if (c == ')' || c == ']') {
            --depth;
        } else if (c == ',' && depth == 0) {
            push(start, i);
            start = i + 1;
        }
    }
    push(start, end);
    if (out.size() == 1 && out[0].first.empty()) out.clear();
    return out;
}

}  // namespace

std::optional<std::string> Assembler::read_file(const std::string& path, std::string* err) {
    std::ifstream f(path, std::ios::binary);
    if (!f) {
        *err = std::strerror(errno);
        return std::nullopt;
    }
    std::ostringstream s;
    s << f.rdbuf();
    return s.str();
}

void Assembler::process_text(const std::string& text, int file, int depth) {
    std::vector<Line> lines;
    std::string cur;
    int n = 1;
    for (size_t i = 0; i <= text.size(); ++i) {
        if (i == text.size() || text[i] == '\n') {
            if (i == text.size() && cur.empty()) break;
            lines.push_back({cur, file, n++, -1});
            cur.clear();
        } else {
            cur += text[i];
        }
    }
    process(lines, 0, lines.size(), depth);
}

// Index of the line closing a block opened at `i` (.macro/.endm, .rept/.endr).
// Scanned lines count against the expansion budget: a nested block is
// scanned again on every expansion of the blocks around it.
size_t Assembler::find_close(const std::vector<Line>& lines, size_t i, size_t end, const char* open,
                             const char* close) {
    int depth = 0;
    for (size_t j = i; j < end; ++j) {
        budget(lines[j], 1 + lines[j].text.size() / 16);
        const std::string w = first_word(lines[j].text);
        if (w == open)
            ++depth;
        else if (w == close && --depth == 0)
            return j;
    }
    return end;
}

void Assembler::process(const std::vector<Line>& lines, size_t begin, size_t end, int depth) {
    std::vector<Cond> conds;
    for (size_t i = begin; i < end; ++i) {
        const Line& L = lines[i];
        budget(L, 1 + L.text.size() / 16);
        const std::string w = first_word(L.text);
        if (w == ".if" || w == ".ifdef" || w == ".ifndef" || w == ".elif" || w == ".else" ||
            w == ".endif") {
            conditional(L, w, conds);
            continue;
        }
        if (!conds.empty() && !conds.back().active) continue;
        if (w == ".macro" || w == ".rept") {
            if (!block(lines, &i, end, w, depth)) return;
            continue;
        }
        if (w == ".endm" || w == ".endr") {
            error(L, 1, w + " without " + (w == ".endm" ? ".macro" : ".rept"));
            continue;
        }
        statement(L, depth);
    }
    if (!conds.empty()) error(conds.back().where, 1, "unterminated .if (missing .endif)");
}

// One .if / .ifdef / .ifndef / .elif / .else / .endif line: updates the
// stack of open conditionals.
void Assembler::conditional(const Line& L, const std::string& w, std::vector<Cond>& conds) {
    auto active = [&] { return conds.empty() || conds.back().active; };
    if (w == ".if" || w == ".ifdef" || w == ".ifndef") {
        if (!active()) {
            conds.push_back({false, false, true, false, L});
            return;
        }
        bool c = false;
        bool ok;
        std::vector<Token> t = lex_line(L, &ok);
        if (ok) {
            if (w == ".if") {
                const auto v = eval_now(L, t, {1, t.size()}, ".if");
                c = v && *v != 0;
            } else if (t.size() != 2 || t[1].kind != Tok::Ident) {
                error(L, t[0].col, w + " expects one symbol name");
            } else {
                c = (syms_.count(t[1].text) != 0) == (w == ".ifdef");
            }
        }
        conds.push_back({true, c, c, false, L});
        return;
    }
    bool ok;
    std::vector<Token> t = lex_line(L, &ok);
    const int col = ok && !t.empty() ? t[0].col : 1;
    if (conds.empty()) {
        error(L, col, w + " without .if");
        return;
    }
    Cond& c = conds.back();
    if (w == ".endif") {
        if (ok && t.size() > 1) error(L, t[1].col, "unexpected text after .endif");
        conds.pop_back();
        return;
    }
    if (c.seen_else) {
        error(L, col, w + " after .else");
        return;
    }
    if (w == ".else") {
        if (ok && t.size() > 1) error(L, t[1].col, "unexpected text after .else");
        c.seen_else = true;
        c.active = c.parent_active && !c.taken;
        c.taken = true;
    } else {
        bool v = false;
        if (c.parent_active && !c.taken && ok) {
            const auto x = eval_now(L, t, {1, t.size()}, ".elif");
            v = x && *x != 0;
        }
        c.active = v;
        c.taken = c.taken || v;
    }
}

// A .macro (defined) or .rept (expanded) block opened at lines[*i]; *i moves
// to its closing line. False when the block is not closed.
bool Assembler::block(const std::vector<Line>& lines, size_t* i, size_t end, const std::string& w,
                      int depth) {
    const Line& L = lines[*i];
    const bool macro = w == ".macro";
    const size_t j =
        find_close(lines, *i, end, macro ? ".macro" : ".rept", macro ? ".endm" : ".endr");
    if (j >= end) {
        error(L, 1,
              macro ? "unterminated .macro (missing .endm)" : "unterminated .rept (missing .endr)");
        return false;
    }
    if (macro) {
        define_macro(lines, *i, j);
        *i = j;
        return true;
    }
    bool ok;
    std::vector<Token> t = lex_line(L, &ok);
    if (ok) {
        const auto n = eval_now(L, t, {1, t.size()}, ".rept");
        if (n && (*n < 0 || *n > 1000000)) {
            error(L, t[1].col, ".rept count " + std::to_string(*n) + " out of range 0..1000000");
        } else if (n) {
            if (depth > 64) {
                error(L, 1, "nesting too deep (64 levels of macros/.rept/.include)");
            } else {
                for (int64_t k = 0; k < *n; ++k) {
                    budget(L);
                    process(lines, *i + 1, j, depth + 1);
                }
            }
        }
    }
    *i = j;
    return true;
}

// Counts the work of the expansion and stops a runaway one: 1 per .rept
// iteration, per line processed or scanned and per token lexed, and 1 per
// 16 characters of each line processed or scanned. Bounds the time of any
// source (the slowest inputs known take 12 to 14 s of CPU in Release) and
// leaves room for about 2^24 typical instruction lines (the largest
// program).
void Assembler::budget(const Line& L, uint64_t units) {
    work_ += units;
    if (work_ <= kMaxWork) return;
    error(L, 1,
          "expansion too large: more than " + std::to_string(kMaxWork) +
              " work units (1 per line, per token and per 16 characters; runaway .rept "
              "or macro?)");
    throw Stop{};
}

void Assembler::define_macro(const std::vector<Line>& lines, size_t i, size_t j) {
    const Line& L = lines[i];
    bool ok;
    std::vector<Token> t = lex_line(L, &ok);
    if (!ok) return;
    if (t.size() < 2 || t[1].kind != Tok::Ident) {
        error(L, t[0].col, ".macro expects a name");
        return;
    }
    const std::string name = t[1].text;
    Macro m;
    m.where = loc(L);
    for (size_t k = 2; k < t.size(); ++k) {
        if (t[k].is(",")) continue;
        if (t[k].kind != Tok::Ident || t[k].text[0] == '.') {
            error(L, t[k].col, "macro parameter must be a name");
            return;
        }
        if (std::find(m.params.begin(), m.params.end(), t[k].text) != m.params.end()) {
            error(L, t[k].col, "duplicate macro parameter '" + t[k].text + "'");
            return;
        }
        m.params.push_back(t[k].text);
    }
    if (op_by_name(lower(name))) {
        error(L, t[1].col, "macro name '" + name + "' is an instruction mnemonic");
        return;
    }
    if (name[0] == '.') {
        error(L, t[1].col, "macro name '" + name + "' must not start with '.'");
        return;
    }
    if (macros_.count(name)) {
        error(L, t[1].col, "macro '" + name + "' already defined at " + macros_[name].where);
        return;
    }
    m.body.assign(lines.begin() + static_cast<std::ptrdiff_t>(i) + 1,
                  lines.begin() + static_cast<std::ptrdiff_t>(j));
    macros_[name] = std::move(m);
}

void Assembler::expand_macro(const std::string& name, const Line& L, int name_col, int depth) {
    const Macro& m = macros_.at(name);
    if (depth > 64) {
        error(L, name_col, "nesting too deep (64 levels of macros/.rept/.include)");
        return;
    }
    const size_t after = static_cast<size_t>(name_col - 1) + name.size();
    const auto args = split_args(L.text.substr(after), static_cast<int>(after) + 1);
    if (args.size() != m.params.size()) {
        std::string ps;
        for (const std::string& p : m.params) ps += (ps.empty() ? "" : ", ") + p;
        error(L, name_col,
              "macro '" + name + "' expects " + std::to_string(m.params.size()) + " argument(s) (" +
                  ps + "), got " + std::to_string(args.size()));
        return;
    }
    for (const auto& [a, col] : args)
        if (a.empty()) {
            error(L, col, "empty argument to macro '" + name + "'");
            return;
        }
    const int id = ++macro_counter_;
    std::string ctx = "in macro '" + name + "' expanded at " + loc(L);
    if (L.ctx >= 0) ctx += ", " + contexts_[static_cast<size_t>(L.ctx)];
    contexts_.push_back(ctx);
    const int ci = static_cast<int>(contexts_.size()) - 1;
    std::vector<Line> body;
    body.reserve(m.body.size());
    for (const Line& b : m.body) {
        Line x = b;
        x.ctx = ci;
        std::string out;
        const std::string& s = b.text;
        for (size_t k = 0; k < s.size(); ++k) {
            if (s[k] != '\\' || k + 1 >= s.size()) {
                out += s[k];
                continue;
            }
            if (s[k + 1] == '@') {
                out += std::to_string(id);
                ++k;
                continue;
            }
            size_t e = k + 1;
            while (e < s.size() && ident_char(s[e])) ++e;
            const std::string p = s.substr(k + 1, e - k - 1);
            const auto it = std::find(m.params.begin(), m.params.end(), p);
            if (it == m.params.end()) {
                out += s[k];  // left alone; the lexer reports it if it is code
                continue;
            }
            out += args[static_cast<size_t>(it - m.params.begin())].first;
            k = e - 1;
        }
        x.text = out;
        body.push_back(std::move(x));
    }
    process(body, 0, body.size(), depth + 1);
}

void Assembler::include(const Line& L, const Token& path_tok, int depth) {
    if (depth > 32) {
        error(L, path_tok.col, "include nesting too deep (32): recursive .include?");
        return;
    }
    std::string path = path_tok.text;
    const std::string& cur = files_[static_cast<size_t>(L.file)];
    if (!path.empty() && path[0] != '/') {
        const size_t slash = cur.find_last_of('/');
        if (slash != std::string::npos) path = cur.substr(0, slash + 1) + path;
    }
    std::string err;
    std::optional<std::string> text;
    if (opt_.files != nullptr) {
        const auto it = opt_.files->find(path);
        if (it != opt_.files->end()) text = it->second;
    }
    if (!text) text = read_file(path, &err);
    if (!text) {
        error(L, path_tok.col, "cannot open include file '" + path + "': " + err);
        return;
    }
    const int f = add_file(path);
    process_text(*text, f, depth + 1);
}

}  // namespace imap::isa::asm_detail
