#pragma once
// Full factorials (mixed levels), two-level fractional factorials and
// Plackett-Burman screening designs.
#include <string>
#include <vector>

#include "demcal/doe/design.hpp"

namespace demcal::doe {

// Every combination of the given level counts, first column fastest (Yates
// standard order, as Minitab and MATLAB's fullfact list it).
Design full_factorial(const std::vector<int>& levels);

// 2^(k-p) design. `generators` define the added factors as products of the
// base factors, by letter: {"D=ABC", "E=-AB"} (the left side is optional; a
// leading '-' negates). Letters skip I (A..H, J..Z), as is customary. With no
// generators and `runs` > 0, generators of maximal resolution are chosen
// (fewest shortest words on ties; exhaustive search when small, greedy from
// odd-length words otherwise). The resolution is recorded in
// the design's settings.
Design fractional_factorial(int factors, const std::vector<std::string>& generators, int runs);

// The Hadamard matrix of order n (n = 2^a, 12 * 2^a or 20 * 2^a, and 24) with
// the first column all +1; throws for other n.
LevelMatrix hadamard(int n);

// Plackett-Burman: the smallest N (multiple of 4, N > factors) with a known
// Hadamard matrix, columns 2..factors+1 of it; levels as 0/1.
LevelMatrix plackett_burman_levels(int runs);
Design plackett_burman(int factors, int runs = 0);
// Run counts the Plackett-Burman construction offers up to `limit`.
std::vector<int> plackett_burman_sizes(int limit);

// Letter of factor i (0-based): A..H, J..Z, then x27, x28...
std::string factor_letter(int index);

}  // namespace demcal::doe
