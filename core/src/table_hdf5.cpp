// HDF5 reading and writing of a Table (one group per table).
#include <limits>
#include <sstream>

#include "demcal/core/error.hpp"
#include "demcal/core/hdf5_file.hpp"
#include "demcal/core/number_format.hpp"
#include "demcal/core/table.hpp"

namespace demcal {

void Table::write_hdf5(const std::string& path, const std::string& group_name) const {
  // HDF5 reads '/' in a dataset name as a path: a ratio column A/B has to go to CSV.
  for (const std::string& name : names_)
    if (name.find('/') != std::string::npos)
      throw Error(path + ": column \"" + name + "\" holds a '/', which an HDF5 dataset name cannot; write a .csv");
  h5::File file(path, h5::Mode::OpenOrCreate);
  file.remove(group_name);
  h5::Group group = file.group(group_name, true);
  std::vector<std::int64_t> runs(run_ids_.begin(), run_ids_.end());
  group.write("run", runs);
  std::string order;
  for (std::size_t i = 0; i < names_.size(); ++i) {
    if (names_[i].find('\n') != std::string::npos) throw Error("table: column names cannot hold a line break");
    group.write(names_[i], columns_[i]);
    order += (i ? "\n" : "") + names_[i];
  }
  group.set_attribute("columns", order);
  for (const auto& [key, value] : attributes_) {
    if (key == "columns") throw Error("table: attribute name \"columns\" is reserved");
    group.set_attribute(key, value);
  }
  file.flush();
}

Table Table::read_hdf5(const std::string& path, const std::string& group_name) {
  h5::File file(path, h5::Mode::ReadOnly);
  h5::Group group = file.group(group_name, false);
  std::vector<std::string> names;
  if (group.has_attribute("columns")) {
    std::istringstream in(group.string_attribute("columns"));
    for (std::string name; std::getline(in, name);)
      if (!name.empty()) names.push_back(name);
  } else {
    for (const auto& child : group.children())
      if (child != "run") names.push_back(child);
  }
  std::vector<int> runs;
  if (group.has("run")) {
    for (std::int64_t r : group.read_integers("run")) {
      if (r < 0 || r > std::numeric_limits<int>::max())
        throw Error(path + ": " + group_name + "/run: run id " + std::to_string(r) + " is out of range");
      runs.push_back(static_cast<int>(r));
    }
  }
  Table table(runs);
  for (const auto& name : names) {
    try {
      table.add_column(name, group.read_doubles(name));
    } catch (const Error& e) {
      throw Error(path + ": " + group_name + ": " + e.what());  // a column of another length
    }
  }
  for (const auto& attribute : group.attribute_names()) {
    if (attribute == "columns") continue;
    try {
      table.attributes_[attribute] = group.string_attribute(attribute);
    } catch (const Error&) {
      // Numeric attributes written by other tools are kept as text.
      table.attributes_[attribute] = format_double(group.double_attribute(attribute));
    }
  }
  return table;
}

}  // namespace demcal
