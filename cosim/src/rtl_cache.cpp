// The RTL cache (imap/rtl/cache.hpp): keys, the folder's safety checks,
// building an entry from the embedded sources, publishing it, and loading
// it into this process's configurations (docs/rtl.md, "Any configuration
// on demand").
#include "imap/rtl/cache.hpp"

#include <dlfcn.h>
#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <deque>
#include <filesystem>
#include <fstream>
#include <map>
#include <ostream>
#include <sstream>
#include <thread>

#include "entry_abi.hpp"
#include "imap/isa/config.hpp"
#include "rtl_cache_impl.hpp"
#include "sha256.hpp"

namespace imap::rtl {

namespace fs = std::filesystem;
using detail::ConfigInfo;

namespace {

// Changes with the entry's layout, its record or the way it is built.
constexpr const char* kCacheFormat = "imap-rtl-cache 1";
std::string g_dir;  // set_cache_dir

std::string env(const char* name) {
    const char* v = std::getenv(name);
    return v ? v : "";
}

const char* variant_name(int trace) {
    return trace == 1 ? "vcd" : "fst";
}

// ---- tools ---------------------------------------------------------------

std::string find_program(const std::string& name) {
    if (name.find('/') != std::string::npos) return ::access(name.c_str(), X_OK) == 0 ? name : "";
    std::stringstream path(env("PATH"));
    std::string d;
    while (std::getline(path, d, ':')) {
        if (d.empty()) continue;
        const std::string p = d + "/" + name;
        if (::access(p.c_str(), X_OK) == 0) return p;
    }
    return "";
}

// Runs argv with stdout and stderr to `out_path` (appended); its exit status
// (-1: could not start).
int run_logged(const std::vector<std::string>& argv, const std::string& out_path) {
    std::vector<char*> a;
    for (const std::string& s : argv) a.push_back(const_cast<char*>(s.c_str()));
    a.push_back(nullptr);
    const pid_t pid = ::fork();
    if (pid < 0) return -1;
    if (pid == 0) {
        const int fd = ::open(out_path.c_str(), O_WRONLY | O_CREAT | O_APPEND | O_CLOEXEC, 0600);
        if (fd >= 0) {
            ::dup2(fd, 1);
            ::dup2(fd, 2);
        }
        ::execv(a[0], a.data());
        ::_exit(127);
    }
    int st = 0;
    while (::waitpid(pid, &st, 0) < 0)
        if (errno != EINTR) return -1;
    return WIFEXITED(st) ? WEXITSTATUS(st) : 128 + (WIFSIGNALED(st) ? WTERMSIG(st) : 0);
}

// The first line a command prints ("" if it cannot run).
std::string first_line(const std::vector<std::string>& argv) {
    char tmpl[] = "/tmp/imapsim-tool-XXXXXX";
    const int fd = ::mkstemp(tmpl);
    if (fd < 0) return "";
    ::close(fd);
    std::string line;
    if (run_logged(argv, tmpl) == 0) {
        std::ifstream f(tmpl);
        std::getline(f, line);
    }
    ::unlink(tmpl);
    return line;
}

struct Tools {
    std::string cmake, verilator, cxx, pkg_config, generator;
    std::string versions;  // one line per tool, in the key
    std::string missing;   // the first missing tool's message ("" = all there)
};

const Tools& tools() {
    static const Tools t = [] {
        Tools r;
        auto need = [&](std::string& slot, const std::string& prog, const char* package) {
            slot = find_program(prog);
            if (slot.empty() && r.missing.empty())
                r.missing = prog + " (Debian package " + package +
                            "), not found on PATH; scripts/install-deps.sh installs it";
        };
        need(r.cmake, "cmake", "cmake");
        need(r.verilator, "verilator", "verilator");
        const std::string cxx = env("CXX").empty() ? "c++" : env("CXX");
        need(r.cxx, cxx, "g++");
        need(r.pkg_config, "pkg-config", "pkg-config");
        r.generator = find_program("ninja").empty() ? "Unix Makefiles" : "Ninja";
        if (r.generator != "Ninja" && find_program("make").empty() && r.missing.empty())
            r.missing = "ninja or make (Debian package ninja-build or make), neither found on PATH";
        std::string systemc;
        if (!r.pkg_config.empty()) {
            systemc = first_line({r.pkg_config, "--modversion", "systemc"});
            if (systemc.empty() && r.missing.empty())
                r.missing =
                    "SystemC (Debian package libsystemc-dev), which pkg-config does not find; "
                    "scripts/install-deps.sh installs it";
        }
        r.versions =
            "verilator: " + (r.verilator.empty() ? "" : first_line({r.verilator, "--version"})) +
            "\ncxx: " + (r.cxx.empty() ? "" : first_line({r.cxx, "--version"})) +
            "\nsystemc: " + systemc +
            "\ncmake: " + (r.cmake.empty() ? "" : first_line({r.cmake, "--version"})) + "\n";
        return r;
    }();
    return t;
}

// The build's flags (in the key with the tools' versions and the sources).
const char* kBuildFlags =
    "-DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS= -DCMAKE_SHARED_LINKER_FLAGS= "
    "(rtl_model/cache/CMakeLists.txt)";

std::string key_of(const CacheConfig& c) {
    detail::Sha256 h;
    h.update(std::string(kCacheFormat) + "\nabi " + std::to_string(detail::kEntryAbi) + "\n");
    h.update("config " + c.name() + "\n" + tools().versions + "flags: " + kBuildFlags + "\n");
    for (const auto& [path, body] : detail::embedded_sources()) {
        const std::string text = body;
        h.update(std::string("file ") + path + " " + std::to_string(text.size()) + "\n");
        h.update(text);
    }
    return h.hex();
}

// ---- the folder ----------------------------------------------------------

std::string mode_text(mode_t m) {
    char b[8];
    std::snprintf(b, sizeof b, "%04o", static_cast<unsigned>(m & 07777));
    return b;
}

// Why a path may not be trusted ("" = it may): it must be a `dir` or a
// regular file (not a link), owned by this user, writable by nobody else.
std::string untrusted(const std::string& path, bool dir) {
    struct stat st {};
    if (::lstat(path.c_str(), &st) != 0) return "missing";
    if (dir ? !S_ISDIR(st.st_mode) : !S_ISREG(st.st_mode))
        return dir ? "not a folder" : "not a regular file";
    if (st.st_uid != ::geteuid())
        return "owned by uid " + std::to_string(st.st_uid) + ", not this user (uid " +
               std::to_string(::geteuid()) + ")";
    if ((st.st_mode & 022) != 0)
        return "writable by group or others (mode " + mode_text(st.st_mode) + ")";
    return "";
}

// Creates the cache folder (owner-only) or checks an existing one.
std::string open_root() {
    const std::string root = cache_dir();
    if (root == "off")
        throw isa::ConfigError("RTL cache: building on demand is off (IMAP_RTL_CACHE=off)");
    if (root.empty())
        throw isa::ConfigError(
            "RTL cache: no folder (HOME is not set): give one with --rtl-cache DIR or "
            "IMAP_RTL_CACHE");
    std::error_code ec;
    const fs::path p(root);
    if (!fs::exists(p, ec)) {
        if (p.has_parent_path()) fs::create_directories(p.parent_path(), ec);
        if (::mkdir(root.c_str(), 0700) != 0 && errno != EEXIST)
            throw isa::ConfigError("RTL cache: cannot create the folder " + root + ": " +
                                   std::strerror(errno));
    }
    // the folder itself may be reached through a link; what it is must be safe
    struct stat st {};
    if (::stat(root.c_str(), &st) != 0 || !S_ISDIR(st.st_mode))
        throw isa::ConfigError("RTL cache: " + root + " is not a folder");
    if (st.st_uid != ::geteuid() || (st.st_mode & 022) != 0)
        throw isa::ConfigError(
            "RTL cache: the folder " + root + " is " +
            (st.st_uid != ::geteuid()
                 ? "owned by uid " + std::to_string(st.st_uid)
                 : "writable by group or others (mode " + mode_text(st.st_mode) + ")") +
            "; it holds code imapsim loads and runs, so it must be this user's and writable by "
            "nobody else (chmod 700 it, or choose another folder with --rtl-cache DIR or "
            "IMAP_RTL_CACHE)");
    return root;
}

std::map<std::string, std::string> read_record(const std::string& path) {
    std::map<std::string, std::string> m;
    std::ifstream f(path);
    std::string line;
    while (std::getline(f, line)) {
        if (line.empty() || line[0] == '#') continue;
        const size_t eq = line.find('=');
        if (eq != std::string::npos) m[line.substr(0, eq)] = line.substr(eq + 1);
    }
    return m;
}

// Why the entry in `dir` may not be loaded for `key` ("" = it may).
std::string entry_problem(const std::string& dir, const std::string& key) {
    if (std::string why = untrusted(dir, true); !why.empty()) return "folder " + why;
    const std::string rec = dir + "/entry.txt", lib = dir + "/model.so";
    if (std::string why = untrusted(rec, false); !why.empty()) return "record " + why;
    if (std::string why = untrusted(lib, false); !why.empty()) return "library " + why;
    const auto r = read_record(rec);
    const auto k = r.find("key"), s = r.find("model_sha256");
    if (k == r.end() || s == r.end()) return "record incomplete";
    if (k->second != key) return "stale (built from other sources, tools or flags)";
    if (detail::sha256_file(lib) != s->second) return "library does not match its recorded hash";
    return "";
}

std::string utc_now() {
    const std::time_t t = std::time(nullptr);
    std::tm tm{};
    ::gmtime_r(&t, &tm);
    char b[32];
    std::strftime(b, sizeof b, "%Y-%m-%dT%H:%M:%SZ", &tm);
    return b;
}

std::string log_tail(const std::string& path, int lines) {
    std::ifstream f(path);
    std::deque<std::string> q;
    std::string l;
    while (std::getline(f, l)) {
        q.push_back(l);
        if (static_cast<int>(q.size()) > lines) q.pop_front();
    }
    std::string s;
    for (const std::string& x : q) s += "\n  " + x;
    return s;
}

void write_text(const std::string& path, const std::string& text, mode_t mode) {
    const int fd =
        ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_NOFOLLOW | O_CLOEXEC, mode);
    if (fd < 0)
        throw isa::ConfigError("RTL cache: cannot write " + path + ": " + std::strerror(errno));
    size_t off = 0;
    while (off < text.size()) {
        const ssize_t w = ::write(fd, text.data() + off, text.size() - off);
        if (w < 0 && errno == EINTR) continue;
        if (w <= 0) {
            ::close(fd);
            throw isa::ConfigError("RTL cache: cannot write " + path + ": " + std::strerror(errno));
        }
        off += static_cast<size_t>(w);
    }
    ::fchmod(fd, mode);
    ::close(fd);
}

// Removes a folder by renaming it aside first (a reader never sees it half gone).
void discard(const std::string& root, const std::string& dir) {
    const std::string aside =
        root + "/.discard-" + std::to_string(::getpid()) + "-" + fs::path(dir).filename().string();
    std::error_code ec;
    fs::rename(dir, aside, ec);
    fs::remove_all(ec ? fs::path(dir) : fs::path(aside), ec);
}

// Builds the entry of `c` into root/name (the caller holds its lock).
void build_entry(const CacheConfig& c, const std::string& root, const std::string& name,
                 const std::string& key, std::ostream& log) {
    const Tools& t = tools();
    if (!t.missing.empty())
        throw isa::ConfigError("RTL cache: building configuration " + c.name() + " needs " +
                               t.missing);
    const std::string stage = root + "/.staging-" + name + "-" + std::to_string(::getpid());
    std::error_code ec;
    fs::remove_all(stage, ec);
    if (::mkdir(stage.c_str(), 0700) != 0)
        throw isa::ConfigError("RTL cache: cannot create " + stage + ": " + std::strerror(errno));
    struct Cleanup {
        std::string dir;
        ~Cleanup() {
            std::error_code e;
            fs::remove_all(dir, e);
        }
    } cleanup{stage};
    for (const auto& [path, text] : detail::embedded_sources()) {
        const fs::path p = fs::path(stage) / "src" / path;
        fs::create_directories(p.parent_path(), ec);
        write_text(p.string(), text, 0600);
    }
    const std::string blog = stage + "/build.log";
    const std::string bdir = stage + "/build";
    const unsigned jobs = std::max(1u, std::thread::hardware_concurrency());
    log << "rtl-cache: building " << c.name() << " (" << c.pes << " PEs, " << c.mem_bytes
        << " B memory, " << c.ext_bytes << " B external, " << (c.trace == 1 ? "VCD" : "FST")
        << " tracing) into " << root
        << ": verilating and compiling (half a minute at a few PEs, under two minutes at 300)"
        << std::endl;
    const auto t0 = std::chrono::steady_clock::now();
    int rc = run_logged({t.cmake, "-S", stage + "/src/cache", "-B", bdir, "-G", t.generator,
                         "-DCMAKE_BUILD_TYPE=Release", "-DCMAKE_CXX_COMPILER=" + t.cxx,
                         // (the environment's CXXFLAGS / LDFLAGS do not reach the entry)
                         "-DCMAKE_CXX_FLAGS=", "-DCMAKE_SHARED_LINKER_FLAGS=",
                         "-DIMAP_ENTRY_PES=" + std::to_string(c.pes),
                         "-DIMAP_ENTRY_MEM=" + std::to_string(c.mem_bytes),
                         "-DIMAP_ENTRY_EXT=" + std::to_string(c.ext_bytes),
                         "-DIMAP_ENTRY_VARIANT=" + std::string(variant_name(c.trace))},
                        blog);
    if (rc == 0)
        rc = run_logged({t.cmake, "--build", bdir, "--parallel", std::to_string(jobs)}, blog);
    const double secs =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (rc != 0) {
        const std::string kept = root + "/failed-" + name + ".log";
        fs::copy_file(blog, kept, fs::copy_options::overwrite_existing, ec);
        throw isa::ConfigError(
            "RTL cache: building configuration " + c.name() + " failed (exit " +
            std::to_string(rc) + ", log " + kept +
            "; a missing zlib1g-dev or libsystemc-dev shows there); its end:" + log_tail(blog, 12));
    }
    // the entry: the library, its record and the build's log, owner-only
    const std::string entry = stage + "/entry";
    if (::mkdir(entry.c_str(), 0700) != 0)
        throw isa::ConfigError("RTL cache: cannot create " + entry + ": " + std::strerror(errno));
    fs::copy_file(bdir + "/model.so", entry + "/model.so", ec);
    if (ec) throw isa::ConfigError("RTL cache: the build left no library: " + ec.message());
    ::chmod((entry + "/model.so").c_str(), 0700);
    fs::copy_file(blog, entry + "/build.log", ec);
    ::chmod((entry + "/build.log").c_str(), 0600);
    std::ostringstream rec;
    std::string versions = t.versions;
    for (char& ch : versions)
        if (ch == '\n') ch = ';';
    char secs_text[32];
    std::snprintf(secs_text, sizeof secs_text, "%.1f", secs);
    rec << "# imapsim RTL cache entry: checked before every load (docs/rtl.md)\n"
        << "name=" << c.name() << "\npes=" << c.pes << "\nmem_bytes=" << c.mem_bytes
        << "\next_bytes=" << c.ext_bytes << "\ntrace=" << c.trace << "\nkey=" << key
        << "\nmodel_sha256=" << detail::sha256_file(entry + "/model.so") << "\ntools=" << versions
        << "\nbuilt=" << utc_now() << "\nbuild_seconds=" << secs_text << "\n";
    write_text(entry + "/entry.txt", rec.str(), 0600);
    const std::string final_dir = root + "/" + name;
    if (fs::exists(final_dir, ec)) discard(root, final_dir);
    if (::rename(entry.c_str(), final_dir.c_str()) != 0)
        throw isa::ConfigError("RTL cache: cannot publish " + final_dir + ": " +
                               std::strerror(errno));
    log << "rtl-cache: built " << c.name() << " in " << secs_text << " s (" << final_dir << ")"
        << std::endl;
}

// An exclusive lock on root/name.lock for the life of the object.
class EntryLock {
  public:
    EntryLock(const std::string& root, const std::string& name, std::ostream& log) {
        const std::string path = root + "/" + name + ".lock";
        fd_ = ::open(path.c_str(), O_RDWR | O_CREAT | O_NOFOLLOW | O_CLOEXEC, 0600);
        if (fd_ < 0)
            throw isa::ConfigError("RTL cache: cannot open the lock " + path + ": " +
                                   std::strerror(errno));
        if (::flock(fd_, LOCK_EX | LOCK_NB) == 0) return;
        waited = true;
        log << "rtl-cache: another process is building " << name << "; waiting for it" << std::endl;
        while (::flock(fd_, LOCK_EX) != 0)
            if (errno != EINTR)
                throw isa::ConfigError("RTL cache: cannot lock " + path + ": " +
                                       std::strerror(errno));
    }
    ~EntryLock() {
        if (fd_ >= 0) ::close(fd_);  // releases the lock
    }
    EntryLock(const EntryLock&) = delete;
    EntryLock& operator=(const EntryLock&) = delete;
    bool waited = false;

