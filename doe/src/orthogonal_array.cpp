#include "demcal/doe/orthogonal_array.hpp"

#include <algorithm>
#include <sstream>

#include "demcal/core/error.hpp"
#include "demcal/doe/factorial.hpp"
#include "demcal/doe/galois_field.hpp"

namespace demcal::doe {
namespace {

int power(int base, int exponent) {
  int result = 1;
  for (int k = 0; k < exponent; ++k) result *= base;
  return result;
}

// Coordinates of index in GF(q)^m, coordinate 0 slowest.
std::vector<int> row_coordinates(int index, int q, int m) {
  std::vector<int> x(static_cast<std::size_t>(m));
  for (int k = m - 1; k >= 0; --k) {
    x[static_cast<std::size_t>(k)] = index % q;
    index /= q;
  }
  return x;
}

// A difference scheme D(12, 12, 3) over Z3: for any two columns the
// differences of their entries take 0, 1, 2 four times each. Found by a
// clique search over normalised columns; the property is checked in
// tests/doe/test_orthogonal_array.cpp through the strength of L36.
const int kDifferenceScheme12[12][12] = {
    {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0}, {0, 1, 0, 1, 2, 2, 0, 1, 2, 1, 2, 0},
    {0, 0, 2, 2, 2, 1, 1, 0, 0, 1, 2, 1}, {0, 1, 2, 0, 1, 0, 0, 2, 1, 2, 2, 1},
    {0, 2, 0, 2, 1, 2, 1, 0, 1, 2, 1, 0}, {0, 0, 1, 1, 2, 1, 2, 2, 1, 2, 0, 0},
    {0, 2, 0, 0, 0, 1, 2, 2, 2, 1, 1, 1}, {0, 0, 2, 1, 0, 0, 1, 1, 2, 2, 1, 2},
    {0, 1, 1, 2, 1, 0, 2, 0, 2, 1, 0, 2}, {0, 1, 1, 0, 2, 2, 1, 2, 0, 0, 1, 2},
    {0, 2, 2, 1, 1, 2, 2, 1, 0, 0, 0, 1}, {0, 2, 1, 2, 0, 1, 0, 1, 1, 0, 2, 2},
};

}  // namespace

LevelMatrix rao_hamming(int q, int m) {
  if (m < 1) throw Error("Rao-Hamming array needs m >= 1");
  GaloisField field(q);
  int rows = power(q, m);
  // Column representatives: last nonzero coordinate 1, grouped by its position,
  // the coordinates before it enumerated with coordinate 0 fastest.
  std::vector<std::vector<int>> representatives;
  for (int t = 0; t < m; ++t) {
    int prefixes = power(q, t);
    for (int prefix = 0; prefix < prefixes; ++prefix) {
      std::vector<int> c(static_cast<std::size_t>(m), 0);
      int value = prefix;
      for (int k = 0; k < t; ++k) {
        c[static_cast<std::size_t>(k)] = value % q;
        value /= q;
      }
      c[static_cast<std::size_t>(t)] = 1;
      representatives.push_back(c);
    }
  }
  LevelMatrix array(rows, static_cast<Eigen::Index>(representatives.size()));
  for (int r = 0; r < rows; ++r) {
    std::vector<int> x = row_coordinates(r, q, m);
    for (std::size_t j = 0; j < representatives.size(); ++j) {
      int dot = 0;
      for (int k = 0; k < m; ++k)
        dot = field.add(dot, field.mul(x[static_cast<std::size_t>(k)], representatives[j][static_cast<std::size_t>(k)]));
      array(r, static_cast<Eigen::Index>(j)) = dot;
    }
  }
  return array;
}

LevelMatrix bose(int q) {
  GaloisField field(q);
  LevelMatrix array(q * q, q + 1);
  for (int i = 0; i < q; ++i)
    for (int j = 0; j < q; ++j) {
      int r = i * q + j;
      array(r, 0) = i;
      array(r, 1) = j;
      for (int c = 2; c <= q; ++c) array(r, c) = field.add(j, field.mul(i, c - 1));
    }
  return array;
}

LevelMatrix addelman_kempthorne(int q) {
  GaloisField field(q);
  if (field.characteristic() == 2) throw Error("Addelman-Kempthorne construction needs an odd prime power");
  int kay = 0;  // a non-square of the field
  for (int a = 2; a < q && kay == 0; ++a)
    if (!field.is_square(a)) kay = a;
  if (kay == 0) throw Error("no non-square in GF(" + std::to_string(q) + ")");
  int four = field.add(field.add(1, 1), field.add(1, 1));
  int kay_minus_1 = field.sub(kay, 1);
  std::vector<int> b(static_cast<std::size_t>(q), 0), k(static_cast<std::size_t>(q), 0), c(static_cast<std::size_t>(q), 0);
  for (int m = 1; m < q; ++m) {
    b[static_cast<std::size_t>(m)] = field.mul(kay_minus_1, field.inv(field.mul(four, field.mul(kay, m))));
    k[static_cast<std::size_t>(m)] = field.mul(kay, m);
    c[static_cast<std::size_t>(m)] = field.mul(field.mul(field.mul(m, m), kay_minus_1), field.inv(four));
  }
  LevelMatrix array(2 * q * q, 2 * q + 1);
  for (int i = 0; i < q; ++i)
    for (int j = 0; j < q; ++j) {
      int first = i * q + j;
      int second = q * q + first;
      int i2 = field.mul(i, i);
      array(first, 0) = j;
      array(second, 0) = j;
      for (int m = 1; m < q; ++m) {
        int value = field.add(i, field.mul(m, j));
        array(first, m) = value;
        array(second, m) = field.add(value, b[static_cast<std::size_t>(m)]);
      }
      for (int m = 0; m < q; ++m) {
        array(first, q + m) = field.add(field.add(j, field.mul(m, i)), i2);
        array(second, q + m) = field.add(field.add(field.add(j, field.mul(kay, i2)), field.mul(i, k[static_cast<std::size_t>(m)])),
                                         c[static_cast<std::size_t>(m)]);
      }
      array(first, 2 * q) = i;
      array(second, 2 * q) = i;
    }
  return array;
}

LevelMatrix l18() {
  LevelMatrix ak = addelman_kempthorne(3);  // 18 x 7
  LevelMatrix array(18, 8);
  for (int r = 0; r < 18; ++r) {
    array(r, 0) = r < 9 ? 0 : 1;
    for (int j = 0; j < 7; ++j) array(r, j + 1) = ak(r, j);
  }
  return array;
}

LevelMatrix l36() {
  LevelMatrix pb = plackett_burman_levels(12);  // 12 x 11
  LevelMatrix array(36, 23);
  for (int block = 0; block < 12; ++block)
    for (int g = 0; g < 3; ++g) {
      int r = block * 3 + g;
      for (int j = 0; j < 11; ++j) array(r, j) = pb(block, j);
      for (int j = 0; j < 12; ++j) array(r, 11 + j) = (kDifferenceScheme12[block][j] + g) % 3;
    }
  return array;
}

LevelMatrix collapse_levels(const LevelMatrix& array, int levels, int onto) {
  if (onto < 0 || onto >= levels) throw Error("collapse: target level out of range");
  LevelMatrix out = array;
  for (Eigen::Index i = 0; i < out.size(); ++i)
    if (out.data()[i] >= levels) out.data()[i] = onto;
  return out;
}

std::vector<std::pair<int, int>> parse_levels(const std::string& text, int factors) {
  std::vector<std::pair<int, int>> groups;
  std::stringstream stream(text);
  std::string part;
  while (std::getline(stream, part, ',')) {
    std::size_t caret = part.find('^');
    try {
      std::size_t used = 0;
      int level = std::stoi(part.substr(0, caret), &used);
      if (used != (caret == std::string::npos ? part.size() : caret)) throw std::invalid_argument("");
      int count = factors;
      if (caret != std::string::npos) {
        count = std::stoi(part.substr(caret + 1), &used);
        if (used != part.size() - caret - 1) throw std::invalid_argument("");
      }
      groups.emplace_back(level, count);
    } catch (const std::exception&) {
      throw Error("--levels \"" + text + "\": expected a level count (3) or groups like 2^1,3^7");
    }
  }
  if (groups.empty()) throw Error("--levels is empty");
  for (auto [level, count] : groups) {
    if (level < 2) throw Error("--levels: a factor needs at least 2 levels (got " + std::to_string(level) + ")");
    if (count < 1) throw Error("--levels: give the number of factors (--factors N, or LEVELS^N)");
  }
  return groups;
}

namespace {

struct Candidate {
  LevelMatrix array;            // level indices
  std::vector<int> levels;      // per column
  std::string description;
};

// Arrays of `runs` rows, by construction, with their level counts.
std::vector<Candidate> candidates_for(int runs) {
  std::vector<Candidate> out;
  auto add = [&](LevelMatrix a, std::vector<int> levels, std::string text) {
    out.push_back({std::move(a), std::move(levels), std::move(text)});
  };
  for (int q = 2; q <= runs; ++q) {
    if (GaloisField::prime_power(q).first == 0) continue;
    for (int m = 2, n = q * q; n <= runs; ++m, n *= q) {
      if (n != runs) continue;
      LevelMatrix a = (m == 2) ? bose(q) : rao_hamming(q, m);
      int cols = static_cast<int>(a.cols());
      std::string kind = (m == 2) ? "Bose" : "Rao-Hamming";
      add(a, std::vector<int>(static_cast<std::size_t>(cols), q),
          "OA(" + std::to_string(runs) + "," + std::to_string(cols) + "," + std::to_string(q) + ",2), " + kind +
              " over GF(" + std::to_string(q) + ")");
    }
  }
  if (runs == 18) {
    std::vector<int> levels(8, 3);
    levels[0] = 2;
    add(l18(), levels, "L18(2^1 3^7), Addelman-Kempthorne OA(18,7,3,2) with its half indicator");
  }
  if (runs == 36) {
    std::vector<int> levels(23, 3);
    std::fill(levels.begin(), levels.begin() + 11, 2);
    add(l36(), levels, "L36(2^11 3^12), Plackett-Burman 12 x difference scheme D(12,12,3)");
  }
  if (runs % 4 == 0 && runs >= 4) {
    std::vector<int> sizes = plackett_burman_sizes(runs);
    if (std::find(sizes.begin(), sizes.end(), runs) != sizes.end() && (runs & (runs - 1)) != 0)
      add(plackett_burman_levels(runs), std::vector<int>(static_cast<std::size_t>(runs - 1), 2),
          "Plackett-Burman OA(" + std::to_string(runs) + "," + std::to_string(runs - 1) + ",2,2)");
  }
  return out;
}

// Picks `count` columns with `level` levels from the candidate, in order.
bool take_columns(const Candidate& c, int level, int count, std::vector<int>& chosen) {
  for (std::size_t j = 0; j < c.levels.size() && count > 0; ++j) {
    if (c.levels[j] != level) continue;
    if (std::find(chosen.begin(), chosen.end(), static_cast<int>(j)) != chosen.end()) continue;
    chosen.push_back(static_cast<int>(j));
    --count;
  }
  return count == 0;
}

int doubled_target(const std::string& doubled, int levels) {
  if (doubled == "low") return 0;
  if (doubled == "middle") return (levels - 1) / 2;
  if (doubled == "high") return levels - 1;
  throw Error("--doubled-level \"" + doubled + "\": expected low, middle or high");
}

}  // namespace

Design orthogonal_array(const OaRequest& request) {
  if (request.runs < 2) throw Error("oa: --runs must be given (e.g. --runs 9, 18, 27, 36, 64)");
  if (request.levels.empty()) throw Error("oa: --levels must be given");
  if (request.blanks < 0) throw Error("oa: --blank must be >= 0");
  // Blank columns take the level count of the last factor group.
  std::vector<std::pair<int, int>> groups = request.levels;
  if (request.blanks > 0) groups.emplace_back(groups.back().first, request.blanks);
  int total = 0;
  for (auto [level, count] : groups) total += count;

  // 1. A strict orthogonal array.
  for (const Candidate& c : candidates_for(request.runs)) {
    std::vector<int> chosen;
    bool ok = true;
    for (auto [level, count] : groups) ok = ok && take_columns(c, level, count, chosen);
    if (!ok) continue;
    LevelMatrix array(c.array.rows(), static_cast<Eigen::Index>(chosen.size()));
    std::vector<int> levels;
    for (std::size_t j = 0; j < chosen.size(); ++j) {
      array.col(static_cast<Eigen::Index>(j)) = c.array.col(chosen[j]);
      levels.push_back(c.levels[static_cast<std::size_t>(chosen[j])]);
    }
    Design design = design_from_levels(array, levels, "oa", c.description);
    design.settings["construction"] = c.description;
    return design;
  }

  // 2. Collapse a q-level Rao-Hamming array (q = s + 1, a prime power, q^m = runs).
  if (groups.size() == 1 || std::all_of(groups.begin(), groups.end(), [&](auto g) { return g.first == groups[0].first; })) {
    int s = groups[0].first;
    int q = s + 1;
    if (GaloisField::prime_power(q).first != 0) {
      int m = 0;
      for (int n = 1; n < request.runs; n *= q) ++m;
      if (power(q, m) == request.runs && m >= 2) {
        LevelMatrix full = rao_hamming(q, m);
        if (full.cols() >= total) {
          int onto = doubled_target(request.doubled, s);
          LevelMatrix array = collapse_levels(full.leftCols(total), s, onto);
          std::string text = "L" + std::to_string(request.runs) + "(" + std::to_string(s) + "^" + std::to_string(total) +
                             "): OA(" + std::to_string(request.runs) + "," + std::to_string(full.cols()) + "," +
                             std::to_string(q) + ",2) over GF(" + std::to_string(q) + ") with level " +
                             std::to_string(q) + " collapsed onto level " + std::to_string(onto + 1) +
                             " (proportional frequencies)";
          Design design = design_from_levels(array, std::vector<int>(static_cast<std::size_t>(total), s), "oa", text);
          design.settings["construction"] = text;
          design.settings["doubled_level"] = request.doubled;
          return design;
        }
      }
    }
  }

  // Nothing fits: say what would.
  std::ostringstream message;
  message << "oa: no orthogonal array with " << request.runs << " runs holds";
  for (auto [level, count] : groups) message << " " << count << " columns of " << level << " levels";
  int s = groups[0].first;
  message << "; for " << s << "-level factors try --runs";
  std::string sep = " ";
  for (int runs = 4; runs <= 256; ++runs) {
    int best = 0;
    for (const Candidate& c : candidates_for(runs)) {
      int n = static_cast<int>(std::count(c.levels.begin(), c.levels.end(), s));
      best = std::max(best, n);
    }
    int q = s + 1;
    if (best == 0 && GaloisField::prime_power(q).first != 0) {
      for (int n = q * q, m = 2; n <= runs; n *= q, ++m)
        if (n == runs) best = (n - 1) / (q - 1);
    }
    if (best >= total) {
      message << sep << runs << " (up to " << best << " columns)";
      sep = ", ";
    }
  }
  if (sep == " ") message << " (none up to 256 runs)";
  throw Error(message.str());
}

}  // namespace demcal::doe
