// The configurations a run can use (the built ones and the cache entries
// loaded into this process) and the loader (rtl_cache.cpp).
#pragma once

#include <deque>
#include <iosfwd>

#include "entry_abi.hpp"
#include "imap/rtl/cache.hpp"

namespace imap::rtl::detail {

// built_configs(), then every cache entry loaded (stable references).
std::deque<ConfigInfo>& configs();
// The configuration of `c` from the cache: built if needed, loaded, added
// to configs(). Throws isa::ConfigError.
const ConfigInfo& cache_load(const CacheConfig& c, std::ostream& log);
// This process's DPI implementations (dpi.cpp), handed to a loaded entry.
const DpiTable& host_dpi_table();

}  // namespace imap::rtl::detail
