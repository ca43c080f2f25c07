#pragma once
// LazyTable: a fixed-size, zero-filled array whose pages the OS maps on first touch (calloc of
// a fresh mapping does no memset). LNS's window x |V| tables are tens of MB on a large map;
// filling them at once took one refinement step 66 ms (warehouse-20-40-10-2-2), while a
// step only touches the cells of its window's agents.
#include <cstddef>
#include <cstdlib>
#include <new>

namespace planner {

template <class T>
class LazyTable {
 public:
  LazyTable() = default;
  ~LazyTable() { std::free(data_); }
  LazyTable(const LazyTable&) = delete;
  LazyTable& operator=(const LazyTable&) = delete;

  // At least n zero cells; keeps the contents when already large enough, else starts anew
  // (zeroed): callers size it once for their largest use.
  void ensure(size_t n)
  {
    if (n <= size_) return;
    std::free(data_);
    data_ = static_cast<T*>(std::calloc(n, sizeof(T)));
    if (!data_) throw std::bad_alloc();
    size_ = n;
  }
  T& operator[](size_t i) { return data_[i]; }
  const T& operator[](size_t i) const { return data_[i]; }
  size_t size() const { return size_; }

 private:
  T* data_ = nullptr;
  size_t size_ = 0;
};

}  // namespace planner
