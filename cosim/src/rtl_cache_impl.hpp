// The configurations a run can use (the built ones and the cache entries
// loaded into this process) and the loader (rtl_cache.cpp).
#pragma once

#include <cstdint>
#include <deque>
#include <iosfwd>
#include <string>

#include "entry_abi.hpp"
#include "imap/rtl/cache.hpp"

namespace imap::rtl::detail {

// built_configs(), then every cache entry loaded (stable references).
std::deque<ConfigInfo>& configs();
// The configuration of configs() with these sizes and trace (0 none, 1 VCD,
// 2 FST), the mutation-check one if `mutants`; nullptr if none.
const ConfigInfo* find_config(int pes, uint32_t mem_bytes, uint32_t ext_bytes, int trace,
                              bool mutants);
// "p<pes>_m<mem>_x<ext>": a configuration's name, as the build names the
// built ones (rtl_model/CMakeLists.txt) and the cache its entries.
std::string config_stem(int pes, uint32_t mem_bytes, uint32_t ext_bytes);
// The configuration of `c` from the cache: built if needed, loaded, added
// to configs(). Throws isa::ConfigError.
const ConfigInfo& cache_load(const CacheConfig& c, std::ostream& log);
// This process's DPI implementations (dpi.cpp), handed to a loaded entry.
const DpiTable& host_dpi_table();

}  // namespace imap::rtl::detail
