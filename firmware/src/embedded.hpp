// The firmware sources compiled into the library (generated from
// firmware/asm by cmake/embed_files.cmake): file name, text.
#pragma once

#include <utility>
#include <vector>

namespace imap::firmware::detail {

const std::vector<std::pair<const char*, const char*>>& embedded_sources();

}  // namespace imap::firmware::detail
