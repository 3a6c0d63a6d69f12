// The RTL cache: any configuration of the design (PE count, memory sizes,
// wave format), verilated and compiled on first use into a shared library
// that later runs load (docs/rtl.md, "Any configuration on demand"). The
// configurations built into the binary (IMAP_RTL_CONFIGS) are used first;
// the cache serves every other one.
//
// Each entry is keyed by the SHA-256 of what it is built from: the design's
// and testbench's sources embedded in the binary, the configuration, the
// versions of Verilator, the C++ compiler, SystemC and CMake, and the build
// flags. The cache holds code the tool loads and runs: its folder is created
// owner-only (0700); an entry is loaded only if it, its library and its
// record are owned by this user and writable by nobody else, and the
// recorded key and library hash match; any other entry is rebuilt. Builds
// take a per-entry lock and publish with an atomic rename, so concurrent
// runs (a sweep, a Slurm array) build a configuration once and never read a
// half-built one.
#pragma once

#include <cstdint>
#include <iosfwd>
#include <string>
#include <vector>

namespace imap::rtl {

// The cache folder: set_cache_dir, else $IMAP_RTL_CACHE, else
// $XDG_CACHE_HOME/imapsim/rtl, else $HOME/.cache/imapsim/rtl. The value
// "off" switches building on demand off (an unbuilt configuration is refused).
std::string cache_dir();
bool cache_enabled();
// For this process and the ones it starts (sets IMAP_RTL_CACHE).
void set_cache_dir(const std::string& dir);

// One configuration of the cache: trace 1 = VCD, 2 = FST (tracing compiled
// in, off until a run asks; every entry has one of the two).
struct CacheConfig {
    int pes = 0;
    uint32_t mem_bytes = 1024, ext_bytes = 65536;
    int trace = 2;
    std::string name() const;  // "p31_m1024_x65536_fst"
};

struct CacheEntry {
    std::string dir;  // the entry's folder
    CacheConfig cfg;
    std::string key;    // as recorded
    std::string built;  // UTC, ISO 8601
    double build_seconds = 0;
    uint64_t bytes = 0;  // the library
    // "ok", "stale" (built from other sources, tools or flags than this
    // binary's: rebuilt on use) or "invalid: <why>" (never loaded)
    std::string status;
};
// Every entry of the cache folder (none if it does not exist).
std::vector<CacheEntry> cache_entries();

struct CacheBuild {
    std::string dir;
    bool built = false;   // false: a valid entry was there (or another process built it)
    bool waited = false;  // another process held the entry's lock
    double seconds = 0;   // the build's wall time
};
// Makes sure the entry of `c` is built and valid (building it if needed),
// with progress lines on `log`. Throws isa::ConfigError: a bad
// configuration, an unsafe cache folder, a missing tool (naming the Debian
// package) or a failed build (with its log).
CacheBuild cache_build(const CacheConfig& c, std::ostream& log);
// Removes the entries (only the stale and invalid ones with stale_only) and
// leftovers of interrupted builds; returns how many entries went.
size_t cache_clean(bool stale_only, std::ostream& log);

}  // namespace imap::rtl
