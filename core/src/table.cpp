#include "demcal/core/table.hpp"

#include <numeric>

#include "demcal/core/error.hpp"

namespace demcal {

void Table::add_column(const std::string& name, std::vector<double> values) {
  if (name.empty()) throw Error("table: a column needs a name");
  if (name == "run") throw Error("table: \"run\" is reserved for the run ids");
  if (has_column(name)) throw Error("table: column \"" + name + "\" already exists");
  if (names_.empty() && run_ids_.empty()) {
    run_ids_.resize(values.size());
    std::iota(run_ids_.begin(), run_ids_.end(), 1);
  }
  if (values.size() != run_ids_.size())
    throw Error("table: column \"" + name + "\" has " + std::to_string(values.size()) + " rows, the table has " +
                std::to_string(run_ids_.size()));
  names_.push_back(name);
  columns_.push_back(std::move(values));
}

void Table::set_statuses(std::vector<std::string> statuses) {
  if (!statuses.empty() && statuses.size() != run_ids_.size())
    throw Error("table: " + std::to_string(statuses.size()) + " statuses for " + std::to_string(run_ids_.size()) + " rows");
  statuses_ = std::move(statuses);
}

Table Table::select_rows(const std::vector<std::size_t>& indices) const {
  std::vector<int> runs;
  for (std::size_t i : indices) runs.push_back(run_ids_.at(i));
  Table out(runs);
  for (std::size_t c = 0; c < names_.size(); ++c) {
    std::vector<double> values;
    for (std::size_t i : indices) values.push_back(columns_[c][i]);
    out.add_column(names_[c], std::move(values));
  }
  if (!statuses_.empty()) {
    std::vector<std::string> statuses;
    for (std::size_t i : indices) statuses.push_back(statuses_[i]);
    out.set_statuses(std::move(statuses));
  }
  out.attributes_ = attributes_;
  return out;
}

bool Table::has_column(const std::string& name) const {
  for (const auto& n : names_)
    if (n == name) return true;
  return false;
}

std::size_t Table::index_of(const std::string& name) const {
  for (std::size_t i = 0; i < names_.size(); ++i)
    if (names_[i] == name) return i;
  std::string list;
  for (const auto& n : names_) list += (list.empty() ? "" : ", ") + n;
  throw Error("table: no column \"" + name + "\" (columns: " + list + ")");
}

const std::vector<double>& Table::column(const std::string& name) const { return columns_[index_of(name)]; }
std::vector<double>& Table::column(const std::string& name) { return columns_[index_of(name)]; }

bool is_hdf5_path(const std::string& path) {
  auto ends_with = [&](const std::string& suffix) {
    return path.size() >= suffix.size() && path.compare(path.size() - suffix.size(), suffix.size(), suffix) == 0;
  };
  return ends_with(".h5") || ends_with(".hdf5");
}

Table Table::read(const std::string& path, const std::string& group) {
  return is_hdf5_path(path) ? read_hdf5(path, group) : read_csv(path);
}

void Table::write(const std::string& path, const std::string& group) const {
  if (is_hdf5_path(path))
    write_hdf5(path, group);
  else
    write_csv(path);
}

}  // namespace demcal
