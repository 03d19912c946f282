#pragma once
// Discs, laid out for the contact loop: everything a contact needs sits in per-disc arrays
// (position, radius, velocity of the owning body carried to the disc), so the pair kernel never
// looks at the bodies.
//
// The position, radius, velocity and body-frame offset of a disc share one 64-byte record
// (DiscState), one cache line: the pair pass reads the two discs of a pair by two line loads
// (transposed into lanes by load_records, dem/lanes.hpp) where one array per quantity took six
// gathers per disc, each the cost of eight loads on this machine (docs/performance.md
// "Session 27"), and a disc beyond the cache costs one line from memory instead of six. The
// records are read and written field by field as if they were arrays (d.x[i], d.r[i]: DiscField),
// so code away from the hot loops does not see the layout.
#include <cstddef>
#include <cstdint>
#include <cstring>
#include <iterator>
#include <type_traits>
#include <utility>

#include "dem/staggered_array.hpp"

namespace cdem::dem {

// The material a disc belongs to; a pair's contact class follows from the two materials.
enum class DiscMaterial : std::uint8_t { Mortar = 0, Aggregate = 1 };

// One disc's position, radius, velocity and offset in its body's frame, in this order (the lane
// code reads them by position: DiscState::kX ...).
struct alignas(64) DiscState {
  double x = 0, y = 0;                // m, centre, world frame
  double r = 0;                       // m, radius
  double vx = 0, vy = 0, omega = 0;   // m/s, rad/s: velocity of the disc centre and spin
  double offset_x = 0, offset_y = 0;  // m, centre in the body frame (0 for free discs)

  static constexpr std::size_t kX = 0, kY = 1, kR = 2, kVx = 3, kVy = 4, kOmega = 5, kOffsetX = 6,
                               kOffsetY = 7;
  static constexpr std::size_t kFields = 8;
};
static_assert(sizeof(DiscState) == DiscState::kFields * sizeof(double));

// The contact forces the last force pass put on one disc, and their moment about its centre,
// in one 32-byte record: the pass adds each pair onto both its discs, and with the three sums of
// a disc in one cache line (two discs a line) a pair touches two lines where three arrays took
// six, and adds (fx, fy) as one two-double vector (dem/disc_pair_kernel.hpp add_onto_discs).
struct alignas(32) DiscLoad {
  double fx = 0, fy = 0;  // N
  double moment = 0;      // N m
  double unused = 0;      // pads the record to 32 bytes: never split across two lines

  static constexpr std::size_t kFx = 0, kFy = 1, kMoment = 2;  // positions, for the lanes
  static constexpr std::size_t kFields = 4;
};
static_assert(sizeof(DiscLoad) == DiscLoad::kFields * sizeof(double));

// Sets the records [begin, end) to DiscLoad{} (all bits zero: +0.0 in every field), as one
// memset: written as std::fill over a thread's range, GCC 12 stored the records one by one, 11 %
// of a two-thread pass's samples on C30 (docs/performance.md "Session 42").
inline void clear_loads(DiscLoad* begin, DiscLoad* end) {
  static_assert(std::is_trivially_copyable_v<DiscLoad>);
  std::memset(static_cast<void*>(begin), 0,
              static_cast<std::size_t>(end - begin) * sizeof(DiscLoad));
}

// One field of every record of an array (DiscState, DiscLoad), used as an array of doubles:
// indexed, sized, iterated.
template <class Record, double Record::*kField>
class RecordField {
 public:
  // Steps through one field of consecutive records.
  template <class Value>
  class Iterator {
   public:
    using iterator_category = std::forward_iterator_tag;
    using value_type = double;
    using difference_type = std::ptrdiff_t;
    using pointer = Value*;
    using reference = Value&;

