#pragma once
// Pairs that may touch (within the neighbour-list skin) as contiguous arrays,
// and each contact model's own per-pair state: the same for disks and spheres.
//
// Pairs are kept sorted by model, so the pairs of one model form one block
// [begin(m), end(m)). A model declares the state columns it keeps per pair
// (ContactModel::state_columns, as LAMMPS pair styles declare their history);
// the set stores exactly those columns for exactly that model's pairs. No
// model sees another's state, and a new model with its own history needs no
// change here.
//
// Disk-disk pairs: j is a disk index. Disk-wall pairs live in a second set
// where j is a wall index. A pair in the list is not necessarily touching:
// its model decides from the overlap each step.
#include <cstdint>
#include <type_traits>
#include <vector>

namespace demcal::dem {

// Per-pair flags. Not a character type on purpose: a store through a
// uint8_t* may alias anything, so the compiler would reload every pointer of
// the force loop after each flag update.
using PairFlags = std::uint32_t;

enum ContactFlags : PairFlags {
  kTouching = 1,   // overlapped in the last step
  kBonded = 2,     // an intact bond (contact or parallel)
};

enum class BreakMode : std::uint8_t { Tension = 0, Shear = 1 };

struct BreakEvent {
  double time_s;
  double x_m, y_m;
  BreakMode mode;
  std::uint8_t group_i, group_j;
  double z_m = 0;  // 0 in 2D
};

// Most state columns one model may declare (a 3D flat joint of 12 elements
// declares 89).
constexpr std::size_t kMaxStateColumns = 96;

// State column c of a block's pairs: pair k's value is base[k].
template <typename T>
struct StateColumn {
  T* base = nullptr;
  T& operator[](std::size_t k) const { return base[k]; }
};

// One pair's state: column c is s[c].
template <typename T>
struct PairState {
  T* base = nullptr;  // the pair's value in column 0
  std::size_t column_stride = 0;
  T& operator[](std::size_t c) const { return base[c * column_stride]; }
};

// A model's state, one array per column, the columns end to end: column c of
// pair k is data[c * column_stride + k]. A batch loop over consecutive pairs
// (pair_batch.hpp) then reads and writes each column as full vectors; with
// the columns of a pair side by side, every lane was a load or store of its
// own.
template <typename T>
struct StateColumns {
  T* data = nullptr;
  std::size_t column_stride = 0;  // values per column (at least the block's pairs)
  std::size_t columns = 0;
  StateColumn<T> operator[](std::size_t c) const { return {data + c * column_stride}; }
  PairState<T> pair(std::size_t k) const { return {data + k, column_stride}; }
  // Column c of pair k. A batch loop indexes one view made outside the loop:
  // a struct made inside an `omp simd` loop becomes an array per lane and
  // stops the loop from vectorising.
  T& operator()(std::size_t c, std::size_t k) const { return data[c * column_stride + k]; }
  // The pairs from `from` on, as pairs 0, 1, ...
  StateColumns from(std::size_t first) const { return {data + first, column_stride, columns}; }
};

// One model's pairs seen with local indices 0..size-1: what a model's force
// loop works on. column[c][k] is state column c of the block's pair k.
template <typename T>
struct BasicPairBlock {
  using Flag = std::conditional_t<std::is_const_v<T>, const PairFlags, PairFlags>;
  std::size_t size = 0;
  const std::int32_t* i = nullptr;
  const std::int32_t* j = nullptr;
  Flag* flags = nullptr;
  StateColumns<T> column;

  // Pairs [from, to) of this block as a block of their own (local index 0 is
  // pair `from`): how threads share one model's pairs.
  BasicPairBlock slice(std::size_t from, std::size_t to) const {
    BasicPairBlock part = *this;
    part.size = to - from;
    part.i = i + from;
    part.j = j + from;
    part.flags = flags + from;
    if (part.column.data) part.column.data += from;
    return part;
  }
};
using PairBlock = BasicPairBlock<double>;
using ConstPairBlock = BasicPairBlock<const double>;

class ContactSet {
 public:
  std::vector<std::int32_t> i, j;
  std::vector<std::uint8_t> model;   // index into the world's model table
  std::vector<PairFlags> flags;

  // The number of state columns of each model index; the set is emptied.
  void set_layout(const std::vector<std::size_t>& columns_per_model);
  std::size_t size() const { return i.size(); }
  void clear();
  void reserve(std::size_t n);
  // Empties the set and makes pairs_per_model[m] pairs of each model index
  // m, in model order, with zero state and flags and i = j = 0, for the
  // caller to fill in (as many add() calls would, at once).
  void assign_blocks(const std::vector<std::size_t>& pairs_per_model);
  // Appends a pair with every state value zero. Pairs must come in
  // non-decreasing model order (the neighbour list's sort order).
  std::size_t add(std::int32_t a, std::int32_t b, std::uint8_t model_index);
  // Copies flags and state of pair `from` of `other` (same model) into pair `to`.
  void copy_state(std::size_t to, const ContactSet& other, std::size_t from);

  // The pairs of model m are [begin(m), end(m)).
  std::size_t begin(std::uint8_t m) const;
  std::size_t end(std::uint8_t m) const;
  // State column c of pair k (a column of pair k's own model).
  double state(std::size_t k, std::size_t c) const;
  double& state(std::size_t k, std::size_t c);

  // Model m's pairs with local indices (pair begin(m) + k is the block's k).
  PairBlock block(std::uint8_t m);
  ConstPairBlock block(std::uint8_t m) const;

 private:
  struct ModelBlock {
    std::size_t begin = 0, count = 0;
    std::size_t columns = 0;
    std::size_t capacity = 0;   // values per column: column c of pair k is state[c * capacity + k]
    std::vector<double> state;  // `columns` columns of `capacity` values
  };
  std::vector<ModelBlock> blocks_;
};

}  // namespace demcal::dem
