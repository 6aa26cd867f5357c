#pragma once
// A growable array that does not initialise what it allocates, so that large per-frame outputs
// are written once (by the pass that fills them) and reused across frames without reallocation.

#include <cstddef>
#include <memory>
#include <span>
#include <type_traits>

namespace lightsampler {

template <class T>
class Buffer {
  static_assert(std::is_trivially_copyable_v<T>);

 public:
  /// Sets the size; contents are unspecified where the buffer grew. Growth leaves 1/64 of room:
  /// a frame's sample count varies from frame to frame (stochastic rounding), and a buffer sized
  /// exactly would be reallocated, and its pages faulted in again, whenever it grows a little.
  void resize(std::size_t n) {
    if (n > capacity_) {
      const std::size_t capacity = n + n / 64;
      data_.reset(new T[capacity]);
      capacity_ = capacity;
    }
    size_ = n;
  }

  std::size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }
  T* data() { return data_.get(); }
  const T* data() const { return data_.get(); }
  T& operator[](std::size_t i) { return data_[i]; }
  const T& operator[](std::size_t i) const { return data_[i]; }
  T* begin() { return data(); }
  T* end() { return data() + size_; }
  const T* begin() const { return data(); }
  const T* end() const { return data() + size_; }
  std::span<T> span() { return {data(), size_}; }
  std::span<const T> span() const { return {data(), size_}; }

 private:
  std::unique_ptr<T[]> data_;
  std::size_t size_ = 0;
  std::size_t capacity_ = 0;
};

}  // namespace lightsampler
