#pragma once
// Arena: bump allocator for search nodes and per-node arrays. The search allocates a few
// small arrays per expansion and frees them all at once (end of search, new goals, or a
// naive RT-LaCAM iteration), so a bump allocator removes per-expansion heap traffic.
// reset() keeps the blocks for reuse.
#include <algorithm>
#include <cstddef>
#include <memory>
#include <vector>

namespace planner {

template <class T>
class Arena {
 public:
  explicit Arena(size_t block_size = 1 << 14) : block_size_(block_size) {}

  T* alloc(size_t n)
  {
    while (cur_ < blocks_.size() && used_ + n > blocks_[cur_].size) ++cur_, used_ = 0;
    if (cur_ == blocks_.size()) {
      size_t size = std::max(block_size_, n);
      blocks_.push_back({std::unique_ptr<T[]>(new T[size]), size});
      used_ = 0;
    }
    T* p = blocks_[cur_].data.get() + used_;
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
  struct Block {
    std::unique_ptr<T[]> data;
    size_t size;
  };
  std::vector<Block> blocks_;
  size_t block_size_;
  size_t cur_ = 0, used_ = 0;
};

}  // namespace planner
