#pragma once
// Truncated Taylor series x(t + h) = c0 + c1 h + c2 h^2 (automatic differentiation to second order): products, sin and
// cos by the usual recurrences (Griewank & Walther, "Evaluating Derivatives", ch. 13). Private to the library.
#include <cmath>

namespace twinslam::sim::detail {

struct Jet {
  double c0 = 0, c1 = 0, c2 = 0;  // value, first derivative, half the second derivative

  static Jet from_derivatives(double x, double dx, double ddx) { return {x, dx, 0.5 * ddx}; }
  double value() const { return c0; }
  double d1() const { return c1; }
  double d2() const { return 2 * c2; }
  // Series of the time derivative; only its c0 and c1 are meaningful (one order is lost).
  Jet derivative() const { return {c1, 2 * c2, 0}; }
};

inline Jet operator+(const Jet& a, const Jet& b) { return {a.c0 + b.c0, a.c1 + b.c1, a.c2 + b.c2}; }
inline Jet operator-(const Jet& a, const Jet& b) { return {a.c0 - b.c0, a.c1 - b.c1, a.c2 - b.c2}; }
inline Jet operator-(const Jet& a) { return {-a.c0, -a.c1, -a.c2}; }
inline Jet operator*(double s, const Jet& a) { return {s * a.c0, s * a.c1, s * a.c2}; }
inline Jet operator*(const Jet& a, const Jet& b) {
  return {a.c0 * b.c0, a.c0 * b.c1 + a.c1 * b.c0, a.c0 * b.c2 + a.c1 * b.c1 + a.c2 * b.c0};
}

// sin and cos together: s_k = (1/k) sum_j j u_j c_{k-j},  c_k = -(1/k) sum_j j u_j s_{k-j}.
inline void sincos(const Jet& u, Jet& s, Jet& c) {
  s.c0 = std::sin(u.c0);
  c.c0 = std::cos(u.c0);
  s.c1 = u.c1 * c.c0;
  c.c1 = -u.c1 * s.c0;
  s.c2 = 0.5 * (u.c1 * c.c1 + 2 * u.c2 * c.c0);
  c.c2 = -0.5 * (u.c1 * s.c1 + 2 * u.c2 * s.c0);
}

}  // namespace twinslam::sim::detail