  private:
    int fd_ = -1;
};

std::string entry_name(const CacheConfig& c, const std::string& key) {
    return c.name() + "-" + key.substr(0, 16);
}

void check_config(const CacheConfig& c) {
    isa::MachineConfig m;
    m.pes = c.pes;
    m.mem_bytes = c.mem_bytes;
    m.ext_bytes = c.ext_bytes;
    try {
        m.validate();
    } catch (const isa::ConfigError& e) {
        throw isa::ConfigError(std::string("RTL cache: ") + e.what());
    }
    if (c.trace != 1 && c.trace != 2)
        throw isa::ConfigError("RTL cache: trace must be 1 (VCD) or 2 (FST)");
}

}  // namespace

std::string CacheConfig::name() const {
    return detail::config_stem(pes, mem_bytes, ext_bytes) + "_" + variant_name(trace);
}

std::string cache_dir() {
    if (!g_dir.empty()) return g_dir;
    if (const std::string e = env("IMAP_RTL_CACHE"); !e.empty()) return e;
    if (const std::string x = env("XDG_CACHE_HOME"); !x.empty()) return x + "/imapsim/rtl";
    if (const std::string h = env("HOME"); !h.empty()) return h + "/.cache/imapsim/rtl";
    return "";
}

bool cache_enabled() {
    return cache_dir() != "off";
}

