#pragma once
// Arithmetic in the finite field GF(q), q = p^n a prime power. Elements are
// the integers 0..q-1, read as polynomials over GF(p) with base-p digits as
// coefficients (digit k is the coefficient of x^k); the field is built modulo
// the first monic irreducible polynomial of degree n in lexicographic order
// (GF(4): x^2 + x + 1). Tables make add/multiply a lookup.
#include <vector>

namespace demcal::doe {

class GaloisField {
 public:
  explicit GaloisField(int q);  // throws unless q is a prime power >= 2

  int order() const { return q_; }
  int characteristic() const { return p_; }
  int degree() const { return n_; }
  int add(int a, int b) const { return add_[a * q_ + b]; }
  int sub(int a, int b) const { return add(a, neg_[b]); }
  int mul(int a, int b) const { return mul_[a * q_ + b]; }
  int neg(int a) const { return neg_[a]; }
  int inv(int a) const;  // throws for 0
  // True when `a` has a square root in the field.
  bool is_square(int a) const;

  // Returns (p, n) with q = p^n, or (0, 0) when q is not a prime power.
  static std::pair<int, int> prime_power(int q);

 private:
  int q_, p_, n_;
  std::vector<int> add_, mul_, neg_, inv_;
};

}  // namespace demcal::doe
