#pragma once
// A table of named double columns with one integer run id per row: designs,
// responses and predictions all travel between stages as Tables.
#include <cstdint>
#include <map>
#include <string>
#include <vector>

namespace demcal {

class Table {
 public:
  Table() = default;
  explicit Table(std::vector<int> run_ids) : run_ids_(std::move(run_ids)) {}

  std::size_t rows() const { return run_ids_.size(); }
  std::size_t cols() const { return names_.size(); }
  const std::vector<int>& run_ids() const { return run_ids_; }
  const std::vector<std::string>& names() const { return names_; }

  // Adds a column; its length must equal rows() (the first column of an empty
  // table with no run ids sets rows() and numbers the runs 1..n).
  void add_column(const std::string& name, std::vector<double> values);
  bool has_column(const std::string& name) const;
  // Throws an Error naming the available columns when `name` is absent.
  const std::vector<double>& column(const std::string& name) const;
  std::vector<double>& column(const std::string& name);
  const std::vector<double>& column(std::size_t index) const { return columns_[index]; }
  double at(std::size_t row, const std::string& name) const { return column(name)[row]; }

  // Status of each row when the table has one: the DEM batch's responses say
  // "ok" or "failed: reason" per point. Empty when the table has no status.
  const std::vector<std::string>& statuses() const { return statuses_; }
  void set_statuses(std::vector<std::string> statuses);

  // The rows at `indices` (in that order), with their run ids and statuses.
  Table select_rows(const std::vector<std::size_t>& indices) const;

  // Free-form text metadata (design kind, seed, settings); CSV does not keep it.
  std::map<std::string, std::string>& attributes() { return attributes_; }
  const std::map<std::string, std::string>& attributes() const { return attributes_; }

  // CSV with a header. A first column named "run" holds the run ids; without
  // it the runs are numbered 1..n. A column named "status" is read as text
  // (statuses()); every other column must hold numbers.
  static Table read_csv(const std::string& path);
  void write_csv(const std::string& path) const;

  // HDF5: one group holding a "run" dataset, one dataset per column and the
  // attributes (plus "columns", the column order).
  static Table read_hdf5(const std::string& path, const std::string& group);
  void write_hdf5(const std::string& path, const std::string& group) const;

  // Reads or writes by file extension (.csv, .h5/.hdf5); HDF5 uses `group`.
  static Table read(const std::string& path, const std::string& group = "/design");
  void write(const std::string& path, const std::string& group = "/design") const;

 private:
  std::size_t index_of(const std::string& name) const;

  std::vector<int> run_ids_;
  std::vector<std::string> names_;
  std::vector<std::vector<double>> columns_;
  std::map<std::string, std::string> attributes_;
  std::vector<std::string> statuses_;
};

// True when `path` ends in .h5 or .hdf5.
bool is_hdf5_path(const std::string& path);

}  // namespace demcal
