// Private to the assembler (isa/src/asm_*.cpp, assembler.cpp): the token and
// line types, the lexer and expression evaluator, and the Assembler class,
// whose members are defined by part: statements and directives in
// assembler.cpp, conditionals/.rept/macros/.include in asm_preprocess.cpp,
// operands and encoding in asm_encode.cpp.
#pragma once

#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "imap/isa/assembler.hpp"
#include "imap/isa/encoding.hpp"
#include "imap/isa/opcodes.hpp"

namespace imap::isa::asm_detail {

// ---- lexer (asm_lexer.cpp) ----

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

bool ident_start(char c);
bool ident_char(char c);
// One step of a scan of s at s[*i] over string literals: true when s[*i]
// opens, is inside or closes a "string" (not code); skips a \-escape.
bool string_char(const std::string& s, size_t* i, bool* in_str);
// Index where the comment of a line starts (or npos).
size_t comment_start(const std::string& s);
// One line (without its newline) into tokens; throws LexError.
std::vector<Token> lex(const std::string& line);
std::string lower(std::string s);
// r<digits> / c<digits>: register syntax (never a symbol name).
bool register_like(const std::string& name, char* kind, long* num);

// ---- constant expressions (asm_expr.cpp) ----

struct ExprError {
    int col;
    std::string msg;
};

using Lookup = std::function<std::optional<int64_t>(const std::string&)>;

// Evaluates the tokens [b, e) of `t`; symbols through `look`. An unknown
// symbol evaluates as 0 and is recorded in undef / undef_name / undef_col.
class Expr {
  public:
    Expr(const std::vector<Token>& t, size_t b, size_t e, const Lookup& look)
        : t_(t), pos_(b), end_(e), look_(look) {}

    // Parses the whole range; throws ExprError.
    int64_t parse_all();
    bool undef = false;
    std::string undef_name;
    int undef_col = 0;

  private:
    int col_at(size_t i) const;
    static int prec(const Token& tk);
    int64_t binary(int min_prec);
    int64_t apply(const Token& op, int64_t a, int64_t b);
    int64_t unary();
    int64_t operand();

    // Nesting of parentheses and unary operators is bounded: the parser is
    // recursive, and a deep enough nest would overflow the stack.
    static constexpr int kMaxDepth = 256;

    const std::vector<Token>& t_;
    size_t pos_, end_;
    const Lookup& look_;
    int depth_ = 0;
};

// ---- the assembler ----

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

// Where an operand value goes in the word, with its range (asm_encode.cpp).
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
    explicit Assembler(const AsmOptions& o);
    Program run(const std::string& text, const std::string& name);
    static std::optional<std::string> read_file(const std::string& path, std::string* err);

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
    struct Cond {
        bool parent_active, active, taken, seen_else;
        Line where;
    };

    // ---- diagnostics and symbols (assembler.cpp) ----
    std::string loc(const Line& l) const;
    void error(const Line& l, int col, const std::string& msg);
    int add_file(const std::string& name);
    static std::string bad_name(const std::string& name);
    std::optional<int64_t> lookup(const std::string& name) const;
    std::vector<Token> lex_line(const Line& l, bool* ok);
    std::optional<int64_t> eval_now(const Line& l, const std::vector<Token>& t, Range r,
                                    const char* what);

    // ---- source processing (asm_preprocess.cpp) ----
    void process_text(const std::string& text, int file, int depth);
    size_t find_close(const std::vector<Line>& lines, size_t i, size_t end, const char* open,
                      const char* close);
    void process(const std::vector<Line>& lines, size_t begin, size_t end, int depth);
    void conditional(const Line& L, const std::string& w, std::vector<Cond>& conds);
    bool block(const std::vector<Line>& lines, size_t* i, size_t end, const std::string& w,
               int depth);
    void budget(const Line& L, uint64_t units = 1);
    void define_macro(const std::vector<Line>& lines, size_t i, size_t j);
    void expand_macro(const std::string& name, const Line& L, int name_col, int depth);
    void include(const Line& L, const Token& path_tok, int depth);

    // ---- statements and directives (assembler.cpp) ----
    void define_label(const Line& L, const Token& t);
    void statement(const Line& L, int depth);
    void directive(const Line& L, const std::vector<Token>& t, size_t k, int depth);
    bool need_name(const Line& L, const std::vector<Token>& t, size_t k, const std::string& d);
    size_t defined_name(const Line& L, const std::vector<Token>& t, size_t k, const std::string& d);
    void define_symbol(const Line& L, const std::vector<Token>& t, size_t k, const std::string& d);
    void define_reg(const Line& L, const std::vector<Token>& t, size_t k);
    void phase(const Line& L, const std::vector<Token>& t, size_t k, const std::string& d);

    // ---- operands and encoding (asm_encode.cpp) ----
    size_t emit(const Line& L, const Word& w);
    std::string apply(size_t idx, Slot s, int64_t v);
    void value(const Line& L, const std::vector<Token>& t, Range r, Slot s, size_t idx,
               bool offset = false);
    void resolve_fixups();
    bool reg_token(const Line& L, const Token& tk, bool* cp, uint8_t* r);
    bool reg(const Line& L, const std::vector<Token>& t, Range r, bool want_cp, uint8_t* out);
    void imm(const Line& L, const std::vector<Token>& t, Range r, Slot s, size_t idx);
    void target(const Line& L, const std::vector<Token>& t, Range r, size_t idx);
    bool brackets(const Line& L, const std::vector<Token>& t, Range r, Range* in);
    void mem(const Line& L, const std::vector<Token>& t, Range r, size_t idx);
    void memx(const Line& L, const std::vector<Token>& t, Range r, size_t idx);
    void ext(const Line& L, const std::vector<Token>& t, Range r, size_t idx);
    void set_field(size_t idx, int field, uint8_t v);
    void instruction(const Line& L, const OpInfo& info, const std::vector<Token>& t, size_t k);

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

}  // namespace imap::isa::asm_detail
