// Umbrella header of the imap_isa library.
#pragma once

#include "imap/isa/assembler.hpp"
#include "imap/isa/config.hpp"
#include "imap/isa/encoding.hpp"
#include "imap/isa/machine.hpp"
#include "imap/isa/opcodes.hpp"
#include "imap/isa/program.hpp"
#include "imap/isa/semantics.hpp"
