// sha256.h -- incremental SHA-256 (FIPS 180-4). The one-shot helpers
// sha256_hex / sha256_file are declared in rtb_offline.h.
#ifndef RTB_OFFLINE_IO_SHA256_H
#define RTB_OFFLINE_IO_SHA256_H

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string>

namespace rtb {

class Sha256 {
 public:
  Sha256();
  void update(const void *data, size_t n);
  // Finishes the hash (call once); 64 lower-case hex digits.
  std::string hex_digest();

 private:
  void block(const unsigned char *p);
  uint32_t h_[8];
  unsigned char buf_[64];
  size_t buffered_ = 0;
  uint64_t total_ = 0;
};

}  // namespace rtb

#endif
