// The assembler's lexer: one source line -> tokens (identifiers, numbers in
// decimal / 0x / 0b, quoted strings, punctuation), with comments stripped
// (';' anywhere, '#' where it cannot be an immediate), and the register-name
// rule (r<digits> / c<digits>) that symbols must not match.
#include <algorithm>
#include <cctype>
#include <cstring>

#include "asm_internal.hpp"

namespace imap::isa::asm_detail {

bool ident_start(char c) {
    return std::isalpha(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '$';
}
bool ident_char(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '.' || c == '$';
}

// Index where the comment of a line starts (or npos). ';' always starts a
// comment (outside strings); '#' does when it is the first non-blank
// character or is followed by a blank or the end of the line.
bool string_char(const std::string& s, size_t* i, bool* in_str) {
    const char c = s[*i];
    if (*in_str) {
        if (c == '\\')
            ++*i;
        else if (c == '"')
            *in_str = false;
        return true;
    }
    if (c != '"') return false;
    *in_str = true;
    return true;
}

size_t comment_start(const std::string& s) {
    bool in_str = false;
    bool seen = false;
    for (size_t i = 0; i < s.size(); ++i) {
        const char c = s[i];
        if (string_char(s, &i, &in_str)) {
            seen = true;
            continue;
        }
        if (c == ';')
            return i;
        else if (c == '#') {
            const char n = i + 1 < s.size() ? s[i + 1] : '\0';
            if (!seen || n == '\0' || n == ' ' || n == '\t' || n == '\r') return i;
        }
        if (c != ' ' && c != '\t') seen = true;
    }
    return std::string::npos;
}

namespace {

// A number starting at line[i] (decimal, 0x hex or 0b binary, at most
// INT64_MAX) into `out`; returns the index after it. Throws LexError.
size_t lex_number(const std::string& line, size_t i, size_t end, std::vector<Token>* out) {
    const char c = line[i];
    const int col = static_cast<int>(i) + 1;
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
        if (dv >= base) throw LexError{col, "invalid number '" + line.substr(i, j + 1 - i) + "'"};
        if (v > (UINT64_MAX - static_cast<uint64_t>(dv)) / static_cast<uint64_t>(base))
            overflow = true;
        v = v * static_cast<uint64_t>(base) + static_cast<uint64_t>(dv);
        ++j;
    }
    if (j == digits) throw LexError{col, "invalid number '" + line.substr(i, j - i) + "'"};
    if (overflow || v > static_cast<uint64_t>(INT64_MAX))
        throw LexError{col, "number '" + line.substr(i, j - i) + "' is too large"};
    out->push_back({Tok::Number, line.substr(i, j - i), static_cast<int64_t>(v), col});
    return j;
}

}  // namespace

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
            i = lex_number(line, i, end, &out);
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

}  // namespace imap::isa::asm_detail
