// The SystemC TLM-2.0 model of the IMAP-VISION board (docs/tlm.md).
#pragma once

#include "imap/tlm/components.hpp"
#include "imap/tlm/config.hpp"
#include "imap/tlm/cp.hpp"
#include "imap/tlm/system.hpp"
