#include "shoremesh/parameters.hpp"

#include <cmath>
#include <string>

#include "shoremesh/error.hpp"

namespace shoremesh {


template <int D>
DerivedParameters<D> DerivedParameters<D>::derive(const Parameters<D>& p) {
  if (!std::isfinite(p.rho) || p.rho <= 1.0)
    throw ParameterError("rho must be a finite number greater than 1 (got " + readable(p.rho) + ")");
  if (p.rho < 1.05)
    throw ParameterError("rho below 1.05 asks for an unbounded number of Steiner points in practice (got " +
                         readable(p.rho) + ")");
  if (!std::isfinite(p.beta) || p.beta <= p.rho)
    throw ParameterError("beta must be greater than rho (got beta " + readable(p.beta) + ", rho " +
                         readable(p.rho) + ")");
  if (!(p.steiner_aim >= 1.0))
    throw ParameterError("steiner_aim must be at least 1 (got " + readable(p.steiner_aim) + ")");
  DerivedParameters<D> d;
  d.rho = p.rho;
  // The canonical rho^2: 2 exactly for the default rho = sqrt(2), so "is v well-spaced" is a polynomial
  // test on the input coordinates; any other rho is taken as the double nearest rho*rho.
  d.rho_squared = (p.rho == std::sqrt(2.0)) ? 2.0 : p.rho * p.rho;
  d.fill_rho_squared = d.rho_squared * (1 + 0x1p-32);
  d.beta = p.beta;
  d.beta_squared = p.beta * p.beta;
  // Lemma 6.1: same-rank fills of one colour are independent when l(r) < rho^r/sqrt(d) and
  // kappa > 1 + 3 beta rho^(r+1) / l(r) = 1 + 3 sqrt(d) beta rho^(3/2) with l(r) = rho^(r-1/2)/sqrt(d).
  const double bound = 1.0 + 3.0 * std::sqrt(double(D)) * p.beta * std::pow(p.rho, 1.5);
  if (std::pow(std::ceil(bound), D) > 1e7)
    throw ParameterError("rho " + readable(p.rho) + " is too large: its colour tiles (Lemma 6.1) would number over 10^7; "
                         "choose a smaller rho");
  int kappa = int(std::ceil(bound));
  if (double(kappa) <= bound) ++kappa;  // strict inequality
  if (p.kappa != 0) {
    if (double(p.kappa) <= bound)
      throw ParameterError("kappa = " + std::to_string(p.kappa) + " colours per axis break Lemma 6.1: it must exceed " +
                           readable(bound) + " for rho " + readable(p.rho) + " and beta " +
                           readable(p.beta));
    kappa = p.kappa;
  }
  if (std::pow(double(kappa), D) > 1e7)
    throw ParameterError("kappa = " + std::to_string(kappa) + " gives over 10^7 colour tiles (Lemma 6.1): choose fewer");
  d.kappa = kappa;
  d.literal_stable_ws = p.literal_stable_ws;
  d.steiner_aim_squared = p.steiner_aim * p.steiner_aim * d.rho_squared;
  d.shore_cells = p.shore_cells;
  return d;
}

template <int D>
double DerivedParameters<D>::tile_side(int rank) const {
  return std::pow(rho, double(rank) - 0.5) / std::sqrt(double(D));
}

template struct DerivedParameters<2>;
template struct DerivedParameters<3>;

}  // namespace shoremesh