    Iterator() = default;
    explicit Iterator(Value* at) : at_(at) {}
    Value& operator*() const { return *at_; }
    Iterator& operator++() {
      at_ += Record::kFields;
      return *this;
    }
    Iterator operator++(int) {
      Iterator before = *this;
      ++*this;
      return before;
    }
    bool operator==(const Iterator& o) const { return at_ == o.at_; }
    bool operator!=(const Iterator& o) const { return at_ != o.at_; }

   private:
    Value* at_ = nullptr;
  };

  using value_type = double;
  using iterator = Iterator<double>;
  using const_iterator = Iterator<const double>;

  explicit RecordField(StaggeredArray<Record>* records) : records_(records) {}

  double& operator[](std::size_t i) { return (*records_)[i].*kField; }
  const double& operator[](std::size_t i) const { return (*records_)[i].*kField; }
  std::size_t size() const { return records_->size(); }
  bool empty() const { return records_->empty(); }
  Iterator<double> begin() { return Iterator<double>(field(0)); }
  Iterator<double> end() { return Iterator<double>(field(size())); }
  Iterator<const double> begin() const { return Iterator<const double>(field(0)); }
  Iterator<const double> end() const { return Iterator<const double>(field(size())); }
  // Element by element, as std::vector's ==.
  bool operator==(const RecordField& o) const {
    if (size() != o.size()) return false;
    for (std::size_t i = 0; i < size(); ++i)
      if (!((*this)[i] == o[i])) return false;
    return true;
  }

 private:
  // The field of record i, i <= size() (one past the end for end()); records are standard
  // layout, so a field's address plus kFields doubles is the same field of the next record.
  double* field(std::size_t i) const { return &(records_->data()->*kField) + i * Record::kFields; }

  StaggeredArray<Record>* records_;
};

template <double DiscState::*kField>
using DiscField = RecordField<DiscState, kField>;
template <double DiscLoad::*kField>
using LoadField = RecordField<DiscLoad, kField>;

// The arrays of the discs; Discs adds the field views onto them.
struct DiscArrays {
  StaggeredArray<DiscState> state;      // position, radius, velocity, offset: one record per disc
  StaggeredArray<std::int32_t> body;    // owning body
  StaggeredArray<std::uint8_t> active;  // 0: never in contact detection (buried pebble)
  StaggeredArray<DiscMaterial> material;
  // Force and moment (about the disc centre) from the contacts of the last force pass.
  StaggeredArray<DiscLoad> load;
};

struct Discs : DiscArrays {
  // The fields of `state` as arrays (m, m/s, rad/s as in DiscState).
  DiscField<&DiscState::x> x{&state};
  DiscField<&DiscState::y> y{&state};
  DiscField<&DiscState::r> r{&state};
  DiscField<&DiscState::vx> vx{&state};
  DiscField<&DiscState::vy> vy{&state};
  DiscField<&DiscState::omega> omega{&state};
  DiscField<&DiscState::offset_x> offset_x{&state};
  DiscField<&DiscState::offset_y> offset_y{&state};
  // The fields of `load` as arrays (N, N m as in DiscLoad).
  LoadField<&DiscLoad::fx> fx{&load};
  LoadField<&DiscLoad::fy> fy{&load};
  LoadField<&DiscLoad::moment> moment{&load};

  Discs() = default;
  // The arrays are copied or moved; the fields keep viewing this object's records.
  Discs(const Discs& o) : DiscArrays(o) {}
  Discs(Discs&& o) noexcept : DiscArrays(std::move(o)) {}
  Discs& operator=(const Discs& o) {
    DiscArrays::operator=(o);
    return *this;
  }
  Discs& operator=(Discs&& o) noexcept {
    DiscArrays::operator=(std::move(o));
    return *this;
  }

  std::size_t size() const { return state.size(); }
  // Room for n discs in every array, so a world built disc by disc holds no growth slack.
  void reserve(std::size_t n) {
    state.reserve(n);
    load.reserve(n);
    body.reserve(n);
    active.reserve(n);
    material.reserve(n);
  }
};

}  // namespace cdem::dem
