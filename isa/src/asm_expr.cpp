// Constant expressions of the assembler: precedence climbing over the tokens
// of an operand or directive (C operators and precedence, 64-bit two's
// complement), symbols through a lookup, unknown ones recorded (forward
// references), nesting bounded.
#include "asm_internal.hpp"

namespace imap::isa::asm_detail {

int64_t Expr::parse_all() {
    if (pos_ >= end_) throw ExprError{col_at(pos_), "expected an expression"};
    const int64_t v = binary(0);
    if (pos_ < end_)
        throw ExprError{t_[pos_].col, "unexpected '" + t_[pos_].text + "' in expression"};
    return v;
}

int Expr::col_at(size_t i) const {
    if (i < end_) return t_[i].col;
    if (end_ > 0 && end_ <= t_.size()) {
        const Token& last = t_[end_ - 1];
        return last.col + static_cast<int>(last.text.size());
    }
    return 1;
}

int Expr::prec(const Token& tk) {
    if (tk.kind != Tok::Punct) return -1;
    static const std::pair<const char*, int> ops[] = {
        {"||", 1}, {"&&", 2}, {"|", 3},  {"^", 4},  {"&", 5},  {"==", 6},
        {"!=", 6}, {"<", 7},  {"<=", 7}, {">", 7},  {">=", 7}, {"<<", 8},
        {">>", 8}, {"+", 9},  {"-", 9},  {"*", 10}, {"/", 10}, {"%", 10}};
    for (const auto& [s, p] : ops)
        if (tk.text == s) return p;
    return -1;
}

int64_t Expr::binary(int min_prec) {
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

int64_t Expr::apply(const Token& op, int64_t a, int64_t b) {
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

int64_t Expr::unary() {
    if (pos_ >= end_) throw ExprError{col_at(pos_), "expected a value"};
    if (++depth_ > kMaxDepth)
        throw ExprError{t_[pos_].col, "expression nested too deeply (more than " +
                                          std::to_string(kMaxDepth) + " levels)"};
    const int64_t v = operand();
    --depth_;
    return v;
}

int64_t Expr::operand() {
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
            throw ExprError{tk.col, "register '" + tk.text + "' cannot be used in an expression"};
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

}  // namespace imap::isa::asm_detail
