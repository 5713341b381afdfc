#include "demcal/dem/contacts.hpp"

#include <algorithm>
#include <string>

#include "demcal/core/error.hpp"

namespace demcal::dem {

void ContactSet::set_layout(const std::vector<std::size_t>& columns_per_model) {
  clear();
  // The same layout keeps the blocks' storage (the neighbour list reuses its sets).
  bool same = blocks_.size() == columns_per_model.size();
  for (std::size_t m = 0; same && m < blocks_.size(); ++m) same = blocks_[m].columns == columns_per_model[m];
  if (same) return;
  blocks_.assign(columns_per_model.size(), ModelBlock{});
  for (std::size_t m = 0; m < columns_per_model.size(); ++m) {
    if (columns_per_model[m] > kMaxStateColumns)
      throw Error("contact model " + std::to_string(m) + " declares " + std::to_string(columns_per_model[m]) +
                  " state columns (at most " + std::to_string(kMaxStateColumns) + ")");
    blocks_[m].columns = columns_per_model[m];
  }
}

void ContactSet::clear() {
  i.clear();
  j.clear();
  model.clear();
  flags.clear();
  for (ModelBlock& b : blocks_) {
    b.begin = b.count = b.capacity = 0;
    b.state.clear();
  }
}

void ContactSet::reserve(std::size_t n) {
  i.reserve(n);
  j.reserve(n);
  model.reserve(n);
  flags.reserve(n);
}

void ContactSet::assign_blocks(const std::vector<std::size_t>& pairs_per_model) {
  if (pairs_per_model.size() > blocks_.size())
    throw Error("contact set: model " + std::to_string(pairs_per_model.size() - 1) + " has no state layout");
  clear();
  std::size_t total = 0;
  for (std::size_t m = 0; m < pairs_per_model.size(); ++m) {
    ModelBlock& block = blocks_[m];
    block.count = block.capacity = pairs_per_model[m];
    block.begin = block.count ? total : 0;  // as add() leaves an empty block
    block.state.assign(block.count * block.columns, 0.0);
    model.insert(model.end(), block.count, static_cast<std::uint8_t>(m));
    total += block.count;
  }
  i.assign(total, 0);
  j.assign(total, 0);
  flags.assign(total, 0);
}

std::size_t ContactSet::add(std::int32_t a, std::int32_t b, std::uint8_t model_index) {
  if (model_index >= blocks_.size())
    throw Error("contact set: model " + std::to_string(model_index) + " has no state layout");
  if (!model.empty() && model.back() > model_index) throw Error("contact set: pairs must be added in model order");
  ModelBlock& block = blocks_[model_index];
  if (block.count == 0) block.begin = i.size();
  if (block.count == block.capacity) {
    // Every column twice as long, in the same vector (whose storage a
    // cleared set keeps, so a rebuild's wall pairs allocate nothing new once
    // warm): the columns move up from the last one down, each to at or beyond
    // where it was (so the copies may overlap), and the new ends are zeroed.
    const std::size_t capacity = std::max<std::size_t>(16, 2 * block.capacity);
    block.state.resize(capacity * block.columns, 0.0);
    double* const state = block.state.data();
    for (std::size_t c = block.columns; c-- > 0;) {
      double* const column = state + c * capacity;
      if (c > 0) std::copy_backward(state + c * block.capacity, state + c * block.capacity + block.count,
                                    column + block.count);  // column 0 stays where it is
      std::fill(column + block.count, column + capacity, 0.0);
    }
    block.capacity = capacity;
  }
  ++block.count;
  i.push_back(a);
  j.push_back(b);
  model.push_back(model_index);
  flags.push_back(0);
  return i.size() - 1;
}

void ContactSet::copy_state(std::size_t to, const ContactSet& other, std::size_t from) {
  flags[to] = other.flags[from];
  const ModelBlock& source = other.blocks_[other.model[from]];
  ModelBlock& target = blocks_[model[to]];
  const double* in = source.state.data() + (from - source.begin);
  double* out = target.state.data() + (to - target.begin);
  for (std::size_t c = 0; c < target.columns; ++c) out[c * target.capacity] = in[c * source.capacity];
}

std::size_t ContactSet::begin(std::uint8_t m) const { return m < blocks_.size() ? blocks_[m].begin : 0; }

std::size_t ContactSet::end(std::uint8_t m) const {
  return m < blocks_.size() ? blocks_[m].begin + blocks_[m].count : 0;
}

double ContactSet::state(std::size_t k, std::size_t c) const {
  const ModelBlock& b = blocks_[model[k]];
  return b.state[c * b.capacity + (k - b.begin)];
}

double& ContactSet::state(std::size_t k, std::size_t c) {
  ModelBlock& b = blocks_[model[k]];
  return b.state[c * b.capacity + (k - b.begin)];
}

namespace {

template <typename Block, typename Set, typename Blocks>
Block make_block(Set& set, Blocks& blocks, std::uint8_t m) {
  Block out;
  if (m >= blocks.size()) return out;
  auto& b = blocks[m];
  out.size = b.count;
  out.i = set.i.data() + b.begin;
  out.j = set.j.data() + b.begin;
  out.flags = set.flags.data() + b.begin;
  out.column.data = b.state.data();
  out.column.column_stride = b.capacity;
  out.column.columns = b.columns;
  return out;
}

}  // namespace

PairBlock ContactSet::block(std::uint8_t m) { return make_block<PairBlock>(*this, blocks_, m); }

ConstPairBlock ContactSet::block(std::uint8_t m) const { return make_block<ConstPairBlock>(*this, blocks_, m); }

}  // namespace demcal::dem
