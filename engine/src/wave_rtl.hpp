// Private to imap_engine_models: the waves of an RTL run (wave_session.cpp),
// used by run_model (model_run.cpp): the design-level selection built from
// the trace options, and the line saying where the waves went.
#pragma once

#include <string>

#if defined(IMAP_ENGINE_HAVE_RTL) && defined(IMAP_ENGINE_HAVE_WAVES)
#include "imap/rtl/system.hpp"
#include "imap/waves/isa_trace.hpp"

namespace imap::engine {

// --vcd with --model rtl: the design's own signals for selection `s`.
rtl::RtlWaves rtl_waves(const std::string& path, const waves::TraceSelection& s);

// The waves line of an RTL run (rr null: the run faulted) and its warnings.
void print_rtl_waves(const rtl::RtlWaves& w, const rtl::RtlRunResult* rr, const std::string& window,
                     const std::string& limit_name);

}  // namespace imap::engine
#endif
