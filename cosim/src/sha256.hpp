// SHA-256 (FIPS 180-4): the RTL cache keys its entries by the hash of what
// they are built from and checks each loaded library against the hash
// recorded when it was built (rtl_cache.cpp).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>

namespace imap::rtl::detail {

class Sha256 {
  public:
    Sha256();
    void update(const void* data, size_t n);
    void update(const std::string& s) { update(s.data(), s.size()); }
    std::string hex();  // finishes: 64 lowercase hex digits

  private:
    void block(const uint8_t* p);
    uint32_t h_[8];
    uint8_t buf_[64];
    size_t used_ = 0;
    uint64_t bytes_ = 0;
};

// The hash of a file's bytes ("" when it cannot be read).
std::string sha256_file(const std::string& path);

}  // namespace imap::rtl::detail
