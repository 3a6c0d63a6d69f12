#include "fuzz_common.hpp"

#include <fcntl.h>
#include <signal.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iterator>
#include <ostream>
#include <set>
#include <stdexcept>
#include <thread>

#if defined(__SANITIZE_ADDRESS__)
#define IMAP_FUZZ_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define IMAP_FUZZ_SANITIZED 1
#endif
#endif
#ifdef IMAP_FUZZ_SANITIZED
#include <sanitizer/common_interface_defs.h>
#endif

namespace imap::fuzz {

namespace fs = std::filesystem;

std::string fuzz_dir() {
    return IMAP_FUZZ_DIR;
}
std::string work_dir() {
    return IMAP_FUZZ_WORK;
}

namespace {

double env_double(const char* name, double def) {
    const char* v = std::getenv(name);
    if (!v || !*v) return def;
    char* end = nullptr;
    const double d = std::strtod(v, &end);
    if (*end != '\0' || !(d >= 0)) throw std::invalid_argument(std::string("bad ") + name);
    return d;
}

uint64_t env_u64(const char* name, uint64_t def) {
    const char* v = std::getenv(name);
    if (!v || !*v) return def;
    char* end = nullptr;
    const unsigned long long x = std::strtoull(v, &end, 10);
    if (*end != '\0') throw std::invalid_argument(std::string("bad ") + name);
    return x;
}

}  // namespace

Options options(double default_seconds, uint64_t default_iterations, int argc, char** argv) {
    Options o;
    o.seconds = env_double("IMAP_FUZZ_SECONDS", default_seconds);
    o.iterations = env_u64("IMAP_FUZZ_ITERATIONS", default_iterations);
    o.seed = env_u64("IMAP_FUZZ_SEED", o.seed);
    o.call_limit = env_double("IMAP_FUZZ_CALL_LIMIT", o.call_limit);
    for (int i = 1; i + 1 < argc; i += 2) {
        const std::string k = argv[i], v = argv[i + 1];
        if (k == "--seconds")
            o.seconds = std::stod(v);
        else if (k == "--iterations")
            o.iterations = std::stoull(v);
        else if (k == "--seed")
            o.seed = std::stoull(v);
        else if (k == "--call-limit")
            o.call_limit = std::stod(v);
        else if (k == "--replay")
            o.replay = v;
        else
            throw std::invalid_argument("unknown fuzz option '" + k +
                                        "' (--seconds --iterations --seed --call-limit --replay)");
    }
    return o;
}

std::string signature(const std::string& prefix, const std::string& message) {
    std::string m = message.substr(0, message.find('\n'));
    // Drop the macro-expansion context: it only repeats where the line was.
    const size_t ctx = m.find(" (in macro '");
    if (ctx != std::string::npos) m.erase(ctx);
    std::string out;
    bool in_quote = false;
    for (size_t i = 0; i < m.size(); ++i) {
        const char c = m[i];
        if (in_quote) {
            // A quote closes the quoted text when a separator follows it
            // (quoted names may contain quotes themselves).
            const char n = i + 1 < m.size() ? m[i + 1] : ' ';
            if (c == '\'' && std::strchr(" :),;.", n)) {
                in_quote = false;
                out += "_'";
            }
            continue;
        }
        if (c == '\'') {
            in_quote = true;
            out += c;
        } else if (std::isdigit(static_cast<unsigned char>(c))) {
            if (out.empty() || out.back() != 'N') out += 'N';
        } else if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) {
            out += '?';
        } else {
            out += c;
        }
    }
    if (out.size() > 90) out.resize(90);
    return prefix.empty() ? out : prefix + ": " + out;
}

Bytes read_file(const std::string& path) {
    std::ifstream f(path, std::ios::binary);
    if (!f) throw std::runtime_error("cannot read '" + path + "'");
    return Bytes((std::istreambuf_iterator<char>(f)), std::istreambuf_iterator<char>());
}

