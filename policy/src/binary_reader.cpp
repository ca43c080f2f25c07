#include "policy/binary_reader.hpp"

#include <cstring>

namespace policy {

BinaryReader::BinaryReader(const std::string& path) : path_(path), in_(path, std::ios::binary)
{
  if (!in_) throw error("cannot open file");
  in_.seekg(0, std::ios::end);
  size_ = static_cast<uint64_t>(in_.tellg());
  in_.seekg(0, std::ios::beg);
}

void BinaryReader::need(uint64_t bytes, const std::string& what) const
{
  if (bytes > size_ - offset_)
    throw error("truncated file: " + what + " needs " + std::to_string(bytes) + " bytes at offset " +
                std::to_string(offset_) + ", only " + std::to_string(size_ - offset_) + " left");
}

void BinaryReader::read(void* dst, uint64_t bytes, const std::string& what)
{
  need(bytes, what);
  in_.read(static_cast<char*>(dst), static_cast<std::streamsize>(bytes));
  if (!in_) throw error("read error at offset " + std::to_string(offset_));
  offset_ += bytes;
}

// The formats are little-endian and so are the hosts we build for (x86-64, aarch64).
uint32_t BinaryReader::u32(const std::string& what)
{
  uint32_t v = 0;
  read(&v, sizeof v, what);
  return v;
}

uint64_t BinaryReader::u64(const std::string& what)
{
  uint64_t v = 0;
  read(&v, sizeof v, what);
  return v;
}

void BinaryReader::expect_magic(const char (&magic)[8], const std::string& kind)
{
  char m[8];
  if (size_ < 8) throw error("not a " + kind + " (file too short for the magic)");
  read(m, 8, "magic");
  if (std::memcmp(m, magic, 8) != 0) throw error("not a " + kind + " (bad magic, expected '" + std::string(magic, 8) + "')");
}

void BinaryReader::expect_end()
{
  if (offset_ != size_) throw error(std::to_string(size_ - offset_) + " unexpected trailing bytes at offset " + std::to_string(offset_));
}

}  // namespace policy
