#include "demcal/doe/galois_field.hpp"

#include "demcal/core/error.hpp"

namespace demcal::doe {
namespace {

using Poly = std::vector<int>;  // coefficients, index = power

Poly digits(int value, int p, int n) {
  Poly poly(static_cast<std::size_t>(n), 0);
  for (int k = 0; k < n; ++k) {
    poly[static_cast<std::size_t>(k)] = value % p;
    value /= p;
  }
  return poly;
}

int from_digits(const Poly& poly, int p) {
  int value = 0;
  for (std::size_t k = poly.size(); k-- > 0;) value = value * p + poly[k];
  return value;
}

// Product of two polynomials of degree < n reduced modulo the monic `modulus`
// of degree n (coefficients mod p).
Poly multiply_mod(const Poly& a, const Poly& b, const Poly& modulus, int p) {
  std::size_t n = modulus.size() - 1;
  Poly product(2 * n, 0);
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = 0; j < n; ++j) product[i + j] = (product[i + j] + a[i] * b[j]) % p;
  for (std::size_t k = product.size(); k-- > n;) {
    int c = product[k];
    if (c == 0) continue;
    for (std::size_t m = 0; m <= n; ++m) {
      std::size_t index = k - n + m;
      product[index] = ((product[index] - c * modulus[m]) % p + p) % p;
    }
  }
  product.resize(n);
  return product;
}

// A monic polynomial of degree n is irreducible iff the multiplication it
// defines has no zero divisors; q is small, so check that directly.
bool irreducible(const Poly& modulus, int p) {
  int n = static_cast<int>(modulus.size()) - 1;
  int q = 1;
  for (int k = 0; k < n; ++k) q *= p;
  for (int a = 1; a < q; ++a)
    for (int b = a; b < q; ++b)
      if (from_digits(multiply_mod(digits(a, p, n), digits(b, p, n), modulus, p), p) == 0) return false;
  return true;
}

}  // namespace

std::pair<int, int> GaloisField::prime_power(int q) {
  if (q < 2) return {0, 0};
  int p = 2;
  while (q % p != 0) ++p;
  int n = 0;
  while (q % p == 0) {
    q /= p;
    ++n;
  }
  return q == 1 ? std::make_pair(p, n) : std::make_pair(0, 0);
}

GaloisField::GaloisField(int q) : q_(q) {
  auto [p, n] = prime_power(q);
  if (p == 0) throw Error("GF(" + std::to_string(q) + ") does not exist: the order must be a prime power");
  if (q > 256) throw Error("GF(" + std::to_string(q) + "): orders above 256 are not supported");
  p_ = p;
  n_ = n;
  add_.resize(static_cast<std::size_t>(q * q));
  mul_.resize(static_cast<std::size_t>(q * q));
  neg_.resize(static_cast<std::size_t>(q));
  inv_.assign(static_cast<std::size_t>(q), 0);

  Poly modulus(static_cast<std::size_t>(n + 1), 0);
  modulus[static_cast<std::size_t>(n)] = 1;
  if (n > 1) {
    bool found = false;
    for (int tail = 0; tail < q && !found; ++tail) {
      Poly low = digits(tail, p, n);
      for (int k = 0; k < n; ++k) modulus[static_cast<std::size_t>(k)] = low[static_cast<std::size_t>(k)];
      found = irreducible(modulus, p);
    }
    if (!found) throw Error("no irreducible polynomial found for GF(" + std::to_string(q) + ")");
  }

  for (int a = 0; a < q; ++a) {
    Poly pa = digits(a, p, n);
    for (int b = 0; b < q; ++b) {
      Poly pb = digits(b, p, n);
      Poly sum(static_cast<std::size_t>(n));
      for (int k = 0; k < n; ++k)
        sum[static_cast<std::size_t>(k)] = (pa[static_cast<std::size_t>(k)] + pb[static_cast<std::size_t>(k)]) % p;
      add_[static_cast<std::size_t>(a * q + b)] = from_digits(sum, p);
      int product = n == 1 ? (a * b) % p : from_digits(multiply_mod(pa, pb, modulus, p), p);
      mul_[static_cast<std::size_t>(a * q + b)] = product;
      if (add_[static_cast<std::size_t>(a * q + b)] == 0) neg_[static_cast<std::size_t>(a)] = b;
      if (product == 1) inv_[static_cast<std::size_t>(a)] = b;
    }
  }
}

int GaloisField::inv(int a) const {
  if (a == 0) throw Error("GF(" + std::to_string(q_) + "): zero has no inverse");
  return inv_[static_cast<std::size_t>(a)];
}

bool GaloisField::is_square(int a) const {
  for (int x = 0; x < q_; ++x)
    if (mul(x, x) == a) return true;
  return false;
}

}  // namespace demcal::doe