void set_cache_dir(const std::string& dir) {
    g_dir = dir;
    ::setenv("IMAP_RTL_CACHE", dir.c_str(), 1);
}

CacheBuild cache_build(const CacheConfig& c, std::ostream& log) {
    check_config(c);
    const std::string root = open_root();
    const std::string key = key_of(c);
    const std::string name = entry_name(c, key);
    CacheBuild r;
    r.dir = root + "/" + name;
    if (entry_problem(r.dir, key).empty()) return r;
    EntryLock lock(root, name, log);
    r.waited = lock.waited;
    const std::string why = entry_problem(r.dir, key);
    if (why.empty()) {
        if (r.waited)
            log << "rtl-cache: " << c.name() << " is ready (built by another process)" << std::endl;
        return r;
    }
    if (why != "folder missing")
        log << "rtl-cache: rebuilding " << name << ": " << why << std::endl;
    const auto t0 = std::chrono::steady_clock::now();
    build_entry(c, root, name, key, log);
    r.built = true;
    r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const std::string after = entry_problem(r.dir, key);
    if (!after.empty())
        throw isa::ConfigError("RTL cache: the entry just built in " + r.dir +
                               " is not valid: " + after);
    return r;
}

std::vector<CacheEntry> cache_entries() {
    std::vector<CacheEntry> v;
    const std::string root = cache_dir();
    std::error_code ec;
    if (root == "off" || root.empty() || !fs::is_directory(root, ec)) return v;
    std::map<std::string, std::string> keys;  // configuration name -> expected key
    for (const fs::directory_entry& d : fs::directory_iterator(root, ec)) {
        const std::string fname = d.path().filename().string();
        if (fname.empty() || fname[0] != 'p' || !d.is_directory(ec)) continue;
        CacheEntry e;
        e.dir = d.path().string();
        const auto r = read_record(e.dir + "/entry.txt");
        auto get = [&](const char* k) {
            const auto it = r.find(k);
            return it == r.end() ? std::string() : it->second;
        };
        try {
            e.cfg.pes = std::stoi(get("pes"));
            e.cfg.mem_bytes = static_cast<uint32_t>(std::stoul(get("mem_bytes")));
            e.cfg.ext_bytes = static_cast<uint32_t>(std::stoul(get("ext_bytes")));
            e.cfg.trace = std::stoi(get("trace"));
            e.build_seconds = std::stod(get("build_seconds"));
        } catch (const std::exception&) {
            e.status = "invalid: record unreadable";
            v.push_back(e);
            continue;
        }
        e.key = get("key");
        e.built = get("built");
        e.bytes = static_cast<uint64_t>(fs::file_size(e.dir + "/model.so", ec));
        if (ec) e.bytes = 0;
        auto [known, fresh] = keys.try_emplace(e.cfg.name());
        if (fresh) known->second = key_of(e.cfg);  // hashes every source: once per configuration
        const std::string& expect = known->second;
        const std::string why = fname == entry_name(e.cfg, e.key) || e.key.size() < 16
                                    ? entry_problem(e.dir, expect)
                                    : "folder name does not match its record";
        e.status = why.empty() ? "ok" : why.rfind("stale", 0) == 0 ? "stale" : "invalid: " + why;
        v.push_back(e);
    }
    std::sort(v.begin(), v.end(),
              [](const CacheEntry& a, const CacheEntry& b) { return a.dir < b.dir; });
    return v;
}

