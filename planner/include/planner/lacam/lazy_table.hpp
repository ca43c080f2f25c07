#pragma once
// LazyTable: a fixed-size, zero-filled array whose pages the OS maps on first touch (calloc of
// a fresh mapping does no memset). LNS's window x |V| tables are tens of MB on a large map;
// filling them at once took one refinement step 66 ms (warehouse-20-40-10-2-2), while a
// step only touches the cells of its window's agents.
//
// First touches are not free either: each new page is a fault and a zeroed page, about 1 us.
// A table that grew with the window (free, then calloc anew) faulted every page in again in
// one step: 9-15 ms steps at a 10 ms cutoff on warehouse-20-40-10-2-2 N = 1000, one at each
// growth. So a caller reserves its largest size once (reserve(): nothing is touched) and
// commits pages ahead of use in pieces (touch()), in whatever budget it has.
#include <cstddef>
#include <cstdlib>
#include <new>

namespace planner {

template <class T>
class LazyTable {
 public:
  static constexpr size_t kPage = 4096;

  LazyTable() = default;
  ~LazyTable() { std::free(data_); }
  LazyTable(const LazyTable&) = delete;
  LazyTable& operator=(const LazyTable&) = delete;

  // At least n zero cells; keeps the contents when already large enough, else starts anew
  // (zeroed, nothing touched): callers size it once for their largest use.
  void ensure(size_t n)
  {
    if (n <= size_) return;
    std::free(data_);
    data_ = static_cast<T*>(std::calloc(n, sizeof(T)));
    if (!data_) throw std::bad_alloc();
    size_ = n;
    touched_ = 0;
    ++allocations_;
  }
  // Maps the pages of cells [touched(), n) (n <= size()) by writing each page's first cell
  // back unchanged; the contents stay. What was touched before is not touched again.
  void touch(size_t n)
  {
    if (n > size_) n = size_;
    if (n <= touched_) return;
    volatile unsigned char* p = reinterpret_cast<volatile unsigned char*>(data_);
    const size_t base = reinterpret_cast<size_t>(data_);
    const size_t end = n * sizeof(T);
    size_t b = touched_ * sizeof(T);
    p[b] = p[b];  // the page of the first cell, then every page boundary up to the last cell
    for (b = ((base + b) / kPage + 1) * kPage - base; b < end; b += kPage) p[b] = p[b];
    touched_ = n;
  }
  size_t touched() const { return touched_; }  // cells [0, touched()) are mapped
  long allocations() const { return allocations_; }  // callocs so far (tests)
  T& operator[](size_t i) { return data_[i]; }
  const T& operator[](size_t i) const { return data_[i]; }
  size_t size() const { return size_; }

 private:
  T* data_ = nullptr;
  size_t size_ = 0;
  size_t touched_ = 0;
  long allocations_ = 0;
};

}  // namespace planner
