#pragma once
// Arena: bump allocator for search nodes and per-node arrays. The search allocates a few
// small arrays per expansion and frees them all at once (end of search, new goals, or a
// naive RT-LaCAM iteration), so a bump allocator removes per-expansion heap traffic.
// reset() keeps the blocks for reuse.
//
// A block is raw storage; alloc() default-initialises only the objects it hands out. Building
// a whole block at once (new T[16384]: 384 KB of links, 1.6 MB of nodes, every page touched)
// was one step of O(block) inside a single iteration whenever a block was opened: the first
// LaCAM* link cost 0.2 ms of a 0.1 ms budget (random-32-32-20 N = 300). Now each object costs
// when it is used, and an untouched page costs nothing.
#include <algorithm>
#include <cstddef>
#include <memory>
#include <new>
#include <type_traits>
#include <vector>

namespace planner {

template <class T>
class Arena {
  static_assert(std::is_trivially_destructible_v<T>, "Arena frees blocks without destructors");

 public:
  explicit Arena(size_t block_size = 1 << 14) : block_size_(block_size) {}

  T* alloc(size_t n)
  {
    while (cur_ < blocks_.size() && used_ + n > blocks_[cur_].size) ++cur_, used_ = 0;
    if (cur_ == blocks_.size()) {
      size_t size = std::max(block_size_, n);
      blocks_.push_back({std::unique_ptr<Slot[]>(new Slot[size]), size});  // not initialised
      used_ = 0;
    }
    Slot* s = blocks_[cur_].data.get() + used_;
    T* p = ::new (static_cast<void*>(s)) T;  // default-initialised, as new T[n] did
    for (size_t k = 1; k < n; ++k) ::new (static_cast<void*>(s + k)) T;
    used_ += n;
    return p;
  }

  void reset() { cur_ = 0, used_ = 0; }

  size_t bytes_reserved() const
  {
    size_t s = 0;
    for (auto& b : blocks_) s += b.size * sizeof(T);
    return s;
  }

 private:
  using Slot = std::aligned_storage_t<sizeof(T), alignof(T)>;
  struct Block {
    std::unique_ptr<Slot[]> data;
    size_t size;
  };
  std::vector<Block> blocks_;
  size_t block_size_;
  size_t cur_ = 0, used_ = 0;
};

}  // namespace planner