size_t cache_clean(bool stale_only, std::ostream& log) {
    const std::string root = cache_dir();
    std::error_code ec;
    if (root == "off" || root.empty() || !fs::is_directory(root, ec)) return 0;
    open_root();  // the folder must be safe to act in
    size_t n = 0;
    for (const CacheEntry& e : cache_entries()) {
        if (stale_only && e.status == "ok") continue;
        const std::string name = fs::path(e.dir).filename().string();
        EntryLock lock(root, name, log);
        discard(root, e.dir);
        log << "rtl-cache: removed " << name << " (" << e.status << ")" << std::endl;
        ++n;
    }
    // leftovers of interrupted builds and removals (not of running ones:
    // their processes are alive)
    for (const fs::directory_entry& d : fs::directory_iterator(root, ec)) {
        const std::string f = d.path().filename().string();
        if (f.rfind(".staging-", 0) != 0 && f.rfind(".discard-", 0) != 0 &&
            f.rfind("failed-", 0) != 0)
            continue;
        const size_t dash = f.find_last_of('-');
        if (f.rfind(".staging-", 0) == 0 && dash != std::string::npos) {
            const long pid = std::atol(f.c_str() + dash + 1);
            if (pid > 0 && ::kill(static_cast<pid_t>(pid), 0) == 0) continue;  // still building
        }
        fs::remove_all(d.path(), ec);
    }
    return n;
}

