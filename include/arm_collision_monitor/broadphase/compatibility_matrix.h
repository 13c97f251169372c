// The seed's compatibility matrix (MoveIt's allowed-collision matrix): entry (i, j) is true
// when primitives i and j may touch (adjacent links, a gripper and the object it grasps).
#pragma once

#include <cstdint>
#include <vector>

namespace arm_collision_monitor {

/// Symmetric bit matrix over primitive ids. Sized once at start-up; Set() at run time only
/// flips bits (no allocation).
class CompatibilityMatrix {
 public:
  explicit CompatibilityMatrix(std::uint32_t size = 0)
      : size_(size), words_per_row_((size + 63) / 64),
        bits_(static_cast<std::size_t>(size) * words_per_row_, 0) {}

  std::uint32_t size() const { return size_; }

  bool AreCompatible(std::uint32_t a, std::uint32_t b) const {
    return (bits_[Index(a, b)] >> (b % 64)) & 1u;
  }
  /// Row `a` as words_per_row() words, bit b % 64 of word b / 64 for column b (the bits past
  /// size() clear); nullptr when a >= size().
  const std::uint64_t* RowWords(std::uint32_t a) const {
    return a < size_ ? &bits_[Index(a, 0)] : nullptr;
  }
  std::uint32_t words_per_row() const { return words_per_row_; }
  void Set(std::uint32_t a, std::uint32_t b, bool compatible) {
    SetBit(a, b, compatible);
    SetBit(b, a, compatible);
  }

 private:
  std::size_t Index(std::uint32_t row, std::uint32_t col) const {
    return static_cast<std::size_t>(row) * words_per_row_ + col / 64;
  }
  void SetBit(std::uint32_t row, std::uint32_t col, bool value) {
    const std::uint64_t mask = std::uint64_t{1} << (col % 64);
    if (value) {
      bits_[Index(row, col)] |= mask;
    } else {
      bits_[Index(row, col)] &= ~mask;
    }
  }

  std::uint32_t size_;
  std::uint32_t words_per_row_;
  std::vector<std::uint64_t> bits_;
};

}  // namespace arm_collision_monitor