void write_file(const std::string& path, const Bytes& b) {
    std::ofstream f(path, std::ios::binary | std::ios::trunc);
    f.write(reinterpret_cast<const char*>(b.data()), static_cast<std::streamsize>(b.size()));
    if (!f) throw std::runtime_error("cannot write '" + path + "'");
}

namespace {

std::string scratch_dir() {
    static const std::string dir = [] {
        const char* e = std::getenv("IMAP_FUZZ_TMP");
        if (e && *e) return std::string(e);
        if (::access("/dev/shm", W_OK | X_OK) == 0) return std::string("/dev/shm");
        return work_dir();
    }();
    return dir;
}

// Open scratch files, closed and removed at exit.
struct Scratch {
    std::map<std::string, int> fds;
    ~Scratch() {
        for (const auto& [path, fd] : fds) {
            ::close(fd);
            ::unlink(path.c_str());
        }
    }
};
Scratch g_scratch;

}  // namespace

std::string put_scratch_file(const std::string& name, const Bytes& b) {
    const std::string path =
        scratch_dir() + "/imap-fuzz-" + std::to_string(static_cast<long>(::getpid())) + "-" + name;
    auto it = g_scratch.fds.find(path);
    if (it == g_scratch.fds.end()) {
        const int fd = ::open(path.c_str(), O_RDWR | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
        if (fd < 0) throw std::runtime_error("cannot create " + path);
        it = g_scratch.fds.emplace(path, fd).first;
    }
    if (::ftruncate(it->second, 0) != 0 ||
        ::pwrite(it->second, b.data(), b.size(), 0) != static_cast<ssize_t>(b.size()))
        throw std::runtime_error("cannot write " + path);
    return path;
}

std::vector<std::pair<std::string, Bytes>> read_dir(const std::string& dir) {
    std::vector<std::pair<std::string, Bytes>> out;
    std::error_code ec;
    if (!fs::is_directory(dir, ec)) return out;
    std::vector<std::string> names;
    for (const auto& e : fs::directory_iterator(dir))
        if (e.is_regular_file()) names.push_back(e.path().string());
    std::sort(names.begin(), names.end());
    for (const std::string& n : names) out.emplace_back(n, read_file(n));
    return out;
}

// ---------------------------------------------------------------------------
// Byte mutations

void mutate_bytes(Rng& rng, Bytes& b, const std::vector<Bytes>& others, size_t max_size,
                  int stack) {
    static const uint8_t kBytes[] = {0, 1, 2, 0x7f, 0x80, 0xfe, 0xff, '\n', ' ', '0', '9', '-'};
    static const uint32_t kWords[] = {
        0,      1,      2,        3,          7,          8,          15,        16,
        63,     64,     255,      256,        4095,       4096,       65535,     65536,
        0x7fff, 0x8000, 1u << 24, 0x7fffffff, 0x80000000, 0xfffffffe, 0xffffffff};
    const int n = 1 + static_cast<int>(rng.below(static_cast<uint64_t>(stack)));
    for (int step = 0; step < n; ++step) {
        const size_t size = b.size();
        const size_t pos = rng.index(size);
        switch (rng.below(12)) {
            case 0:  // flip one bit
                if (size) b[pos] ^= static_cast<uint8_t>(1u << rng.below(8));
                break;
            case 1:  // random byte
                if (size) b[pos] = static_cast<uint8_t>(rng.next());
                break;
            case 2:  // interesting byte
                if (size) b[pos] = kBytes[rng.index(sizeof kBytes)];
                break;
            case 3: {  // interesting 16/32-bit value, little or big endian
                const uint32_t v = kWords[rng.index(sizeof kWords / sizeof kWords[0])];
                const size_t w = rng.chance(50) ? 2 : 4;
                if (size < w) break;
                const size_t at = rng.index(size - w + 1);
                const bool be = rng.chance(50);
                for (size_t k = 0; k < w; ++k)
                    b[at + k] = static_cast<uint8_t>(v >> (8 * (be ? w - 1 - k : k)));
                break;
            }
            case 4:  // small add / subtract
                if (size) b[pos] = static_cast<uint8_t>(b[pos] + rng.below(33) - 16);
                break;
            case 5: {  // delete a range
                if (!size) break;
                const size_t len = 1 + rng.index(std::min<size_t>(32, size - pos));
                b.erase(b.begin() + static_cast<std::ptrdiff_t>(pos),
                        b.begin() + static_cast<std::ptrdiff_t>(pos + len));
                break;
            }
            case 6: {  // insert random bytes
                const size_t len = 1 + rng.index(16);
                Bytes ins(len);
                for (auto& x : ins) x = static_cast<uint8_t>(rng.next());
                b.insert(b.begin() + static_cast<std::ptrdiff_t>(rng.index(size + 1)), ins.begin(),
                         ins.end());
                break;
            }
            case 7: {  // duplicate a block of itself somewhere
                if (!size) break;
                const size_t len = 1 + rng.index(std::min<size_t>(64, size - pos));
                const Bytes blk(b.begin() + static_cast<std::ptrdiff_t>(pos),
                                b.begin() + static_cast<std::ptrdiff_t>(pos + len));
                b.insert(b.begin() + static_cast<std::ptrdiff_t>(rng.index(size + 1)), blk.begin(),
                         blk.end());
                break;
            }
            case 8: {  // overwrite a block with another block of itself
                if (size < 2) break;
                const size_t len = 1 + rng.index(std::min<size_t>(64, size / 2));
                const size_t from = rng.index(size - len + 1), to = rng.index(size - len + 1);
                std::memmove(b.data() + to, b.data() + from, len);
                break;
            }
            case 9: {  // splice: head of this one, tail of another
                if (others.empty()) break;
                const Bytes& o = rng.pick(others);
                const size_t cut = rng.index(size + 1), from = rng.index(o.size() + 1);
                b.resize(cut);
                b.insert(b.end(), o.begin() + static_cast<std::ptrdiff_t>(from), o.end());
                break;
            }
            case 10:  // truncate
                if (size) b.resize(rng.index(size));
                break;
            case 11: {  // insert a block of another input
                if (others.empty()) break;
                const Bytes& o = rng.pick(others);
                if (o.empty()) break;
                const size_t from = rng.index(o.size());
                const size_t len = 1 + rng.index(std::min<size_t>(64, o.size() - from));
                b.insert(b.begin() + static_cast<std::ptrdiff_t>(rng.index(size + 1)),
                         o.begin() + static_cast<std::ptrdiff_t>(from),
                         o.begin() + static_cast<std::ptrdiff_t>(from + len));
                break;
            }
        }
        if (b.size() > max_size) b.resize(max_size);
    }
}

// ---------------------------------------------------------------------------
// Campaign: crash / hang reporting. One campaign at a time per process.

namespace {

std::atomic<int64_t> g_call_start{0};  // steady-clock ns, 0 = not in a call
std::atomic<bool> g_watch{false};
double g_call_limit = 0;
char g_cur_path[1024];   // scratch file holding the input under test
char g_keep_path[1024];  // where it is copied when the process dies
int g_err_fd = 2;        // the real stderr while the decoders' chatter is redirected
std::thread g_watchdog;

int64_t now_ns() {
    return std::chrono::duration_cast<std::chrono::nanoseconds>(
               std::chrono::steady_clock::now().time_since_epoch())
        .count();
}

void say(const char* a, const char* b = "", const char* c = "") {
    for (const char* s : {a, b, c}) {
        ssize_t r = ::write(g_err_fd, s, std::strlen(s));
        (void)r;
    }
}

// Copies the input under test to the work dir (async-signal-safe calls only).
void keep_input() {
    const int in = ::open(g_cur_path, O_RDONLY);
    const int out = ::open(g_keep_path, O_WRONLY | O_CREAT | O_TRUNC, 0644);
    char buf[4096];
    ssize_t n;
    while (in >= 0 && out >= 0 && (n = ::read(in, buf, sizeof buf)) > 0)
        if (::write(out, buf, static_cast<size_t>(n)) != n) break;
    if (in >= 0) ::close(in);
    if (out >= 0) ::close(out);
}

void on_death() {
    keep_input();
    say("\nfuzz: the process is dying; the input under test is saved in ", g_keep_path, "\n");
}

#ifndef IMAP_FUZZ_SANITIZED
constexpr int kSignals[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGABRT};
struct sigaction g_old[5];
alignas(16) char g_altstack[1 << 16];

void on_signal(int sig) {
    on_death();
    ::signal(sig, SIG_DFL);
    ::raise(sig);
}
#endif

void watchdog() {
    while (g_watch.load()) {
        const int64_t s = g_call_start.load();
        if (s != 0 && static_cast<double>(now_ns() - s) * 1e-9 > g_call_limit) {
            keep_input();
            say("\nfuzz: one call ran longer than the per-call limit (hang); the input is saved "
                "in ",
                g_keep_path, "\n");
            std::_Exit(97);
        }
        std::this_thread::sleep_for(std::chrono::milliseconds(50));
    }
}

int g_saved_stderr = -1;

}  // namespace

Campaign::Campaign(std::string target, const Options& opt, std::string work_dir, std::string ext)
    : target_(std::move(target)), work_(std::move(work_dir)), ext_(std::move(ext)), opt_(opt) {
    start_ = std::chrono::steady_clock::now();
    cur_path_ = put_scratch_file("current-" + target_ + ext_, {});
    std::snprintf(g_cur_path, sizeof g_cur_path, "%s", cur_path_.c_str());
    std::snprintf(g_keep_path, sizeof g_keep_path, "%s",
                  (work_ + "/fuzz-" + target_ + "-crash" + ext_).c_str());

    // Decoder libraries (libpng, libjpeg, OpenCV) print warnings on stderr
    // for corrupt files: they go to a log file; our messages and sanitizer
    // reports still go to the real stderr.
    const std::string log = work_ + "/fuzz-" + target_ + "-stderr.log";
    const int lf = ::open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
    if (lf >= 0) {
        g_saved_stderr = ::dup(2);
        ::dup2(lf, 2);
        ::close(lf);
        g_err_fd = g_saved_stderr;
    }
#ifdef IMAP_FUZZ_SANITIZED
    __sanitizer_set_report_fd(reinterpret_cast<void*>(static_cast<intptr_t>(g_err_fd)));
    __sanitizer_set_death_callback(&on_death);
#else
    stack_t ss{};
    ss.ss_sp = g_altstack;
    ss.ss_size = sizeof g_altstack;
    ::sigaltstack(&ss, nullptr);
    for (size_t i = 0; i < 5; ++i) {
        struct sigaction sa {};
        sa.sa_handler = &on_signal;
        sa.sa_flags = SA_ONSTACK;
        sigemptyset(&sa.sa_mask);
        ::sigaction(kSignals[i], &sa, &g_old[i]);
    }
#endif
    g_call_limit = opt_.call_limit;
    g_watch = true;
    g_watchdog = std::thread(watchdog);
}

Campaign::~Campaign() {
    finish();
}

void Campaign::finish() {
    if (finished_) return;
    wall_ = seconds();
    finished_ = true;
    g_watch = false;
    if (g_watchdog.joinable()) g_watchdog.join();
#ifdef IMAP_FUZZ_SANITIZED
    __sanitizer_set_death_callback(nullptr);
#else
    for (size_t i = 0; i < 5; ++i) ::sigaction(kSignals[i], &g_old[i], nullptr);
#endif
    if (g_saved_stderr >= 0) {
        ::dup2(g_saved_stderr, 2);
        ::close(g_saved_stderr);
        g_saved_stderr = -1;
        g_err_fd = 2;
#ifdef IMAP_FUZZ_SANITIZED
        __sanitizer_set_report_fd(reinterpret_cast<void*>(static_cast<intptr_t>(2)));
#endif
    }
}

double Campaign::seconds() const {
    if (finished_) return wall_;
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
}

bool Campaign::more() const {
    if (finished_) return false;
    if (opt_.iterations != 0 && tried_ >= opt_.iterations) return false;
    return seconds() < opt_.seconds;
}

Result Campaign::run(const Bytes& input, const std::function<Result(const Bytes&)>& fn) {
    ++tried_;
    put_scratch_file("current-" + target_ + ext_, input);
    const auto t0 = std::chrono::steady_clock::now();
    g_call_start = now_ns();
    Result r;
    try {
        r = fn(input);
    } catch (const std::exception& e) {
        r = {"escaped exception", std::string("exception escaped the harness: ") + e.what()};
    } catch (...) {
        r = {"escaped exception", "unknown exception escaped the harness"};
    }
    g_call_start = 0;
    const double dt = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (dt > slowest_) {
        slowest_ = dt;
        slowest_outcome_ = r.outcome;
        if (dt > 0.5) write_file(work_ + "/fuzz-" + target_ + "-slowest" + ext_, input);
    }
    if (!r.violation.empty()) {
        const std::string path =
            work_ + "/fuzz-" + target_ + "-violation-" + std::to_string(violations_.size()) + ext_;
        if (violations_.size() < 20) write_file(path, input);
        violations_.push_back(r.violation + " (input saved in " + path + ")");
        ++outcomes_["VIOLATION: " + signature("", r.violation)];
    } else {
        ++outcomes_[r.outcome];
    }
    return r;
}

void Campaign::report(std::ostream& os) const {
    std::vector<std::pair<uint64_t, std::string>> top;
    for (const auto& [k, v] : outcomes_) top.emplace_back(v, k);
    std::sort(top.begin(), top.end(), [](const auto& a, const auto& b) {
        return a.first != b.first ? a.first > b.first : a.second < b.second;
    });
    os << "fuzz summary: target=" << target_ << " inputs=" << tried_
       << " distinct_outcomes=" << outcomes_.size() << " violations=" << violations_.size()
       << " wall=" << std::fixed << std::setprecision(1) << seconds() << "s seed=" << opt_.seed
       << " slowest_call=" << std::setprecision(3) << slowest_ << "s (" << slowest_outcome_
       << ")\n";
    // IMAP_FUZZ_VERBOSE=1 lists every outcome class.
    const size_t shown = std::getenv("IMAP_FUZZ_VERBOSE") ? top.size() : 15;
    for (size_t i = 0; i < top.size() && i < shown; ++i)
        os << "  " << std::setw(8) << top[i].first << "  " << top[i].second << "\n";
    if (top.size() > shown) os << "  ... " << top.size() - shown << " more outcome classes\n";
    for (size_t i = 0; i < violations_.size() && i < 10; ++i)
        os << "  !! " << violations_[i] << "\n";
    os.flush();
}

void fuzz_loop(Campaign& c, Rng& rng, const std::vector<Bytes>& seeds, const Mutator& mutate,
               const Checker& check) {
    if (seeds.empty()) throw std::invalid_argument("fuzz_loop: no seeds");
    std::vector<Bytes> pool = seeds;
    std::set<std::string> seen;
    for (const Bytes& s : seeds) seen.insert(c.run(s, check).outcome);
    while (c.more()) {
        Bytes b = rng.pick(pool);
        mutate(rng, b, pool);
        const Result r = c.run(b, check);
        // Small ones only: big inputs (deep nests, long lines) are slow and
        // every mutant of them would be big too.
        if (seen.insert(r.outcome).second && r.violation.empty() && b.size() <= (16u << 10) &&
            pool.size() < seeds.size() + 1000)
            pool.push_back(std::move(b));
    }
}

}  // namespace imap::fuzz
