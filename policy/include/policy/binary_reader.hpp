#pragma once
// BinaryReader: the little-endian reads shared by the policy's file formats. Every
// failure is a planner::InputError "path: what" that says which field was cut short, so
// a truncated file is reported as such instead of being read as garbage.
#include <cstdint>
#include <fstream>
#include <string>

#include "planner/error.hpp"

namespace policy {

class BinaryReader {
 public:
  explicit BinaryReader(const std::string& path);

  const std::string& path() const { return path_; }
  uint64_t size() const { return size_; }
  uint64_t offset() const { return offset_; }

  // Reads `bytes` bytes of field `what`; throws "truncated" naming it when the file ends.
  void read(void* dst, uint64_t bytes, const std::string& what);
  // The same check without reading: call it before allocating a buffer whose size comes
  // from the file, so a corrupt header is "truncated", not a multi-gigabyte allocation.
  void need(uint64_t bytes, const std::string& what) const;
  uint32_t u32(const std::string& what);
  uint64_t u64(const std::string& what);
  void expect_magic(const char (&magic)[8], const std::string& kind);
  void expect_end();  // throws on trailing bytes

  planner::InputError error(const std::string& what) const { return planner::input_error(path_, 0, what); }

 private:
  std::string path_;
  std::ifstream in_;
  uint64_t size_ = 0, offset_ = 0;
};

}  // namespace policy
