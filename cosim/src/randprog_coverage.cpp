// Functional coverage of the random suite (docs/rtl.md, "Random suite"):
// the bins (opcode x operand class x mask state, ring distances, transfer
// lengths, mask depths and states, branch directions, call depths), sampled
// from each retired instruction's word and the reference model's state after
// it, merged over programs, and printed as a table or JSON.
#include <algorithm>
#include <cstdio>
#include <sstream>

#include "imap/rtl/random.hpp"

namespace imap::rtl {

namespace {
const char* const kFormats[] = {"none", "Rrr",  "Rri8", "Rr",  "Ri8", "Rsh",   "Cmp",
                                "Cmpi", "R",    "Rc",   "Rck", "Rk",  "Ld",    "Ldx",
                                "Xfer", "Ring", "Stat", "Ci",  "Cc",  "Ccc",   "Cci",
                                "Csh",  "Cmem", "J",    "Bcc", "B1",  "Video", "Phase"};
struct OpInfo {
    uint8_t op;
    const char* name;
    int fmt;  // index into kFormats
    bool pe;  // masked by M
};
const std::vector<OpInfo>& ops() {
    static const std::vector<OpInfo> v = {
        {0x00, "nop", 0, false},    {0x01, "halt", 0, false},   {0x02, "phase", 27, false},
        {0x08, "cli", 17, false},   {0x09, "cmov", 18, false},  {0x0A, "cadd", 19, false},
        {0x0B, "caddi", 20, false}, {0x0C, "csub", 19, false},  {0x0D, "csubi", 20, false},
        {0x0E, "cand", 19, false},  {0x0F, "candi", 20, false}, {0x10, "cor", 19, false},
        {0x11, "cori", 20, false},  {0x12, "cxor", 19, false},  {0x13, "cxori", 20, false},
        {0x14, "cshli", 21, false}, {0x15, "cshri", 21, false}, {0x16, "csrai", 21, false},
        {0x17, "cld", 22, false},   {0x18, "cst", 22, false},   {0x20, "jmp", 23, false},
        {0x21, "beq", 24, false},   {0x22, "bne", 24, false},   {0x23, "blt", 24, false},
        {0x24, "bge", 24, false},   {0x25, "bz", 25, false},    {0x26, "bnz", 25, false},
        {0x27, "loop", 25, false},  {0x28, "call", 23, false},  {0x29, "ret", 0, false},
        {0x40, "add", 1, true},     {0x41, "adc", 1, true},     {0x42, "sub", 1, true},
        {0x43, "sbc", 1, true},     {0x44, "and", 1, true},     {0x45, "or", 1, true},
        {0x46, "xor", 1, true},     {0x47, "min", 1, true},     {0x48, "max", 1, true},
        {0x50, "addi", 2, true},    {0x51, "adci", 2, true},    {0x52, "subi", 2, true},
        {0x53, "sbci", 2, true},    {0x54, "andi", 2, true},    {0x55, "ori", 2, true},
        {0x56, "xori", 2, true},    {0x57, "mini", 2, true},    {0x58, "maxi", 2, true},
        {0x60, "mov", 3, true},     {0x61, "li", 4, true},      {0x62, "lc", 9, true},
        {0x63, "lcb", 10, true},    {0x64, "pidx", 11, true},   {0x65, "setc", 8, true},
        {0x66, "sett", 8, true},    {0x67, "csel", 1, true},    {0x68, "tsel", 1, true},
        {0x70, "shli", 5, true},    {0x71, "shri", 5, true},    {0x72, "rolc", 3, true},
        {0x73, "rorc", 3, true},    {0x74, "shlv", 1, true},    {0x75, "shrv", 1, true},
        {0x80, "ceq", 6, true},     {0x81, "cne", 6, true},     {0x82, "cltu", 6, true},
        {0x83, "cleu", 6, true},    {0x84, "cgtu", 6, true},    {0x85, "cgeu", 6, true},
        {0x88, "ceqi", 7, true},    {0x89, "cnei", 7, true},    {0x8A, "cltui", 7, true},
        {0x8B, "cleui", 7, true},   {0x8C, "cgtui", 7, true},   {0x8D, "cgeui", 7, true},
        {0x8E, "tc", 0, true},      {0x8F, "tnot", 0, true},    {0x90, "ld", 12, true},
        {0x91, "st", 12, true},     {0x92, "ldx", 13, true},    {0x93, "stx", 13, true},
        {0x94, "xld", 14, true},    {0x95, "xst", 14, true},    {0xA0, "rxl", 15, true},
        {0xA1, "rxr", 15, true},    {0xB0, "mif", 0, false},    {0xB1, "melse", 0, false},
        {0xB2, "mend", 0, false},   {0xB3, "mall", 0, false},   {0xB4, "rany", 16, false},
        {0xB5, "rall", 16, false},  {0xC0, "vin", 26, false},   {0xC1, "vout", 26, false}};
    return v;
}
const OpInfo* op_info(uint8_t op) {
    for (const OpInfo& o : ops())
        if (o.op == op) return &o;
    return nullptr;
}
// Operand classes of a format (the second coordinate of the opcode bins).
std::vector<std::string> classes(int fmt) {
    switch (fmt) {
        case 1:
            return {"distinct", "rd=ra", "ra=rb"};
        case 2:
            return {"imm=0", "imm=255", "imm"};
        case 5:
            return {"n=0", "n=7", "n"};
        case 12:
            return {"absolute", "base"};
        case 13:
            return {"lo", "lo+hi", "+cN"};
        case 14:
            return {"len=0", "len>0"};
        case 15:
            return {"k<P", "k=P", "k>P"};
        case 24:
        case 25:
            return {"taken", "not taken"};
        case 26:
            return {"port0", "port1"};
        default:
            return {"-"};
    }
}
std::string klass(int fmt, uint64_t w, const isa::Machine& m, uint32_t pc, int P) {
    const uint32_t rd = (w >> 8) & 0xff, ra = (w >> 16) & 0xff, rb = (w >> 24) & 0xff;
    const uint32_t imm = static_cast<uint32_t>(w >> 32);
    switch (fmt) {
        case 1:
            return rd == ra ? "rd=ra" : ra == rb ? "ra=rb" : "distinct";
        case 2:
            return imm == 0 ? "imm=0" : imm == 255 ? "imm=255" : "imm";
        case 5:
            return imm == 0 ? "n=0" : imm == 7 ? "n=7" : "n";
        case 12:
            return rb == 128 ? "absolute" : "base";
        case 13:
            return ((imm >> 28) & 1) ? "+cN" : ((imm >> 29) & 1) ? "lo" : "lo+hi";
        case 14:
            return m.cp(static_cast<int>(rd & 15)) == 0 ? "len=0" : "len>0";
        case 15:
            return static_cast<int>(imm) < P ? "k<P" : static_cast<int>(imm) == P ? "k=P" : "k>P";
        case 24:
        case 25:
            return m.pc() != pc + 1 ? "taken" : "not taken";
        case 26:
            return rd == 0 ? "port0" : "port1";
        default:
            return "-";
    }
}
}  // namespace

Coverage::Coverage(int pes) : P_(pes) {
    for (const OpInfo& o : ops())
        for (const std::string& c : classes(o.fmt))
            for (const char* mk : o.pe ? std::vector<const char*>{"all active", "some masked"}
                                       : std::vector<const char*>{"-"})
                bins_[std::string("op/") + o.name + "/" + c + "/" + mk] = 0;
    for (const char* d : {"rxl", "rxr"})
        for (const char* k : {"1", "2..P-2", "P-1", "P", "P+1..2P", ">2P"})
            bins_[std::string("ring/") + d + "/" + k] = 0;
    for (const char* d : {"xld", "xst"})
        for (const char* k : {"0", "1", "2..7", "8..P", ">P"})
            bins_[std::string("xfer/") + d + "/" + k] = 0;
    for (int d = 0; d <= 3; ++d) bins_["mask/depth " + std::to_string(d)] = 0;
    for (const char* s : {"none active", "all active", "some masked"})
        bins_[std::string("mask/state/") + s] = 0;
    for (const char* b : {"taken to next", "backward", "forward"})
        bins_[std::string("branch/") + b] = 0;
    for (int d = 1; d <= 2; ++d) bins_["call/depth " + std::to_string(d)] = 0;
}

void Coverage::hit(const std::string& bin) {
    auto it = bins_.find(bin);
    if (it != bins_.end()) ++it->second;
}

void Coverage::sample(uint64_t w, uint32_t pc, int active_before, int mask_depth_before,
                      const isa::Machine& m) {
    const uint8_t op = static_cast<uint8_t>(w);
    const OpInfo* o = op_info(op);
    if (!o) return;
    const std::string mk = !o->pe ? "-" : active_before == P_ ? "all active" : "some masked";
    hit(std::string("op/") + o->name + "/" + klass(o->fmt, w, m, pc, P_) + "/" + mk);
    const uint32_t imm = static_cast<uint32_t>(w >> 32);
    if (op == 0xA0 || op == 0xA1) {
        const int k = static_cast<int>(imm), P = P_;
        const char* b = k == 1       ? "1"
                        : k <= P - 2 ? "2..P-2"
                        : k == P - 1 ? "P-1"
                        : k == P     ? "P"
                        : k <= 2 * P ? "P+1..2P"
                                     : ">2P";
        hit(std::string("ring/") + (op == 0xA0 ? "rxl/" : "rxr/") + b);
    }
    if (op == 0x94 || op == 0x95) {
        const uint32_t len = m.cp(static_cast<int>((w >> 8) & 15));
        const char* b = len == 0                      ? "0"
                        : len == 1                    ? "1"
                        : len <= 7                    ? "2..7"
                        : static_cast<int>(len) <= P_ ? "8..P"
                                                      : ">P";
        hit(std::string("xfer/") + (op == 0x94 ? "xld/" : "xst/") + b);
    }
    if (op >= 0xB0 && op <= 0xB3)
        hit("mask/depth " + std::to_string(std::min(mask_depth_before, 3)));
    hit(std::string("mask/state/") + (active_before == 0    ? "none active"
                                      : active_before == P_ ? "all active"
                                                            : "some masked"));
    if (op >= 0x20 && op <= 0x27 && m.pc() != pc + 1)
        hit(m.pc() < pc ? "branch/backward" : "branch/forward");
    if (op >= 0x21 && op <= 0x27 && imm == pc + 1) hit("branch/taken to next");
    if (op == 0x28) hit("call/depth " + std::to_string(std::min(m.call_stack_size(), 2)));
}

void Coverage::merge(const Coverage& o) {
    for (const auto& [b, n] : o.bins_) bins_[b] += n;
}

size_t Coverage::covered() const {
    size_t n = 0;
    for (const auto& [b, k] : bins_) n += k > 0;
    return n;
}

std::vector<std::string> Coverage::uncovered() const {
    std::vector<std::string> v;
    for (const auto& [b, k] : bins_)
        if (k == 0) v.push_back(b);
    return v;
}

std::string Coverage::table() const {
    std::map<std::string, std::pair<size_t, size_t>> g;  // group -> (covered, total)
    for (const auto& [b, k] : bins_) {
        std::string grp = b.substr(0, b.find('/'));
        if (grp == "op") {
            const size_t s2 = b.find('/', 3);
            const OpInfo* oi = nullptr;
            const std::string name = b.substr(3, s2 - 3);
            for (const OpInfo& o : ops())
                if (name == o.name) oi = &o;
            grp = std::string("op ") + (oi ? kFormats[oi->fmt] : "?");
        }
        auto& e = g[grp];
        e.first += k > 0;
        ++e.second;
    }
    std::ostringstream o;
    o << "functional coverage: " << covered() << " of " << bins() << " bins\n";
    char line[128];
    for (const auto& [grp, e] : g) {
        std::snprintf(line, sizeof line, "  %-16s %5zu / %-5zu %5.1f%%\n", grp.c_str(), e.first,
                      e.second,
                      100.0 * static_cast<double>(e.first) / static_cast<double>(e.second));
        o << line;
    }
    const std::vector<std::string> u = uncovered();
    o << "  uncovered (" << u.size() << "):";
    for (const std::string& b : u) o << " " << b;
    o << "\n";
    return o.str();
}

nlohmann::json Coverage::json() const {
    nlohmann::json j;
    j["bins"] = bins();
    j["covered"] = covered();
    nlohmann::json h = nlohmann::json::object();
    for (const auto& [b, k] : bins_) h[b] = k;
    j["hits"] = h;
    j["uncovered"] = uncovered();
    return j;
}

}  // namespace imap::rtl