namespace detail {

std::deque<ConfigInfo>& configs() {
    static std::deque<ConfigInfo> v(built_configs().begin(), built_configs().end());
    return v;
}

const ConfigInfo* find_config(int pes, uint32_t mem_bytes, uint32_t ext_bytes, int trace,
                              bool mutants) {
    for (const ConfigInfo& k : configs())
        if (k.pes == pes && k.mem_bytes == mem_bytes && k.ext_bytes == ext_bytes &&
            k.trace == trace && (k.mutants != 0) == mutants)
            return &k;
    return nullptr;
}

std::string config_stem(int pes, uint32_t mem_bytes, uint32_t ext_bytes) {
    return "p" + std::to_string(pes) + "_m" + std::to_string(mem_bytes) + "_x" +
           std::to_string(ext_bytes);
}

const ConfigInfo& cache_load(const CacheConfig& c, std::ostream& log) {
    if (const ConfigInfo* k = find_config(c.pes, c.mem_bytes, c.ext_bytes, c.trace, false))
        return *k;
    const CacheBuild b = cache_build(c, log);
    const std::string lib = b.dir + "/model.so";
    void* h = ::dlopen(lib.c_str(), RTLD_NOW | RTLD_LOCAL);
    if (!h)
        throw isa::ConfigError(std::string("RTL cache: cannot load ") + lib + ": " + ::dlerror());
    auto info = reinterpret_cast<imap_rtl_entry_info_fn>(::dlsym(h, "imap_rtl_entry_info"));
    auto dpi = reinterpret_cast<imap_rtl_entry_dpi_fn>(::dlsym(h, "imap_rtl_entry_dpi"));
    auto make = reinterpret_cast<imap_rtl_entry_make_fn>(::dlsym(h, "imap_rtl_entry_make"));
    if (!info || !dpi || !make)
        throw isa::ConfigError("RTL cache: " + lib +
                               " is not an RTL cache entry (its functions are missing)");
    EntryInfo ei{};
    info(&ei);
    if (ei.abi != kEntryAbi || ei.pes != c.pes || ei.mem_bytes != c.mem_bytes ||
        ei.ext_bytes != c.ext_bytes || ei.trace != c.trace || ei.mutants != 0)
        throw isa::ConfigError("RTL cache: " + lib + " holds another configuration than " +
                               c.name());
    dpi(&host_dpi_table());
    // (never unloaded: the model's SystemC objects live until the process ends)
    static std::deque<std::string> names;
    names.push_back(config_stem(c.pes, c.mem_bytes, c.ext_bytes));
    configs().push_back(
        ConfigInfo{names.back().c_str(), c.pes, c.mem_bytes, c.ext_bytes, c.trace, 0, make});
    return configs().back();
}

}  // namespace detail

}  // namespace imap::rtl
