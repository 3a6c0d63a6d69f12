// Program helpers and the IMAPFW01 binary format.
#include <cstdio>
#include <cstring>
#include <fstream>
#include <iterator>

#include "imap/isa/program.hpp"

namespace imap::isa {

namespace {
// A name read from a file, safe for a one-line message: control characters
// become '?'.
std::string printable(std::string s) {
    for (char& c : s)
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) c = '?';
    return s;
}
}  // namespace

std::string Program::location(uint32_t pc) const {
    if (pc >= source_map.size()) return "";
    const SourceLoc& l = source_map[pc];
    if (l.file >= files.size() || l.line == 0) return "";
    return printable(files[l.file]) + ":" + std::to_string(l.line);
}

std::string Program::phase_name(uint32_t id) const {
    return id < phases.size() ? phases[id] : "#" + std::to_string(id);
}

bool Program::same_map(const Program& o) const {
    for (size_t i = 0; i < source_map.size(); ++i)
        if (source_map[i].file != o.source_map[i].file ||
            source_map[i].line != o.source_map[i].line)
            return false;
    return true;
}

namespace {

constexpr uint32_t kMaxCode = 1u << 24;
constexpr uint32_t kMaxString = 4096;
constexpr uint32_t kMaxCount = 1u << 20;
constexpr size_t kHeader = 32;

uint32_t fnv1a(const uint8_t* p, size_t n) {
    uint32_t h = 2166136261u;
    for (size_t i = 0; i < n; ++i) h = (h ^ p[i]) * 16777619u;
    return h;
}

struct Writer {
    std::vector<uint8_t> out;
    void u32(uint32_t v) {
        for (int i = 0; i < 4; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
    }
    void u64(uint64_t v) {
        for (int i = 0; i < 8; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
    }
    void str(const std::string& s) {
        u32(static_cast<uint32_t>(s.size()));
        out.insert(out.end(), s.begin(), s.end());
    }
};

struct Reader {
    const std::vector<uint8_t>& in;
    size_t end;  // excluding the checksum
    const std::string& name;
    size_t pos = 0;

    [[noreturn]] void fail(const std::string& what) const {
        throw FormatError("bad program file '" + name + "': " + what);
    }
    void need(size_t n, const char* what) const {
        if (end - pos < n)
            fail("truncated: " + std::string(what) + " needs " + std::to_string(n) +
                 " bytes at offset " + std::to_string(pos) + ", only " + std::to_string(end - pos) +
                 " left");
    }
    uint32_t u32(const char* what) {
        need(4, what);
        uint32_t v = 0;
        for (int i = 0; i < 4; ++i) v |= uint32_t{in[pos + i]} << (8 * i);
        pos += 4;
        return v;
    }
    uint64_t u64(const char* what) {
        need(8, what);
        uint64_t v = 0;
        for (int i = 0; i < 8; ++i) v |= uint64_t{in[pos + i]} << (8 * i);
        pos += 8;
        return v;
    }
    std::string str(const char* what) {
        const uint32_t n = u32(what);
        if (n > kMaxString)
            fail(std::string(what) + " length " + std::to_string(n) + " exceeds " +
                 std::to_string(kMaxString));
        need(n, what);
        std::string s(reinterpret_cast<const char*>(in.data() + pos), n);
        pos += n;
        return s;
    }
    uint32_t count(const char* what, uint32_t max, size_t min_each) {
        const uint32_t n = u32(what);
        if (n > max)
            fail(std::string(what) + " " + std::to_string(n) + " exceeds " + std::to_string(max));
        if (static_cast<uint64_t>(n) * min_each > end - pos)
            fail("truncated: " + std::to_string(n) + " " + what + " need at least " +
                 std::to_string(static_cast<uint64_t>(n) * min_each) + " bytes, only " +
                 std::to_string(end - pos) + " left");
        return n;
    }
};

}  // namespace

std::vector<uint8_t> serialize(const Program& p, bool with_source_map) {
    const bool map =
        with_source_map && !p.source_map.empty() && p.source_map.size() == p.code.size();
    Writer w;
    w.out.insert(w.out.end(), kProgramMagic, kProgramMagic + 8);
    w.u32(kProgramVersion);
    w.u32(map ? 1u : 0u);
    w.u32(static_cast<uint32_t>(p.code.size()));
    w.u32(static_cast<uint32_t>(p.phases.size()));
    w.u32(static_cast<uint32_t>(p.symbols.size()));
    w.u32(map ? static_cast<uint32_t>(p.files.size()) : 0u);
    for (uint64_t c : p.code) w.u64(c);
    for (const std::string& s : p.phases) w.str(s);
    for (const auto& [name, pc] : p.symbols) {
        w.str(name);
        w.u32(pc);
    }
    if (map) {
        for (const std::string& f : p.files) w.str(f);
        for (const SourceLoc& l : p.source_map) {
            w.u32(l.file);
            w.u32(l.line);
        }
    }
    w.u32(fnv1a(w.out.data(), w.out.size()));
    return std::move(w.out);
}

Program deserialize(const std::vector<uint8_t>& in, const std::string& name) {
    if (in.size() < 8 || std::memcmp(in.data(), kProgramMagic, 8) != 0)
        throw FormatError("bad program file '" + name +
                          "': not an IMAP-VISION program (magic \"IMAPFW01\" missing)");
    if (in.size() < kHeader + 4)
        throw FormatError("bad program file '" + name + "': truncated header (" +
                          std::to_string(in.size()) + " bytes, need at least " +
                          std::to_string(kHeader + 4) + ")");
    Reader r{in, in.size() - 4, name};
    r.pos = 8;
    const uint32_t version = r.u32("version");
    if (version != kProgramVersion)
        r.fail("unsupported version " + std::to_string(version) + " (this tool reads version " +
               std::to_string(kProgramVersion) + ")");
    const uint32_t flags = r.u32("flags");
    if (flags > 1) r.fail("unknown flags " + std::to_string(flags));
    Program p;
    const uint32_t n_code = r.u32("code count");
    const uint32_t n_phases = r.u32("phase count");
    const uint32_t n_symbols = r.u32("symbol count");
    const uint32_t n_files = r.u32("file count");
    if (n_code > kMaxCode)
        r.fail("code count " + std::to_string(n_code) + " exceeds " + std::to_string(kMaxCode));
    if (n_phases > kMaxCount || n_symbols > kMaxCount || n_files > kMaxCount)
        r.fail("implausible table sizes (phases " + std::to_string(n_phases) + ", symbols " +
               std::to_string(n_symbols) + ", files " + std::to_string(n_files) + ")");
    r.need(static_cast<size_t>(n_code) * 8, "code");
    p.code.reserve(n_code);
    for (uint32_t i = 0; i < n_code; ++i) p.code.push_back(r.u64("code"));
    r.need(static_cast<size_t>(n_phases) * 4, "phase names");
    for (uint32_t i = 0; i < n_phases; ++i) p.phases.push_back(r.str("phase name"));
    r.need(static_cast<size_t>(n_symbols) * 8, "symbols");
    for (uint32_t i = 0; i < n_symbols; ++i) {
        std::string s = r.str("symbol name");
        const uint32_t pc = r.u32("symbol value");
        if (pc > n_code)
            r.fail("symbol '" + printable(s) + "' at PC " + std::to_string(pc) +
                   " beyond the code");
        p.symbols[s] = pc;
    }
    if (flags & 1) {
        r.need(static_cast<size_t>(n_files) * 4, "file names");
        for (uint32_t i = 0; i < n_files; ++i) p.files.push_back(r.str("file name"));
        r.need(static_cast<size_t>(n_code) * 8, "source map");
        p.source_map.resize(n_code);
        for (uint32_t i = 0; i < n_code; ++i) {
            p.source_map[i].file = r.u32("source map");
            p.source_map[i].line = r.u32("source map");
            if (p.source_map[i].file >= n_files)
                r.fail("source map entry " + std::to_string(i) + " names file " +
                       std::to_string(p.source_map[i].file) + " of " + std::to_string(n_files));
        }
    } else if (n_files != 0) {
        r.fail("file table without a source map");
    }
    if (r.pos != r.end)
        r.fail(std::to_string(r.end - r.pos) + " unexpected bytes after the last section");
    uint32_t stored = 0;
    for (int i = 0; i < 4; ++i) stored |= uint32_t{in[r.end + i]} << (8 * i);
    if (stored != fnv1a(in.data(), r.end)) r.fail("checksum mismatch (file corrupted)");
    return p;
}

void save_program(const Program& p, const std::string& path, bool with_source_map) {
    const std::vector<uint8_t> bytes = serialize(p, with_source_map);
    const std::string tmp = path + ".tmp";
    {
        std::ofstream f(tmp, std::ios::binary | std::ios::trunc);
        if (!f) throw FormatError("cannot write '" + tmp + "': " + std::strerror(errno));
        f.write(reinterpret_cast<const char*>(bytes.data()),
                static_cast<std::streamsize>(bytes.size()));
        f.flush();
        if (!f) {
            std::remove(tmp.c_str());
            throw FormatError("cannot write '" + tmp + "': " + std::strerror(errno));
        }
    }
    if (std::rename(tmp.c_str(), path.c_str()) != 0) {
        const std::string err = std::strerror(errno);
        std::remove(tmp.c_str());
        throw FormatError("cannot write '" + path + "': " + err);
    }
}

Program load_program(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw FormatError("cannot open program file '" + path + "': " + std::strerror(errno));
    std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(f)),
                               std::istreambuf_iterator<char>());
    if (f.bad()) throw FormatError("cannot read program file '" + path + "'");
    return deserialize(bytes, path);
}

}  // namespace imap::isa
