// The assembler: the public entry points (assemble_file / assemble_string,
// -D parsing, diagnostics), the Assembler's symbols and errors, and its
// statements: labels, directives (.equ/.set, .reg, .phase/.defphase,
// .include, .error, .word) and the dispatch of a line to a macro or an
// instruction. Lexer: asm_lexer.cpp; expressions: asm_expr.cpp; conditionals,
// .rept, macros, .include: asm_preprocess.cpp; operands and encoding:
// asm_encode.cpp. Syntax reference: docs/isa.md.
#include <algorithm>

#include "asm_internal.hpp"

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

namespace asm_detail {

Assembler::Assembler(const AsmOptions& o) : opt_(o) {
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

Program Assembler::run(const std::string& text, const std::string& name) {
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

std::string Assembler::loc(const Line& l) const {
    return files_[static_cast<size_t>(l.file)] + ":" + std::to_string(l.line);
}

void Assembler::error(const Line& l, int col, const std::string& msg) {
    std::string m = msg;
    if (l.ctx >= 0) m += " (" + contexts_[static_cast<size_t>(l.ctx)] + ")";
    diags_.push_back({files_[static_cast<size_t>(l.file)], l.line, col, m});
    if (static_cast<int>(diags_.size()) >= opt_.max_errors) {
        diags_.push_back({files_[static_cast<size_t>(l.file)], l.line, col,
                          "too many errors (" + std::to_string(opt_.max_errors) + "), stopping"});
        throw Stop{};
    }
}

int Assembler::add_file(const std::string& name) {
    files_.push_back(name);
    return static_cast<int>(files_.size()) - 1;
}

std::string Assembler::bad_name(const std::string& name) {
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

std::optional<int64_t> Assembler::lookup(const std::string& name) const {
    auto it = syms_.find(name);
    if (it == syms_.end()) return std::nullopt;
    return it->second.value;
}

std::vector<Token> Assembler::lex_line(const Line& l, bool* ok) {
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
std::optional<int64_t> Assembler::eval_now(const Line& l, const std::vector<Token>& t, Range r,
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

void Assembler::define_label(const Line& L, const Token& t) {
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

void Assembler::statement(const Line& L, int depth) {
    bool ok;
    std::vector<Token> t = lex_line(L, &ok);
    if (!ok) return;
    size_t k = 0;
    while (k + 1 < t.size() && t[k].kind == Tok::Ident && t[k + 1].is(":") && t[k].text[0] != '.') {
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

// The NAME of "<d> NAME ...": false (with an error) when it is missing.
bool Assembler::need_name(const Line& L, const std::vector<Token>& t, size_t k,
                          const std::string& d) {
    const size_t n = t.size() - k - 1;  // operand tokens
    if (n < 1 || t[k + 1].kind != Tok::Ident) {
        error(L, n < 1 ? t[k].col : t[k + 1].col, d + " expects a name");
        return false;
    }
    return true;
}

// "<d> NAME[,] VALUE...": checks NAME; the index of VALUE, or 0 after an error.
size_t Assembler::defined_name(const Line& L, const std::vector<Token>& t, size_t k,
                               const std::string& d) {
    if (!need_name(L, t, k, d)) return 0;
    const Token& nt = t[k + 1];
    size_t b = k + 2;
    if (b < t.size() && t[b].is(",")) ++b;
    const std::string why = bad_name(nt.text);
    if (!why.empty()) {
        error(L, nt.col, d + ": " + why);
        return 0;
    }
    return b;
}

// .equ NAME, VALUE (a constant; may be repeated with the same value) or
// .set NAME, VALUE (a variable: may be set again).
void Assembler::define_symbol(const Line& L, const std::vector<Token>& t, size_t k,
                              const std::string& d) {
    const size_t b = defined_name(L, t, k, d);
    if (b == 0) return;
    const Token& nt = t[k + 1];
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
            error(L, nt.col, "symbol '" + nt.text + "' already defined (" + it->second.where + ")");
            return;
        }
        if (same) return;
    }
    syms_[nt.text] = {*v, d == ".set" ? Sym::Set : Sym::Equ, d + " at " + loc(L)};
}

// .reg NAME, rN|cN: a register alias.
void Assembler::define_reg(const Line& L, const std::vector<Token>& t, size_t k) {
    const size_t b = defined_name(L, t, k, ".reg");
    if (b == 0) return;
    const Token& nt = t[k + 1];
    if (b + 1 != t.size()) {
        error(L, b < t.size() ? t[b].col : nt.col, ".reg expects: .reg NAME, rN|cN");
        return;
    }
    bool cp;
    uint8_t r;
    if (!reg_token(L, t[b], &cp, &r)) return;
    regs_[nt.text] = {cp, r};
}

// .defphase NAME (names a phase) or .phase NAME (also emits the phase marker).
void Assembler::phase(const Line& L, const std::vector<Token>& t, size_t k, const std::string& d) {
    if (!need_name(L, t, k, d)) return;
    if (t.size() - k - 1 != 1) {
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
}

void Assembler::directive(const Line& L, const std::vector<Token>& t, size_t k, int depth) {
    const Token& head = t[k];
    const std::string d = lower(head.text);
    const size_t n = t.size() - k - 1;  // operand tokens
    if (d == ".equ" || d == ".set") {
        define_symbol(L, t, k, d);
        return;
    }
    if (d == ".reg") {
        define_reg(L, t, k);
        return;
    }
    if (d == ".phase" || d == ".defphase") {
        phase(L, t, k, d);
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

}  // namespace asm_detail

using namespace asm_detail;

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