#include "demcal/surrogate/sensitivity.hpp"

#include <cmath>

#include <Eigen/Dense>

#include "demcal/core/error.hpp"
#include "demcal/core/rng.hpp"
#include "demcal/doe/space_filling.hpp"

namespace demcal::surrogate {

namespace {

std::vector<double> natural_point(const Model& model, const double* unit) {
  const std::vector<InputRange>& box = model.domain();
  std::vector<double> x(box.size());
  for (std::size_t i = 0; i < box.size(); ++i) x[i] = box[i].low + unit[i] * (box[i].high - box[i].low);
  return x;
}

void require_box(const Model& model) {
  for (const InputRange& r : model.domain())
    if (!(r.high > r.low)) throw Error("sensitivity: input " + r.name + " has an empty range in the model's domain");
}

double standard_deviation(const std::vector<double>& v) {
  if (v.size() < 2) return 0.0;
  double mean = 0.0;
  for (double x : v) mean += x;
  mean /= static_cast<double>(v.size());
  double ss = 0.0;
  for (double x : v) ss += (x - mean) * (x - mean);
  return std::sqrt(ss / static_cast<double>(v.size() - 1));
}

}  // namespace

std::vector<SobolIndices> sobol_indices(const Model& model, int base_samples, std::uint64_t seed, int bootstrap) {
  require_box(model);
  if (base_samples < 16) throw Error("sobol: --samples must be at least 16");
  const int k = static_cast<int>(model.inputs().size()), o = static_cast<int>(model.outputs().size());
  const Eigen::MatrixXd base = doe::sobol(base_samples, 2 * k, seed).coded;  // columns 0..k-1: A, k..2k-1: B
  const int N = base_samples;
  // f[c](i, out): c = 0 for A, 1 for B, 2 + j for A with column j from B.
  std::vector<Eigen::MatrixXd> f(static_cast<std::size_t>(k + 2), Eigen::MatrixXd(N, o));
  std::vector<double> unit(static_cast<std::size_t>(k)), y(static_cast<std::size_t>(o));
  for (int i = 0; i < N; ++i) {
    for (int c = 0; c < k + 2; ++c) {
      for (int j = 0; j < k; ++j) {
        bool from_b = c == 1 || (c >= 2 && c - 2 == j);
        unit[static_cast<std::size_t>(j)] = base(i, from_b ? k + j : j);
      }
      model.predict(natural_point(model, unit.data()).data(), y.data());
      for (int out = 0; out < o; ++out) f[static_cast<std::size_t>(c)](i, out) = y[static_cast<std::size_t>(out)];
    }
  }
  auto estimate = [&](const std::vector<int>& rows, int out, int j, double& s1, double& st) {
    double mean = 0.0, m2 = 0.0, a = 0.0, b = 0.0;
    for (int i : rows) mean += f[0](i, out) + f[1](i, out);
    mean /= 2.0 * static_cast<double>(rows.size());
    for (int i : rows) m2 += std::pow(f[0](i, out) - mean, 2) + std::pow(f[1](i, out) - mean, 2);
    double variance = m2 / (2.0 * static_cast<double>(rows.size()));
    for (int i : rows) {
      double fa = f[0](i, out), fb = f[1](i, out), fab = f[static_cast<std::size_t>(2 + j)](i, out);
      a += (fb - mean) * (fab - fa);  // centred: same expectation, far less variance
      b += (fa - fab) * (fa - fab);
    }
    s1 = a / static_cast<double>(rows.size()) / variance;
    st = 0.5 * b / static_cast<double>(rows.size()) / variance;
    return variance;
  };
  std::vector<int> all(static_cast<std::size_t>(N));
  for (int i = 0; i < N; ++i) all[static_cast<std::size_t>(i)] = i;
  Rng rng(seed, 0xb007);
  std::vector<SobolIndices> result;
  for (int out = 0; out < o; ++out) {
    SobolIndices s;
    s.output = model.outputs()[static_cast<std::size_t>(out)];
    s.inputs = model.inputs();
    s.evaluations = N * (k + 2);
    for (int j = 0; j < k; ++j) {
      double s1 = 0.0, st = 0.0;
      s.variance = estimate(all, out, j, s1, st);
      if (!(s.variance > 0)) throw Error("sobol: output " + s.output + " does not vary over the domain");
      std::vector<double> s1_boot, st_boot;
      for (int r = 0; r < bootstrap; ++r) {
        std::vector<int> rows(static_cast<std::size_t>(N));
        for (int& row : rows) row = static_cast<int>(rng.below(static_cast<std::uint64_t>(N)));
        double b1 = 0.0, bt = 0.0;
        estimate(rows, out, j, b1, bt);
        s1_boot.push_back(b1);
        st_boot.push_back(bt);
      }
      s.first.push_back(s1);
      s.total.push_back(st);
      s.first_conf.push_back(1.959963984540054 * standard_deviation(s1_boot));
      s.total_conf.push_back(1.959963984540054 * standard_deviation(st_boot));
    }
    result.push_back(s);
  }
  return result;
}

std::vector<MorrisIndices> morris_indices(const Model& model, int trajectories, std::uint64_t seed, int levels) {
  require_box(model);
  if (trajectories < 2) throw Error("morris: --trajectories must be at least 2");
  if (levels < 2 || levels % 2 != 0) throw Error("morris: the number of grid levels must be even and >= 2");
  const int k = static_cast<int>(model.inputs().size()), o = static_cast<int>(model.outputs().size());
  const double delta = levels / (2.0 * (levels - 1));
  Rng rng(seed, 0x303215);
  // effects[out][j]: one elementary effect per trajectory.
  std::vector<std::vector<std::vector<double>>> effects(
      static_cast<std::size_t>(o), std::vector<std::vector<double>>(static_cast<std::size_t>(k)));
  std::vector<double> unit(static_cast<std::size_t>(k)), before(static_cast<std::size_t>(o)),
      after(static_cast<std::size_t>(o));
  int evaluations = 0;
  for (int t = 0; t < trajectories; ++t) {
    for (double& u : unit) u = static_cast<double>(rng.below(static_cast<std::uint64_t>(levels))) / (levels - 1);
    std::vector<int> order(static_cast<std::size_t>(k));
    for (int j = 0; j < k; ++j) order[static_cast<std::size_t>(j)] = j;
    rng.shuffle(order);
    model.predict(natural_point(model, unit.data()).data(), before.data());
    ++evaluations;
    for (int j : order) {
      double step = unit[static_cast<std::size_t>(j)] + delta <= 1.0 + 1e-12 ? delta : -delta;
      unit[static_cast<std::size_t>(j)] += step;
      model.predict(natural_point(model, unit.data()).data(), after.data());
      ++evaluations;
      for (int out = 0; out < o; ++out)
        effects[static_cast<std::size_t>(out)][static_cast<std::size_t>(j)].push_back(
            (after[static_cast<std::size_t>(out)] - before[static_cast<std::size_t>(out)]) / step);
      before = after;
    }
  }
  std::vector<MorrisIndices> result;
  for (int out = 0; out < o; ++out) {
    MorrisIndices m;
    m.output = model.outputs()[static_cast<std::size_t>(out)];
    m.inputs = model.inputs();
    m.evaluations = evaluations;
    for (int j = 0; j < k; ++j) {
      const std::vector<double>& ee = effects[static_cast<std::size_t>(out)][static_cast<std::size_t>(j)];
      double mu = 0.0, mu_star = 0.0;
      for (double e : ee) {
        mu += e;
        mu_star += std::fabs(e);
      }
      m.mu.push_back(mu / static_cast<double>(ee.size()));
      m.mu_star.push_back(mu_star / static_cast<double>(ee.size()));
      m.sigma.push_back(standard_deviation(ee));
    }
    result.push_back(m);
  }
  return result;
}

}  // namespace demcal::surrogate
