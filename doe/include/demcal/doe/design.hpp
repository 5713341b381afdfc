#pragma once
// A design of experiments: a runs x columns matrix in coded units plus what a
// later stage needs to interpret it (level counts, blank columns, how coded
// values map to natural units, and the generator settings).
#include <Eigen/Dense>

#include <map>
#include <string>
#include <vector>

namespace demcal::doe {

using LevelMatrix = Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic>;

// How coded values map to natural units.
enum class Coding {
  Symmetric,  // -1 -> low, +1 -> high (factorials, OAs, CCD, BBD)
  Unit,       //  0 -> low,  1 -> high (LHS, Sobol)
};

struct Design {
  std::string kind;                  // "oa", "fullfact", "ccd", ...
  std::string description;           // e.g. "L64(3^14): OA(64,21,4,2) collapsed to 3 levels"
  Eigen::MatrixXd coded;             // runs x columns
  std::vector<std::string> columns;  // one name per column
  std::vector<int> levels;           // distinct levels per column; 0 = continuous
  std::vector<bool> blank;           // columns that carry no factor (error columns)
  Coding coding = Coding::Symmetric;
  std::map<std::string, std::string> settings;  // generator settings, kept as HDF5 attributes

  std::size_t runs() const { return static_cast<std::size_t>(coded.rows()); }
  std::size_t width() const { return static_cast<std::size_t>(coded.cols()); }
  std::size_t factors() const;  // columns that are not blank
};

// Level indices 0..s-1 to coded values evenly spread over [-1, 1]
// (2 levels: -1/+1, 3 levels: -1/0/+1).
double coded_level(int index, int levels);
// A design of `coded` with every column a factor named x1..xN holding
// `levels` distinct levels (0 = continuous).
Design make_design(std::string kind, Eigen::MatrixXd coded, int levels, Coding coding = Coding::Symmetric);
// Builds a Symmetric design from a level-index array (level counts per column).
Design design_from_levels(const LevelMatrix& level_indices, const std::vector<int>& levels_per_column,
                          std::string kind, std::string description);

// Names x1..xN.
std::vector<std::string> default_names(std::size_t count);

}  // namespace demcal::doe
