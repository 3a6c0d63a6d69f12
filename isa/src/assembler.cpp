// The assembler: preprocessing (macros, .rept, .if, .include, -D), labels
// with forward references, constant expressions, and encoding through the
// opcode table. Syntax reference: docs/isa.md.
#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <functional>
#include <optional>
#include <sstream>

#include "imap/isa/assembler.hpp"
#include "imap/isa/encoding.hpp"
#include "imap/isa/opcodes.hpp"

namespace imap::isa {

std::string Diagnostic::str() const {
    std::string s = file;
    if (line > 0) {
        s += ":" + std::to_string(line);
        if (col > 0) s += ":" + std::to_string(col);
    }
    return s + ": error: " + message;
}

namespace {
std::string join_diags(const std::vector<Diagnostic>& d) {
    std::string s;
    for (const Diagnostic& x : d) s += (s.empty() ? "" : "\n") + x.str();
    return s;
}
}  // namespace

AsmError::AsmError(std::vector<Diagnostic> d)
    : std::runtime_error(join_diags(d)), diags_(std::move(d)) {}

namespace {

// ---------------------------------------------------------------------------
// Lexer

enum class Tok { Ident, Number, String, Punct };

struct Token {
    Tok kind;
    std::string text;  // identifier / punctuation / string contents
    int64_t value = 0;
    int col = 0;  // 1-based
    bool is(const char* p) const { return kind == Tok::Punct && text == p; }
};

struct LexError {
    int col;
    std::string msg;
};

bool ident_start(char c) {
    return std::isalpha(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '$';
}
bool ident_char(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '$';
}

// Index where the comment of a line starts (or npos). ';' always starts a
// comment (outside strings); '#' does when it is the first non-blank
// character or is followed by a blank or the end of the line.
size_t comment_start(const std::string& s) {
    bool in_str = false;
    bool seen = false;
    for (size_t i = 0; i < s.size(); ++i) {
        const char c = s[i];
        if (in_str) {
            if (c == '\\')
                ++i;
            else if (c == '"')
                in_str = false;
            continue;
        }
        if (c == '"')
            in_str = true;
        else if (c == ';')
            return i;
        else if (c == '#') {
            const char n = i + 1 < s.size() ? s[i + 1] : '\0';
            if (!seen || n == '\0' || n == ' ' || n == '\t' || n == '\r') return i;
        }
        if (c != ' ' && c != '\t') seen = true;
    }
    return std::string::npos;
}

std::vector<Token> lex(const std::string& line) {
    std::vector<Token> out;
    const size_t end = std::min(comment_start(line), line.size());
    size_t i = 0;
    while (i < end) {
        const char c = line[i];
        const int col = static_cast<int>(i) + 1;
        if (c == ' ' || c == '\t' || c == '\r') {
            ++i;
            continue;
        }
        if (ident_start(c)) {
            size_t j = i + 1;
            while (j < end && ident_char(line[j])) ++j;
            out.push_back({Tok::Ident, line.substr(i, j - i), 0, col});
            i = j;
            continue;
        }
        if (std::isdigit(static_cast<unsigned char>(c))) {
            size_t j = i;
            int base = 10;
            if (c == '0' && i + 1 < end && (line[i + 1] == 'x' || line[i + 1] == 'X')) {
                base = 16;
                j += 2;
            } else if (c == '0' && i + 1 < end && (line[i + 1] == 'b' || line[i + 1] == 'B')) {
                base = 2;
                j += 2;
            }
            const size_t digits = j;
            uint64_t v = 0;
            bool overflow = false;
            while (j < end && std::isalnum(static_cast<unsigned char>(line[j]))) {
                const char d = static_cast<char>(std::tolower(static_cast<unsigned char>(line[j])));
                int dv = std::isdigit(static_cast<unsigned char>(d)) ? d - '0'
                         : (d >= 'a' && d <= 'f')                    ? d - 'a' + 10
                                                                     : 99;
                if (dv >= base)
                    throw LexError{col, "invalid number '" + line.substr(i, j + 1 - i) + "'"};
                if (v > (UINT64_MAX - static_cast<uint64_t>(dv)) / static_cast<uint64_t>(base))
                    overflow = true;
                v = v * static_cast<uint64_t>(base) + static_cast<uint64_t>(dv);
                ++j;
            }
            if (j == digits) throw LexError{col, "invalid number '" + line.substr(i, j - i) + "'"};
            if (overflow || v > static_cast<uint64_t>(INT64_MAX))
                throw LexError{col, "number '" + line.substr(i, j - i) + "' is too large"};
            out.push_back({Tok::Number, line.substr(i, j - i), static_cast<int64_t>(v), col});
            i = j;
            continue;
        }
        if (c == '"') {
            std::string s;
            size_t j = i + 1;
            bool closed = false;
            while (j < end) {
                if (line[j] == '\\' && j + 1 < end) {
                    s += line[j + 1];
                    j += 2;
                } else if (line[j] == '"') {
                    closed = true;
                    ++j;
                    break;
                } else {
                    s += line[j++];
                }
            }
            if (!closed) throw LexError{col, "missing closing '\"'"};
            out.push_back({Tok::String, s, 0, col});
            i = j;
            continue;
        }
        static const char* two[] = {"<<", ">>", "<=", ">=", "==", "!=", "&&", "||"};
        bool matched = false;
        for (const char* t : two) {
            if (i + 1 < end && line[i] == t[0] && line[i + 1] == t[1]) {
                out.push_back({Tok::Punct, t, 0, col});
                i += 2;
                matched = true;
                break;
            }
        }
        if (matched) continue;
        if (std::strchr("+-*/%&|^~!()[],:#<>=", c)) {
            out.push_back({Tok::Punct, std::string(1, c), 0, col});
            ++i;
            continue;
        }
        if (c == '\\')
            throw LexError{col, "'\\' outside a macro body (or unknown macro parameter)"};
        throw LexError{col, std::string("unexpected character '") + c + "'"};
    }
    return out;
}

std::string lower(std::string s) {
    for (char& c : s) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
    return s;
}

// r<digits> / c<digits>: register syntax (never a symbol name).
bool register_like(const std::string& name, char* kind, long* num) {
    const std::string l = lower(name);
    if (l.size() < 2 || (l[0] != 'r' && l[0] != 'c')) return false;
    for (size_t i = 1; i < l.size(); ++i)
        if (!std::isdigit(static_cast<unsigned char>(l[i]))) return false;
    if (l.size() > 6) {
        *num = 1000000;
    } else {
        *num = std::stol(l.substr(1));
    }
    *kind = l[0];
    return true;
}

// ---------------------------------------------------------------------------
// Expressions

struct ExprError {
    int col;
    std::string msg;
};

using Lookup = std::function<std::optional<int64_t>(const std::string&)>;

class Expr {
  public:
    Expr(const std::vector<Token>& t, size_t b, size_t e, const Lookup& look)
        : t_(t), pos_(b), end_(e), look_(look) {}

    // Parses the whole range. `undef` tells whether an unknown symbol was used.
    int64_t parse_all() {
        if (pos_ >= end_) throw ExprError{col_at(pos_), "expected an expression"};
        const int64_t v = binary(0);
        if (pos_ < end_)
            throw ExprError{t_[pos_].col, "unexpected '" + t_[pos_].text + "' in expression"};
        return v;
    }
    bool undef = false;
    std::string undef_name;
    int undef_col = 0;

  private:
    int col_at(size_t i) const {
        if (i < end_) return t_[i].col;
        if (end_ > 0 && end_ <= t_.size()) {
            const Token& last = t_[end_ - 1];
            return last.col + static_cast<int>(last.text.size());
        }
        return 1;
    }

    static int prec(const Token& tk) {
        if (tk.kind != Tok::Punct) return -1;
        static const std::pair<const char*, int> ops[] = {
            {"||", 1}, {"&&", 2}, {"|", 3},  {"^", 4},  {"&", 5},  {"==", 6},
            {"!=", 6}, {"<", 7},  {"<=", 7}, {">", 7},  {">=", 7}, {"<<", 8},
            {">>", 8}, {"+", 9},  {"-", 9},  {"*", 10}, {"/", 10}, {"%", 10}};
        for (const auto& [s, p] : ops)
            if (tk.text == s) return p;
        return -1;
    }

    int64_t binary(int min_prec) {
        int64_t lhs = unary();
        while (pos_ < end_) {
            const Token& op = t_[pos_];
            const int p = prec(op);
            if (p < 0 || p < min_prec) break;
            ++pos_;
            const int64_t rhs = binary(p + 1);
            lhs = apply(op, lhs, rhs);
        }
        return lhs;
    }

    int64_t apply(const Token& op, int64_t a, int64_t b) {
        const uint64_t ua = static_cast<uint64_t>(a), ub = static_cast<uint64_t>(b);
        const std::string& o = op.text;
        if (o == "+") return static_cast<int64_t>(ua + ub);
        if (o == "-") return static_cast<int64_t>(ua - ub);
        if (o == "*") return static_cast<int64_t>(ua * ub);
        if (o == "/" || o == "%") {
            if (b == 0) {
                if (undef) return 0;
                throw ExprError{op.col, "division by zero"};
            }
            if (a == INT64_MIN && b == -1) throw ExprError{op.col, "overflow in division"};
            return o == "/" ? a / b : a % b;
        }
        if (o == "<<" || o == ">>") {
            if (b < 0 || b > 63) {
                if (undef) return 0;
                throw ExprError{op.col, "shift count " + std::to_string(b) + " out of range 0..63"};
            }
            if (o == "<<") return static_cast<int64_t>(ua << b);
            return a < 0 ? ~(~a >> b) : a >> b;
        }
        if (o == "&") return a & b;
        if (o == "|") return a | b;
        if (o == "^") return a ^ b;
        if (o == "==") return a == b;
        if (o == "!=") return a != b;
        if (o == "<") return a < b;
        if (o == "<=") return a <= b;
        if (o == ">") return a > b;
        if (o == ">=") return a >= b;
        if (o == "&&") return (a != 0) && (b != 0);
        if (o == "||") return (a != 0) || (b != 0);
        throw ExprError{op.col, "unknown operator '" + o + "'"};
    }

    // Nesting of parentheses and unary operators is bounded: the parser is
    // recursive, and a deep enough nest would overflow the stack.
    static constexpr int kMaxDepth = 256;

    int64_t unary() {
        if (pos_ >= end_) throw ExprError{col_at(pos_), "expected a value"};
        if (++depth_ > kMaxDepth)
            throw ExprError{t_[pos_].col, "expression nested too deeply (more than " +
                                              std::to_string(kMaxDepth) + " levels)"};
        const int64_t v = operand();
        --depth_;
        return v;
    }

    int64_t operand() {
        const Token& tk = t_[pos_];
        if (tk.is("-")) {
            ++pos_;
            return static_cast<int64_t>(0 - static_cast<uint64_t>(unary()));
        }
        if (tk.is("+")) {
            ++pos_;
            return unary();
        }
        if (tk.is("~")) {
            ++pos_;
            return ~unary();
        }
        if (tk.is("!")) {
            ++pos_;
            return unary() == 0;
        }
        if (tk.is("(")) {
            ++pos_;
            const int64_t v = binary(0);
            if (pos_ >= end_ || !t_[pos_].is(")")) throw ExprError{col_at(pos_), "missing ')'"};
            ++pos_;
            return v;
        }
        if (tk.kind == Tok::Number) {
            ++pos_;
            return tk.value;
        }
        if (tk.kind == Tok::Ident) {
            ++pos_;
            char kind;
            long num;
            if (register_like(tk.text, &kind, &num))
                throw ExprError{tk.col,
                                "register '" + tk.text + "' cannot be used in an expression"};
            const std::optional<int64_t> v = look_(tk.text);
            if (v) return *v;
            if (!undef) {
                undef = true;
                undef_name = tk.text;
                undef_col = tk.col;
            }
            return 0;
        }
        if (tk.is("#"))
            throw ExprError{tk.col, "unexpected '#' (immediates take a single leading '#')"};
        throw ExprError{tk.col, "unexpected '" + tk.text + "' in expression"};
    }

    const std::vector<Token>& t_;
    size_t pos_, end_;
    const Lookup& look_;
    int depth_ = 0;
};

// ---------------------------------------------------------------------------
// The assembler proper

struct Line {
    std::string text;
    int file = 0;
    int line = 0;
    int ctx = -1;  // expansion context (index into contexts_) or -1
};

struct Range {
    size_t b, e;
    bool empty() const { return b >= e; }
};

enum class Slot {
    Imm8,
    Shift3,
    Byte2,
    Imm32,
    Off32,
    Target,
    RingK,
    Csh,
    Port,
    PhaseId,
    LdxOff,
    Raw64
};

struct Stop {};  // too many errors

class Assembler {
  public:
    explicit Assembler(const AsmOptions& o) : opt_(o) {
        phases_.push_back("default");
        for (const auto& [name, value] : o.defines) {
            std::string why = bad_name(name);
            if (!why.empty()) {
                diags_.push_back({"<command line>", 0, 0, "-D " + name + ": " + why});
                continue;
            }
            syms_[name] = {value, Sym::Define, "-D " + name + "=" + std::to_string(value)};
        }
    }

    Program run(const std::string& text, const std::string& name) {
        try {
            if (!diags_.empty()) throw Stop{};
            const int f = add_file(name);
            process_text(text, f, 0);
            resolve_fixups();
        } catch (const Stop&) {
        }
        if (!diags_.empty()) throw AsmError(diags_);
        Program p;
        p.code = code_;
        p.phases = phases_;
        p.symbols = labels_;
        if (opt_.source_map) {
            p.files = files_;
            p.source_map = map_;
        }
        return p;
    }

    static std::optional<std::string> read_file(const std::string& path, std::string* err) {
        std::ifstream f(path, std::ios::binary);
        if (!f) {
            *err = std::strerror(errno);
            return std::nullopt;
        }
        std::ostringstream s;
        s << f.rdbuf();
        return s.str();
    }

  private:
    struct Sym {
        int64_t value;
        enum Kind { Equ, Set, Label, Define } kind;
        std::string where;
    };
    struct Macro {
        std::vector<std::string> params;
        std::vector<Line> body;
        std::string where;
    };
    struct Fixup {
        size_t index;
        Slot slot;
        std::vector<Token> expr;
        Line line;
        int col;
    };

    // ---- diagnostics ----
    std::string loc(const Line& l) const {
        return files_[static_cast<size_t>(l.file)] + ":" + std::to_string(l.line);
    }
    void error(const Line& l, int col, const std::string& msg) {
        std::string m = msg;
        if (l.ctx >= 0) m += " (" + contexts_[static_cast<size_t>(l.ctx)] + ")";
        diags_.push_back({files_[static_cast<size_t>(l.file)], l.line, col, m});
        if (static_cast<int>(diags_.size()) >= opt_.max_errors) {
            diags_.push_back(
                {files_[static_cast<size_t>(l.file)], l.line, col,
                 "too many errors (" + std::to_string(opt_.max_errors) + "), stopping"});
            throw Stop{};
        }
    }

    int add_file(const std::string& name) {
        files_.push_back(name);
        return static_cast<int>(files_.size()) - 1;
    }

    static std::string bad_name(const std::string& name) {
        if (name.empty() || !ident_start(name[0]) || name[0] == '.')
            return "'" + name + "' is not a valid name";
        for (char c : name)
            if (!ident_char(c)) return "'" + name + "' is not a valid name";
        char k;
        long n;
        if (register_like(name, &k, &n)) return "'" + name + "' is a register name";
        if (lower(name) == "ext") return "'ext' is reserved";
        return "";
    }

    std::optional<int64_t> lookup(const std::string& name) const {
        auto it = syms_.find(name);
        if (it == syms_.end()) return std::nullopt;
        return it->second.value;
    }

    // ---- source processing ----
    void process_text(const std::string& text, int file, int depth) {
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

    static std::string first_word(const std::string& s) {
        size_t i = 0;
        while (i < s.size() && (s[i] == ' ' || s[i] == '\t')) ++i;
        size_t j = i;
        while (j < s.size() && ident_char(s[j])) ++j;
        return lower(s.substr(i, j - i));
    }

    // Index of the line closing a block opened at `i` (.macro/.endm, .rept/.endr).
    // Scanned lines count against the expansion budget: a nested block is
    // scanned again on every expansion of the blocks around it.
    size_t find_close(const std::vector<Line>& lines, size_t i, size_t end, const char* open,
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

    struct Cond {
        bool parent_active, active, taken, seen_else;
        Line where;
    };

    std::vector<Token> lex_line(const Line& l, bool* ok) {
        try {
            *ok = true;
            std::vector<Token> t = lex(l.text);
            budget(l, t.size());
            return t;
        } catch (const LexError& e) {
            error(l, e.col, e.msg);
            *ok = false;
            return {};
        }
    }

    // Evaluates a condition / count: all symbols must be defined.
    std::optional<int64_t> eval_now(const Line& l, const std::vector<Token>& t, Range r,
                                    const char* what) {
        const Lookup look = [this](const std::string& n) { return lookup(n); };
        try {
            Expr e(t, r.b, r.e, look);
            const int64_t v = e.parse_all();
            if (e.undef) {
                error(l, e.undef_col,
                      "undefined symbol '" + e.undef_name + "' in " + what +
                          " (must be defined before this line)");
                return std::nullopt;
            }
            return v;
        } catch (const ExprError& x) {
            error(l, x.col, x.msg);
            return std::nullopt;
        }
    }

    void process(const std::vector<Line>& lines, size_t begin, size_t end, int depth) {
        std::vector<Cond> conds;
        auto active = [&] { return conds.empty() || conds.back().active; };
        for (size_t i = begin; i < end; ++i) {
            const Line& L = lines[i];
            budget(L, 1 + L.text.size() / 16);
            const std::string w = first_word(L.text);
            if (w == ".if" || w == ".ifdef" || w == ".ifndef") {
                if (!active()) {
                    conds.push_back({false, false, true, false, L});
                    continue;
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
                continue;
            }
            if (w == ".elif" || w == ".else" || w == ".endif") {
                bool ok;
                std::vector<Token> t = lex_line(L, &ok);
                const int col = ok && !t.empty() ? t[0].col : 1;
                if (conds.empty()) {
                    error(L, col, w + " without .if");
                    continue;
                }
                Cond& c = conds.back();
                if (w == ".endif") {
                    if (ok && t.size() > 1) error(L, t[1].col, "unexpected text after .endif");
                    conds.pop_back();
                    continue;
                }
                if (c.seen_else) {
                    error(L, col, w + " after .else");
                    continue;
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
                continue;
            }
            if (!active()) continue;
            if (w == ".macro") {
                const size_t j = find_close(lines, i, end, ".macro", ".endm");
                if (j >= end) {
                    error(L, 1, "unterminated .macro (missing .endm)");
                    return;
                }
                define_macro(lines, i, j);
                i = j;
                continue;
            }
            if (w == ".rept") {
                const size_t j = find_close(lines, i, end, ".rept", ".endr");
                if (j >= end) {
                    error(L, 1, "unterminated .rept (missing .endr)");
                    return;
                }
                bool ok;
                std::vector<Token> t = lex_line(L, &ok);
                if (ok) {
                    const auto n = eval_now(L, t, {1, t.size()}, ".rept");
                    if (n && (*n < 0 || *n > 1000000)) {
                        error(L, t[1].col,
                              ".rept count " + std::to_string(*n) + " out of range 0..1000000");
                    } else if (n) {
                        if (depth > 64) {
                            error(L, 1, "nesting too deep (64 levels of macros/.rept/.include)");
                        } else {
                            for (int64_t k = 0; k < *n; ++k) {
                                budget(L);
                                process(lines, i + 1, j, depth + 1);
                            }
                        }
                    }
                }
                i = j;
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

    // Counts the work of the expansion and stops a runaway one: 1 per .rept
    // iteration, per line processed or scanned and per token lexed, and 1 per
    // 16 characters of each line processed or scanned. Bounds the time of any
    // source (the slowest inputs known take 12 to 14 s of CPU in Release) and
    // leaves room for about 2^24 typical instruction lines (the largest
    // program).
    void budget(const Line& L, uint64_t units = 1) {
        work_ += units;
        if (work_ <= kMaxWork) return;
        error(L, 1,
              "expansion too large: more than " + std::to_string(kMaxWork) +
                  " work units (1 per line, per token and per 16 characters; runaway .rept "
                  "or macro?)");
        throw Stop{};
    }

    void define_macro(const std::vector<Line>& lines, size_t i, size_t j) {
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

    static std::vector<std::pair<std::string, int>> split_args(const std::string& s, int col0) {
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
            if (in_str) {
                if (c == '\\')
                    ++i;
                else if (c == '"')
                    in_str = false;
            } else if (c == '"') {
                in_str = true;
            } else if (c == '(' || c == '[') {
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

    void expand_macro(const std::string& name, const Line& L, int name_col, int depth) {
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
                  "macro '" + name + "' expects " + std::to_string(m.params.size()) +
                      " argument(s) (" + ps + "), got " + std::to_string(args.size()));
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

    void include(const Line& L, const Token& path_tok, int depth) {
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

    // ---- statements ----
    void define_label(const Line& L, const Token& t) {
        const std::string why = bad_name(t.text);
        if (!why.empty()) {
            error(L, t.col, "invalid label: " + why);
            return;
        }
        auto it = syms_.find(t.text);
        if (it != syms_.end()) {
            error(L, t.col, "symbol '" + t.text + "' already defined (" + it->second.where + ")");
            return;
        }
        const uint32_t pc = static_cast<uint32_t>(code_.size());
        syms_[t.text] = {pc, Sym::Label, "label at " + loc(L)};
        labels_[t.text] = pc;
    }

    void statement(const Line& L, int depth) {
        bool ok;
        std::vector<Token> t = lex_line(L, &ok);
        if (!ok) return;
        size_t k = 0;
        while (k + 1 < t.size() && t[k].kind == Tok::Ident && t[k + 1].is(":") &&
               t[k].text[0] != '.') {
            define_label(L, t[k]);
            k += 2;
        }
        if (k >= t.size()) return;
        const Token& head = t[k];
        if (head.kind != Tok::Ident) {
            error(L, head.col, "expected an instruction, a directive or a label");
            return;
        }
        if (head.text[0] == '.') {
            directive(L, t, k, depth);
            return;
        }
        if (macros_.count(head.text)) {
            expand_macro(head.text, L, head.col, depth);
            return;
        }
        const OpInfo* info = op_by_name(lower(head.text));
        if (!info) {
            error(L, head.col, "unknown instruction '" + head.text + "'");
            return;
        }
        instruction(L, *info, t, k);
    }

    void directive(const Line& L, const std::vector<Token>& t, size_t k, int depth) {
        const Token& head = t[k];
        const std::string d = lower(head.text);
        const size_t n = t.size() - k - 1;  // operand tokens
        auto need_name = [&]() -> bool {
            if (n < 1 || t[k + 1].kind != Tok::Ident) {
                error(L, n < 1 ? head.col : t[k + 1].col, d + " expects a name");
                return false;
            }
            return true;
        };
        if (d == ".equ" || d == ".set") {
            if (!need_name()) return;
            const Token& nt = t[k + 1];
            size_t b = k + 2;
            if (b < t.size() && t[b].is(",")) ++b;
            const std::string why = bad_name(nt.text);
            if (!why.empty()) {
                error(L, nt.col, d + ": " + why);
                return;
            }
            if (b >= t.size()) {
                error(L, nt.col + static_cast<int>(nt.text.size()), d + " expects a value");
                return;
            }
            const auto v = eval_now(L, t, {b, t.size()}, d.c_str());
            if (!v) return;
            auto it = syms_.find(nt.text);
            if (it != syms_.end()) {
                const bool both_set = d == ".set" && it->second.kind == Sym::Set;
                const bool same = d == ".equ" && it->second.value == *v &&
                                  (it->second.kind == Sym::Equ || it->second.kind == Sym::Define);
                if (!both_set && !same) {
                    error(L, nt.col,
                          "symbol '" + nt.text + "' already defined (" + it->second.where + ")");
                    return;
                }
                if (same) return;
            }
            syms_[nt.text] = {*v, d == ".set" ? Sym::Set : Sym::Equ, d + " at " + loc(L)};
            return;
        }
        if (d == ".reg") {
            if (!need_name()) return;
            const Token& nt = t[k + 1];
            size_t b = k + 2;
            if (b < t.size() && t[b].is(",")) ++b;
            const std::string why = bad_name(nt.text);
            if (!why.empty()) {
                error(L, nt.col, ".reg: " + why);
                return;
            }
            if (b + 1 != t.size()) {
                error(L, b < t.size() ? t[b].col : nt.col, ".reg expects: .reg NAME, rN|cN");
                return;
            }
            bool cp;
            uint8_t r;
            if (!reg_token(L, t[b], &cp, &r)) return;
            regs_[nt.text] = {cp, r};
            return;
        }
        if (d == ".phase" || d == ".defphase") {
            if (!need_name()) return;
            if (n != 1) {
                error(L, t[k + 2].col, "unexpected text after the phase name");
                return;
            }
            const std::string& name = t[k + 1].text;
            auto it = std::find(phases_.begin(), phases_.end(), name);
            uint32_t id = static_cast<uint32_t>(it - phases_.begin());
            if (it == phases_.end()) {
                if (phases_.size() >= 65536) {
                    error(L, t[k + 1].col, "too many phases (65536)");
                    return;
                }
                phases_.push_back(name);
            }
            if (d == ".phase") emit(L, Word{static_cast<uint8_t>(Op::PHASE), 0, 0, 0, id});
            return;
        }
        if (d == ".include") {
            if (n != 1 || t[k + 1].kind != Tok::String) {
                error(L, n ? t[k + 1].col : head.col, ".include expects a quoted file name");
                return;
            }
            include(L, t[k + 1], depth);
            return;
        }
        if (d == ".error") {
            if (n == 1 && t[k + 1].kind == Tok::String)
                error(L, head.col, t[k + 1].text);
            else
                error(L, head.col, ".error expects a quoted message");
            return;
        }
        if (d == ".word") {
            if (n < 1) {
                error(L, head.col, ".word expects a value");
                return;
            }
            const size_t idx = emit(L, Word{});
            value(L, t, {k + 1, t.size()}, Slot::Raw64, idx);
            return;
        }
        if (d == ".if" || d == ".ifdef" || d == ".ifndef" || d == ".else" || d == ".elif" ||
            d == ".endif" || d == ".macro" || d == ".endm" || d == ".rept" || d == ".endr") {
            error(L, head.col, d + " must start its line (not follow a label)");
            return;
        }
        error(L, head.col, "unknown directive '" + head.text + "'");
    }

    size_t emit(const Line& L, const Word& w) {
        if (code_.size() >= (1u << 24)) {
            error(L, 1, "program too large (16777216 instructions)");
            throw Stop{};
        }
        code_.push_back(w.encode());
        map_.push_back({static_cast<uint32_t>(L.file), static_cast<uint32_t>(L.line)});
        return code_.size() - 1;
    }

    // Stores `v` into the slot of instruction `idx`; returns "" or a range error.
    std::string apply(size_t idx, Slot s, int64_t v) {
        Word w = Word::decode(code_[idx]);
        auto range = [&](int64_t lo, int64_t hi, const char* what) -> std::string {
            if (v < lo || v > hi)
                return std::string(what) + " " + std::to_string(v) + " out of range " +
                       std::to_string(lo) + ".." + std::to_string(hi);
            return "";
        };
        std::string e;
        switch (s) {
            case Slot::Imm8:
                e = range(-128, 255, "immediate");
                w.imm = static_cast<uint32_t>(v & 0xff);
                break;
            case Slot::Shift3:
                e = range(0, 7, "shift count");
                w.imm = static_cast<uint32_t>(v);
                break;
            case Slot::Byte2:
                e = range(0, 3, "byte index");
                w.imm = static_cast<uint32_t>(v);
                break;
            case Slot::Csh:
                e = range(0, 31, "shift count");
                w.imm = static_cast<uint32_t>(v);
                break;
            case Slot::RingK:
                e = range(1, 65535, "hop count");
                w.imm = static_cast<uint32_t>(v);
                break;
            case Slot::PhaseId:
                e = range(0, 65535, "phase id");
                w.imm = static_cast<uint32_t>(v);
                break;
            case Slot::Port:
                e = range(0, 1, "video port");
                w.rd = static_cast<uint8_t>(v);
                break;
            case Slot::Imm32:
                e = range(INT32_MIN, UINT32_MAX, "immediate");
                w.imm = static_cast<uint32_t>(v);
                break;
            case Slot::Off32:
                e = range(INT32_MIN, INT32_MAX, "offset");
                w.imm = static_cast<uint32_t>(v);
                break;
            case Slot::Target:
                e = range(0, UINT32_MAX, "branch target");
                w.imm = static_cast<uint32_t>(v);
                break;
            case Slot::LdxOff:
                e = range(kLdxOffsetMin, kLdxOffsetMax, "ldx/stx offset");
                w.imm = (w.imm & ~kLdxOffsetMask) | (static_cast<uint32_t>(v) & kLdxOffsetMask);
                break;
            case Slot::Raw64:
                code_[idx] = static_cast<uint64_t>(v);
                return "";
        }
        if (e.empty()) code_[idx] = w.encode();
        return e;
    }

    // Evaluates tokens r (as "0 <r>" when `offset`) into a slot, now or at the end.
    void value(const Line& L, const std::vector<Token>& t, Range r, Slot s, size_t idx,
               bool offset = false) {
        std::vector<Token> ex;
        if (offset) ex.push_back({Tok::Number, "0", 0, t[r.b].col});
        ex.insert(ex.end(), t.begin() + static_cast<std::ptrdiff_t>(r.b),
                  t.begin() + static_cast<std::ptrdiff_t>(r.e));
        const Lookup look = [this](const std::string& n) { return lookup(n); };
        try {
            Expr e(ex, 0, ex.size(), look);
            const int64_t v = e.parse_all();
            if (e.undef) {
                // Forward reference: freeze the symbols known now, finish at the end.
                for (Token& tk : ex)
                    if (tk.kind == Tok::Ident)
                        if (auto x = lookup(tk.text)) tk = {Tok::Number, tk.text, *x, tk.col};
                fixups_.push_back({idx, s, std::move(ex), L, t[r.b].col});
                return;
            }
            const std::string err = apply(idx, s, v);
            if (!err.empty()) error(L, t[r.b].col, err);
        } catch (const ExprError& x) {
            error(L, x.col, x.msg);
        }
    }

    void resolve_fixups() {
        const Lookup look = [this](const std::string& n) { return lookup(n); };
        for (const Fixup& f : fixups_) {
            try {
                Expr e(f.expr, 0, f.expr.size(), look);
                const int64_t v = e.parse_all();
                if (e.undef) {
                    error(f.line, e.undef_col, "undefined symbol '" + e.undef_name + "'");
                    continue;
                }
                const std::string err = apply(f.index, f.slot, v);
                if (!err.empty()) error(f.line, f.col, err);
            } catch (const ExprError& x) {
                error(f.line, x.col, x.msg);
            }
        }
    }

    // ---- operands ----
    bool reg_token(const Line& L, const Token& tk, bool* cp, uint8_t* r) {
        if (tk.kind == Tok::Ident) {
            auto a = regs_.find(tk.text);
            if (a != regs_.end()) {
                *cp = a->second.first;
                *r = a->second.second;
                return true;
            }
            char kind;
            long num;
            if (register_like(tk.text, &kind, &num)) {
                *cp = kind == 'c';
                const long max = *cp ? kCpRegs - 1 : kMaxPeRegs - 1;
                if (num > max) {
                    error(L, tk.col,
                          "no register '" + tk.text + "' (" + (*cp ? "c0..c15" : "r0..r63") + ")");
                    return false;
                }
                *r = static_cast<uint8_t>(num);
                return true;
            }
        }
        error(L, tk.col, "expected a register, got '" + tk.text + "'");
        return false;
    }

    bool reg(const Line& L, const std::vector<Token>& t, Range r, bool want_cp, uint8_t* out) {
        if (r.empty()) return false;
        const char* what = want_cp ? "a CP register (c0..c15)" : "a PE register (r0..r63)";
        if (r.e - r.b != 1 || t[r.b].kind != Tok::Ident) {
            error(L, t[r.b].col, std::string("expected ") + what);
            return false;
        }
        bool cp;
        if (!reg_token(L, t[r.b], &cp, out)) return false;
        if (cp != want_cp) {
            error(L, t[r.b].col, std::string("expected ") + what + ", got '" + t[r.b].text + "'");
            return false;
        }
        return true;
    }

    void imm(const Line& L, const std::vector<Token>& t, Range r, Slot s, size_t idx) {
        if (!t[r.b].is("#")) {
            error(L, t[r.b].col, "expected '#' before an immediate value");
            return;
        }
        if (r.e - r.b < 2) {
            error(L, t[r.b].col + 1, "expected a value after '#'");
            return;
        }
        value(L, t, {r.b + 1, r.e}, s, idx);
    }

    void target(const Line& L, const std::vector<Token>& t, Range r, size_t idx) {
        if (t[r.b].is("#")) {
            error(L, t[r.b].col, "branch target is a label or expression, without '#'");
            return;
        }
        value(L, t, r, Slot::Target, idx);
    }

    bool brackets(const Line& L, const std::vector<Token>& t, Range r, Range* in) {
        if (t[r.b].is("[") && !t[r.e - 1].is("]")) {
            error(L, t[r.e - 1].col + static_cast<int>(t[r.e - 1].text.size()),
                  "missing ']' at the end of the memory operand");
            return false;
        }
        if (!t[r.b].is("[") || r.e - r.b < 2) {
            error(L, t[r.b].col, "expected a memory operand '[...]'");
            return false;
        }
        *in = {r.b + 1, r.e - 1};
        if (in->empty()) {
            error(L, t[r.b].col, "empty memory operand");
            return false;
        }
        return true;
    }

    // [cB], [cB + expr], [cB - expr] or [#expr]: base into rb, offset into imm.
    void mem(const Line& L, const std::vector<Token>& t, Range r, size_t idx) {
        Range in;
        if (!brackets(L, t, r, &in)) return;
        if (t[in.b].is("#")) {
            if (in.e - in.b < 2) {
                error(L, t[in.b].col + 1, "expected an address after '#'");
                return;
            }
            set_field(idx, 3, kNoBase);
            value(L, t, {in.b + 1, in.e}, Slot::Off32, idx);
            return;
        }
        bool cp = false;
        uint8_t b = 0;
        if (t[in.b].kind != Tok::Ident || !reg_token(L, t[in.b], &cp, &b)) {
            if (t[in.b].kind != Tok::Ident)
                error(L, t[in.b].col, "expected a CP base register [cN + offset] or [#address]");
            return;
        }
        if (!cp) {
            error(L, t[in.b].col,
                  "the base of a broadcast address is a CP register (c0..c15), got '" +
                      t[in.b].text + "' (per-PE addresses: ldx/stx)");
            return;
        }
        set_field(idx, 3, b);
        if (in.b + 1 == in.e) return;
        if (!t[in.b + 1].is("+") && !t[in.b + 1].is("-")) {
            error(L, t[in.b + 1].col, "expected '+' or '-' after the base register");
            return;
        }
        value(L, t, {in.b + 1, in.e}, Slot::Off32, idx, true);
    }

    // [ra], [ra:rb], optionally "+ cN", then an optional +/- offset.
    void memx(const Line& L, const std::vector<Token>& t, Range r, size_t idx) {
        Range in;
        if (!brackets(L, t, r, &in)) return;
        size_t k = in.b;
        uint8_t lo = 0, hi = 0;
        if (!reg(L, t, {k, k + 1}, false, &lo)) return;
        ++k;
        uint32_t flags = kLdxNoHigh;
        if (k < in.e && t[k].is(":")) {
            if (k + 1 >= in.e) {
                error(L, t[k].col + 1, "expected the high-byte register after ':'");
                return;
            }
            if (!reg(L, t, {k + 1, k + 2}, false, &hi)) return;
            flags = 0;
            k += 2;
        }
        if (k + 1 < in.e && t[k].is("+") && t[k + 1].kind == Tok::Ident) {
            bool cp;
            uint8_t c;
            const bool is_reg = regs_.count(t[k + 1].text) || [&] {
                char kk;
                long nn;
                return register_like(t[k + 1].text, &kk, &nn);
            }();
            if (is_reg) {
                if (!reg_token(L, t[k + 1], &cp, &c)) return;
                if (!cp) {
                    error(L, t[k + 1].col,
                          "expected a CP register after '+', got '" + t[k + 1].text + "'");
                    return;
                }
                flags |= kLdxUseCp | (uint32_t{c} << kLdxCpShift);
                k += 2;
            }
        }
        Word w = Word::decode(code_[idx]);
        w.ra = lo;
        w.rb = hi;
        w.imm = flags;
        code_[idx] = w.encode();
        if (k == in.e) return;
        if (!t[k].is("+") && !t[k].is("-")) {
            error(L, t[k].col, "expected '+' or '-' before the offset");
            return;
        }
        value(L, t, {k, in.e}, Slot::LdxOff, idx, true);
    }

    void set_field(size_t idx, int field, uint8_t v) {
        Word w = Word::decode(code_[idx]);
        if (field == 1)
            w.rd = v;
        else if (field == 2)
            w.ra = v;
        else
            w.rb = v;
        code_[idx] = w.encode();
    }

    static std::vector<Range> split_operands(const std::vector<Token>& t, size_t b) {
        std::vector<Range> out;
        if (b >= t.size()) return out;
        int depth = 0;
        size_t start = b;
        for (size_t i = b; i < t.size(); ++i) {
            if (t[i].is("[") || t[i].is("("))
                ++depth;
            else if (t[i].is("]") || t[i].is(")"))
                --depth;
            else if (t[i].is(",") && depth == 0) {
                out.push_back({start, i});
                start = i + 1;
            }
        }
        out.push_back({start, t.size()});
        return out;
    }

    static int operand_count(Format f) {
        switch (f) {
            case Format::None:
                return 0;
            case Format::R:
            case Format::Stat:
            case Format::J:
            case Format::Phase:
                return 1;
            case Format::Rr:
            case Format::Ri8:
            case Format::Cmp:
            case Format::Cmpi:
            case Format::Rc:
            case Format::Rk:
            case Format::Ld:
            case Format::Ldx:
            case Format::Ci:
            case Format::Cc:
            case Format::Cmem:
            case Format::B1:
                return 2;
            case Format::Rrr:
            case Format::Rri8:
            case Format::Rsh:
            case Format::Rck:
            case Format::Xfer:
            case Format::Ring:
            case Format::Ccc:
            case Format::Cci:
            case Format::Csh:
            case Format::Bcc:
                return 3;
            case Format::Video:
                return 4;
        }
        return 0;
    }

    void instruction(const Line& L, const OpInfo& info, const std::vector<Token>& t, size_t k) {
        const std::vector<Range> ops = split_operands(t, k + 1);
        const int want = operand_count(info.format);
        const std::string mn(info.mnemonic);
        if (static_cast<int>(ops.size()) != want) {
            const std::string syn = operand_syntax(info.format);
            error(L, t[k].col,
                  mn + " expects " + std::to_string(want) + " operand(s)" +
                      (syn.empty() ? "" : " (" + mn + " " + syn + ")") + ", got " +
                      std::to_string(ops.size()));
            return;
        }
        for (const Range& r : ops)
            if (r.empty()) {
                error(L, r.b < t.size() ? t[r.b].col : t.back().col, "empty operand");
                return;
            }
        const size_t idx = emit(L, Word{static_cast<uint8_t>(info.op)});
        uint8_t x = 0;
        auto pe = [&](int i, int field) {
            const Range& r = ops[static_cast<size_t>(i)];
            const OpInfo* imm_form = op_by_name(mn + "i");
            if (t[r.b].is("#") && imm_form != nullptr) {
                // an immediate where the register form wants a register
                error(L, t[r.b].col,
                      "expected a PE register (r0..r63), got an immediate: for an immediate "
                      "operand use " +
                          mn + "i (" + mn + "i " + operand_syntax(imm_form->format) + ")");
                return;
            }
            if (reg(L, t, r, false, &x)) set_field(idx, field, x);
        };
        auto cp = [&](int i, int field) {
            if (reg(L, t, ops[static_cast<size_t>(i)], true, &x)) set_field(idx, field, x);
        };
        auto im = [&](int i, Slot s) { imm(L, t, ops[static_cast<size_t>(i)], s, idx); };
        switch (info.format) {
            case Format::None:
                break;
            case Format::Rrr:
                pe(0, 1);
                pe(1, 2);
                pe(2, 3);
                break;
            case Format::Rri8:
                pe(0, 1);
                pe(1, 2);
                im(2, Slot::Imm8);
                break;
            case Format::Rr:
                pe(0, 1);
                pe(1, 2);
                break;
            case Format::Ri8:
                pe(0, 1);
                im(1, Slot::Imm8);
                break;
            case Format::Rsh:
                pe(0, 1);
                pe(1, 2);
                im(2, Slot::Shift3);
                break;
            case Format::Cmp:
                pe(0, 2);
                pe(1, 3);
                break;
            case Format::Cmpi:
                pe(0, 2);
                im(1, Slot::Imm8);
                break;
            case Format::R:
                pe(0, 1);
                break;
            case Format::Rc:
                pe(0, 1);
                cp(1, 2);
                break;
            case Format::Rck:
                pe(0, 1);
                cp(1, 2);
                im(2, Slot::Byte2);
                break;
            case Format::Rk:
                pe(0, 1);
                im(1, Slot::Byte2);
                break;
            case Format::Ld:
                pe(0, 1);
                mem(L, t, ops[1], idx);
                break;
            case Format::Ldx:
                pe(0, 1);
                memx(L, t, ops[1], idx);
                break;
            case Format::Xfer: {
                mem(L, t, ops[0], idx);
                const Range e = ops[1];
                if (e.e - e.b == 4 && t[e.b].kind == Tok::Ident && lower(t[e.b].text) == "ext" &&
                    t[e.b + 1].is("[") && t[e.b + 3].is("]")) {
                    if (reg(L, t, {e.b + 2, e.b + 3}, true, &x)) set_field(idx, 2, x);
                } else {
                    error(L, t[e.b].col, "expected an external address ext[cN]");
                }
                cp(2, 1);
                break;
            }
            case Format::Ring:
                pe(0, 1);
                pe(1, 2);
                im(2, Slot::RingK);
                break;
            case Format::Stat:
                cp(0, 1);
                break;
            case Format::Ci:
                cp(0, 1);
                im(1, Slot::Imm32);
                break;
            case Format::Cc:
                cp(0, 1);
                cp(1, 2);
                break;
            case Format::Ccc:
                cp(0, 1);
                cp(1, 2);
                cp(2, 3);
                break;
            case Format::Cci:
                cp(0, 1);
                cp(1, 2);
                im(2, Slot::Imm32);
                break;
            case Format::Csh:
                cp(0, 1);
                cp(1, 2);
                im(2, Slot::Csh);
                break;
            case Format::Cmem:
                cp(0, 1);
                mem(L, t, ops[1], idx);
                break;
            case Format::J:
                target(L, t, ops[0], idx);
                break;
            case Format::Bcc:
                cp(0, 2);
                cp(1, 3);
                target(L, t, ops[2], idx);
                break;
            case Format::B1:
                cp(0, 2);
                target(L, t, ops[1], idx);
                break;
            case Format::Video: {
                im(0, Slot::Port);
                mem(L, t, ops[1], idx);
                uint8_t y = 0, xx = 0;
                if (reg(L, t, ops[2], true, &y) && reg(L, t, ops[3], true, &xx))
                    set_field(idx, 2, static_cast<uint8_t>(y | (xx << 4)));
                break;
            }
            case Format::Phase:
                im(0, Slot::PhaseId);
                break;
        }
    }

    const AsmOptions& opt_;
    std::vector<Diagnostic> diags_;
    std::map<std::string, Sym> syms_;
    std::map<std::string, std::pair<bool, uint8_t>> regs_;
    std::map<std::string, Macro> macros_;
    std::vector<std::string> files_;
    std::vector<std::string> contexts_;
    std::vector<uint64_t> code_;
    std::vector<SourceLoc> map_;
    std::vector<std::string> phases_;
    std::map<std::string, uint32_t> labels_;
    std::vector<Fixup> fixups_;
    int macro_counter_ = 0;
    static constexpr uint64_t kMaxWork = 150000000;
    uint64_t work_ = 0;
};

}  // namespace

Program assemble_string(const std::string& text, const std::string& name, const AsmOptions& opt) {
    Assembler a(opt);
    return a.run(text, name);
}

Program assemble_file(const std::string& path, const AsmOptions& opt) {
    std::string err;
    const auto text = Assembler::read_file(path, &err);
    if (!text) throw AsmError({{path, 0, 0, "cannot open source file '" + path + "': " + err}});
    Assembler a(opt);
    return a.run(*text, path);
}

std::pair<std::string, int64_t> parse_define(const std::string& text) {
    const size_t eq = text.find('=');
    const std::string name = text.substr(0, eq);
    const std::string val = eq == std::string::npos ? "1" : text.substr(eq + 1);
    bool ok = !name.empty() && ident_start(name[0]) && name[0] != '.';
    for (char c : name) ok = ok && ident_char(c);
    char k;
    long n;
    if (!ok || register_like(name, &k, &n))
        throw std::invalid_argument("invalid -D '" + text + "': '" + name +
                                    "' is not a valid symbol name");
    try {
        const std::vector<Token> t = lex(val);
        const Lookup none = [](const std::string&) { return std::optional<int64_t>{}; };
        Expr e(t, 0, t.size(), none);
        const int64_t v = e.parse_all();
        if (e.undef)
            throw std::invalid_argument("invalid -D '" + text + "': unknown symbol '" +
                                        e.undef_name + "' (values must be numbers)");
        return {name, v};
    } catch (const LexError& e) {
        throw std::invalid_argument("invalid -D '" + text + "': " + e.msg);
    } catch (const ExprError& e) {
        throw std::invalid_argument("invalid -D '" + text + "': " + e.msg);
    }
}

}  // namespace imap::isa
