// imapsim rtl-cache: the RTL cache of on-demand configurations of the design
// (imap/rtl/cache.hpp; docs/rtl.md, "Any configuration on demand"): list its
// entries, build one ahead of a sweep or a Slurm array, clean it.
#ifdef IMAPSIM_HAVE_RTL
#include <cstdio>
#include <iostream>

#include "cli_common.hpp"
#include "imap/rtl/cache.hpp"
#include "imap/rtl/config.hpp"
#include "model_runner.hpp"

namespace imapsim {

namespace rtl = imap::rtl;

namespace {
struct CacheOptions {
    std::string dir;
    std::string pes, mem_bytes = "1024", ext_bytes = "65536", waves = "fst";
    bool stale = false;
};

std::string megabytes(uint64_t bytes) {
    char b[32];
    std::snprintf(b, sizeof b, "%.1f MB", static_cast<double>(bytes) / 1e6);
    return b;
}

int list_entries() {
    const std::vector<rtl::CacheEntry> v = rtl::cache_entries();
    uint64_t total = 0;
    for (const rtl::CacheEntry& e : v) total += e.bytes;
    std::printf("RTL cache %s: %zu entr%s, %s\n", rtl::cache_dir().c_str(), v.size(),
                v.size() == 1 ? "y" : "ies", megabytes(total).c_str());
    if (!v.empty()) {
        std::printf("  %-24s %5s %8s %8s %5s %9s  %-20s %8s  %s\n", "configuration", "PEs", "mem B",
                    "ext B", "waves", "library", "built (UTC)", "build s", "status");
        for (const rtl::CacheEntry& e : v)
            std::printf("  %-24s %5d %8u %8u %5s %9s  %-20s %8.1f  %s\n", e.cfg.name().c_str(),
                        e.cfg.pes, e.cfg.mem_bytes, e.cfg.ext_bytes,
                        e.cfg.trace == 1 ? "VCD" : "FST", megabytes(e.bytes).c_str(),
                        e.built.c_str(), e.build_seconds, e.status.c_str());
    }
    std::printf("built into this binary (used first):");
    for (const std::string& c : rtl::built_configurations()) std::printf(" %s;", c.c_str());
    std::printf("\n");
    return static_cast<int>(kExitOk);
}
}  // namespace

Subcommand register_rtl_cache(CLI::App& app) {
    auto o = std::make_shared<CacheOptions>();
    CLI::App* sub = app.add_subcommand(
        "rtl-cache",
        "The cache of RTL configurations built on demand (docs/rtl.md): list, build, clean");
    sub->require_subcommand(1);
    add_rtl_cache_flag(sub, o->dir);
    CLI::App* list = sub->add_subcommand("list", "List the entries, their size and status");
    CLI::App* build = sub->add_subcommand(
        "build", "Build one configuration now (ahead of a sweep or a cluster array)");
    build->add_option("--pes", o->pes, "PEs in the array (>= 2)")->required();
    build->add_option("--mem-bytes", o->mem_bytes, "local memory per PE")->capture_default_str();
    build->add_option("--ext-bytes", o->ext_bytes, "external memory per PE, 0 = none")
        ->capture_default_str();
    build
        ->add_option("--waves", o->waves,
                     "wave format compiled in: fst (also the untraced runs) or vcd")
        ->capture_default_str();
    CLI::App* clean = sub->add_subcommand("clean", "Remove the entries (all, or --stale ones)");
    clean->add_flag("--stale", o->stale,
                    "only the entries this binary would not load (other sources, tools or "
                    "flags; bad ownership or hash)");
    for (CLI::App* s : {list, build, clean}) add_rtl_cache_flag(s, o->dir);

    return {
        sub, [o, list, build, clean]() {
            apply_rtl_cache_flag(o->dir);
            if (list->parsed()) return list_entries();
            if (clean->parsed()) {
                const size_t n = rtl::cache_clean(o->stale, std::cout);
                std::printf("rtl-cache: %zu entr%s removed from %s\n", n, n == 1 ? "y" : "ies",
                            rtl::cache_dir().c_str());
                return static_cast<int>(kExitOk);
            }
            (void)build;
            rtl::CacheConfig c;
            c.pes = static_cast<int>(parse_int_flag("--pes", o->pes, 2, 1 << 20));
            c.mem_bytes =
                static_cast<uint32_t>(parse_int_flag("--mem-bytes", o->mem_bytes, 1, 1 << 20));
            c.ext_bytes =
                static_cast<uint32_t>(parse_int_flag("--ext-bytes", o->ext_bytes, 0, 0xffffffffLL));
            if (o->waves != "fst" && o->waves != "vcd")
                throw UserError("invalid value '" + o->waves +
                                "' for --waves: expected fst or vcd");
            c.trace = o->waves == "vcd" ? 1 : 2;
            rtl::CacheBuild b;
            try {
                b = rtl::cache_build(c, std::cerr);
            } catch (const imap::isa::ConfigError& e) {
                throw UserError(e.what());
            }
            char how[64];
            if (b.built)
                std::snprintf(how, sizeof how, "built in %.1f s", b.seconds);
            else
                std::snprintf(how, sizeof how, "%s",
                              b.waited ? "built by another process" : "already built");
            std::printf("rtl-cache: %s ready in %s (%s)\n", c.name().c_str(), b.dir.c_str(), how);
            return static_cast<int>(kExitOk);
        }};
}

}  // namespace imapsim
#endif
