#pragma once
// A fixed-length array of plain values in anonymous memory that the kernel fills with zeros page
// by page when it is first touched: an array far larger than what a run uses costs address space
// only. The unbounded medium's cell heads live in one (a zero head means "not made"), as many as
// a 32766^2 grid, of which a run touches the few near its front. Dense arrays (a box's cell
// heads, filled at once) ask for huge pages as HugeVector does; sparse ones forbid them, or every
// touched cell would bring in 2 MiB.
#include <sys/mman.h>

#include <cstddef>
#include <new>
#include <type_traits>
#include <utility>

namespace gs {

enum class Touch { Dense, Sparse };

template <class T>
class ZeroPages {
  static_assert(std::is_trivially_copyable_v<T>);

 public:
  ZeroPages() = default;
  ZeroPages(std::size_t n, Touch touch) : size_(n) {
    if (n == 0) return;
    bytes_ = n * sizeof(T);
    // No swap is reserved for pages never touched (Linux's overcommit heuristic would refuse a
    // reservation of several GB that a run will never use).
    void* p = ::mmap(nullptr, bytes_, PROT_READ | PROT_WRITE,
                     MAP_PRIVATE | MAP_ANONYMOUS | MAP_NORESERVE, -1, 0);
    if (p == MAP_FAILED) throw std::bad_alloc();
    ::madvise(p, bytes_, touch == Touch::Dense ? MADV_HUGEPAGE : MADV_NOHUGEPAGE);  // a hint
    data_ = static_cast<T*>(p);
  }
  ZeroPages(ZeroPages&& o) noexcept { swap(o); }
  ZeroPages& operator=(ZeroPages&& o) noexcept {
    ZeroPages(std::move(o)).swap(*this);
    return *this;
  }
  ZeroPages(const ZeroPages&) = delete;
  ZeroPages& operator=(const ZeroPages&) = delete;
  ~ZeroPages() {
    if (data_) ::munmap(data_, bytes_);
  }

  std::size_t size() const { return size_; }
  T* data() { return data_; }
  const T* data() const { return data_; }
  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }

 private:
  void swap(ZeroPages& o) noexcept {
    std::swap(data_, o.data_);
    std::swap(size_, o.size_);
    std::swap(bytes_, o.bytes_);
  }

  T* data_ = nullptr;
  std::size_t size_ = 0, bytes_ = 0;
};

}  // namespace gs
