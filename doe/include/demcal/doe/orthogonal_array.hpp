#pragma once
// Orthogonal arrays of strength 2 and the 64-run three-level plan.
//
// Level matrices hold level indices 0..s-1, rows x columns.
#include <string>
#include <vector>

#include "demcal/doe/design.hpp"

namespace demcal::doe {

// Rao-Hamming OA(q^m, (q^m-1)/(q-1), q, 2) over GF(q): rows are all x in
// GF(q)^m (x_0 slowest), columns one representative c of each 1-D subspace,
// entry x.c. Column order follows Taguchi's (basic columns, then their
// interactions: L8 = A B AB C AC BC ABC).
LevelMatrix rao_hamming(int q, int m);

// Bose OA(q^2, q+1, q, 2): col 0 = i, col 1 = j, col c = j + (c-1) i.
LevelMatrix bose(int q);

// Addelman-Kempthorne OA(2q^2, 2q+1, q, 2) for odd prime powers q.
LevelMatrix addelman_kempthorne(int q);

// Taguchi's L18 (2^1 3^7): a two-level column followed by seven three-level
// columns (the two halves of the Addelman-Kempthorne OA(18, 7, 3, 2)).
LevelMatrix l18();

// L36 (2^11 3^12): eleven two-level columns (the Plackett-Burman 12-run
// array on the 12 blocks) followed by twelve three-level columns from a
// difference scheme D(12, 12, 3) developed over Z3.
LevelMatrix l36();

// Maps every level >= `levels` onto `onto`: collapses a q-level column to
// fewer levels (OA(64, 21, 4, 2) -> 3 levels with frequencies 32/16/16 when
// onto = 0). Proportional frequencies keep the main effects orthogonal.
LevelMatrix collapse_levels(const LevelMatrix& array, int levels, int onto);

struct OaRequest {
  int runs = 0;
  // Level counts per factor group, e.g. {{3, 14}} or {{2, 1}, {3, 7}}.
  std::vector<std::pair<int, int>> levels;
  int blanks = 0;                  // extra columns left without a factor (error columns)
  std::string doubled = "low";     // which level takes the collapsed ones: low, middle, high
};

// Picks the array that holds the request: a strict OA when one exists
// (Rao-Hamming/Bose, L18, L36, Plackett-Burman), else a collapsed
// Rao-Hamming array over the next prime power (the 64-run 3-level plan).
// Throws an Error that lists the reachable run counts otherwise.
Design orthogonal_array(const OaRequest& request);

// Parses "3", "3^14" or "2^1,3^7" into level groups; `factors` fills a bare
// level count.
std::vector<std::pair<int, int>> parse_levels(const std::string& text, int factors);

}  // namespace demcal::doe
