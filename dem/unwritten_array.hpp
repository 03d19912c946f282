#pragma once
// Scratch room for values that are always written before they are read, sized without writing
// them.
//
// Why: a std::vector value-initialises what it grows by, so every page of it is touched, and
// stays resident, even where a step never writes. The two-thread cycle packs each chunk's
// non-zero slip work terms from the start of the chunk's range (dem/threaded_cycle.hpp): a
// frictionless packing writes one term per chunk, so in this array nearly all of its pages stay
// unbacked (the 10^6-disc packing: docs/performance.md "Session 39"). A large block comes from a
// mapping of its own (glibc's threshold, which `cdem` keeps at its default: core/heap_policy.hpp)
// and the kernel backs it page by page as it is written.
#include <cstddef>
#include <memory>
#include <type_traits>
#include <utility>

namespace cdem::dem {

template <class T>
class UnwrittenArray {
  static_assert(std::is_trivially_default_constructible_v<T>);

 public:
  UnwrittenArray() = default;
  // A copy gets room for as many values (an assigned-to array keeps more if it had more),
  // unwritten: the values are scratch, written before they are read.
  UnwrittenArray(const UnwrittenArray& other) { reserve(other.capacity_); }
  UnwrittenArray& operator=(const UnwrittenArray& other) {
    reserve(other.capacity_);
    return *this;
  }
  UnwrittenArray(UnwrittenArray&& other) noexcept
      : data_(std::move(other.data_)), capacity_(std::exchange(other.capacity_, 0)) {}
  UnwrittenArray& operator=(UnwrittenArray&& other) noexcept {
    data_ = std::move(other.data_);
    capacity_ = std::exchange(other.capacity_, 0);
    return *this;
  }

  // Room for at least n values; the values are not kept when it grows.
  void reserve(std::size_t n) {
    if (n <= capacity_) return;
    data_.reset();  // the old block goes back before the new one is mapped
    data_ = std::make_unique_for_overwrite<T[]>(n);
    capacity_ = n;
  }
  T* data() { return data_.get(); }
  const T* data() const { return data_.get(); }
  std::size_t capacity() const { return capacity_; }

 private:
  std::unique_ptr<T[]> data_;
  std::size_t capacity_ = 0;
};

}  // namespace cdem::dem
