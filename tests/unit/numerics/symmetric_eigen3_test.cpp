// symmetric_eigen3 (numerics/symmetric_eigen3.h) returns Eigen's
// SelfAdjointEigenSolver<Matrix3d> results bit for bit, on matrices like the
// shape operators it serves and on the cases that take the solver's other
// branches; and the eigenpairs of known matrices.
#include "crestline/numerics/symmetric_eigen3.h"

#include <Eigen/Eigenvalues>
#include <catch2/catch.hpp>
#include <cmath>
#include <cstring>
#include <limits>
#include <random>
#include <vector>

using namespace crestline;

namespace {

// Same bits (so −0 differs from 0); any NaN equals any other (which
// operand's NaN an operation passes on is the compiler's choice).
bool same_bits(const double* a, const double* b, size_t n) {
  for (size_t i = 0; i < n; ++i)
    if (!(std::isnan(a[i]) && std::isnan(b[i])) && std::memcmp(a + i, b + i, sizeof(double)) != 0) return false;
  return true;
}

// The lower triangle is all either solver reads; the upper one is filled
// with something else, to show it.
Eigen::Matrix3d symmetric(double a00, double a10, double a20, double a11, double a21, double a22) {
  Eigen::Matrix3d s;
  s << a00, 7, 7, a10, a11, 7, a20, a21, a22;
  return s;
}

bool matches_eigen(const Eigen::Matrix3d& s, const SymmetricEigen3& ours) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(s);
  return same_bits(eigen.eigenvalues().data(), ours.values.data(), 3) &&
         same_bits(eigen.eigenvectors().data(), ours.vectors.data(), 9);
}

bool matches_eigen(const Eigen::Matrix3d& s) { return matches_eigen(s, symmetric_eigen3(s)); }

SymmetricLower3 lower(const Eigen::Matrix3d& s) { return {s(0, 0), s(1, 0), s(2, 0), s(1, 1), s(2, 1), s(2, 2)}; }

}  // namespace

TEST_CASE("symmetric_eigen3 is Eigen's SelfAdjointEigenSolver bit for bit", "[numerics]") {
  std::mt19937 random(5);
  std::uniform_real_distribution<double> unit(-1, 1);
  std::uniform_int_distribution<int> exponent(-300, 300), pick(0, 9);
  std::vector<Eigen::Matrix3d> cases;
  // Shape operators: sums of a few H_e w w^T with w ⟂ a normal (rank 2 up to
  // rounding), at scales from 1e-300 to 1e300.
  for (int i = 0; i < 20000; ++i) {
    const Eigen::Vector3d n = Eigen::Vector3d(unit(random), unit(random), unit(random)).normalized();
    Eigen::Matrix3d s = Eigen::Matrix3d::Zero();
    const double scale = std::ldexp(1.0, exponent(random) / 4);
    for (int e = 0; e < 3 + i % 7; ++e) {
      const Eigen::Vector3d w = n.cross(Eigen::Vector3d(unit(random), unit(random), unit(random))).normalized();
      s += scale * unit(random) * w * w.transpose();
    }
    cases.push_back(s);
  }
  // General symmetric matrices, with exact and signed zeros, subnormals and
  // repeated values among the coefficients (the deflation and shift branches).
  const double specials[] = {0.0, -0.0, 1.0, -1.0, 0.5, 4.9e-324, -2.2e-308, 1e-200, 1e200, 3.0};
  for (int i = 0; i < 50000; ++i) {
    double a[6];
    for (double& x : a)
      x = pick(random) < 3 ? specials[pick(random)] : std::ldexp(unit(random), exponent(random) / (1 + i % 4));
    cases.push_back(symmetric(a[0], a[1], a[2], a[3], a[4], a[5]));
  }
  // Repeated eigenvalues: rotations of diag(a, a, b) and diag(a, a, a).
  for (int i = 0; i < 5000; ++i) {
    const Eigen::Matrix3d r =
        Eigen::Quaterniond(unit(random), unit(random), unit(random), unit(random)).normalized().toRotationMatrix();
    const double a = unit(random), b = i % 2 ? a : unit(random);
    cases.push_back(r * Eigen::Vector3d(a, a, b).asDiagonal() * r.transpose());
  }
  cases.push_back(Eigen::Matrix3d::Zero());
  cases.push_back(Eigen::Matrix3d::Identity());
  cases.push_back(symmetric(1, 0, 0, 2, 0, 3));
  cases.push_back(symmetric(3, 0, 0, 2, 0, 1));
  cases.push_back(symmetric(0, 1, 0, 0, 1, 0));
  cases.push_back(symmetric(1, 1e-170, 1e-170, 1, 1e-170, 1));
  // A coefficient that is not finite goes to Eigen's solver: the same too.
  const double inf = std::numeric_limits<double>::infinity(), nan = std::numeric_limits<double>::quiet_NaN();
  const Eigen::Matrix3d not_finite[] = {symmetric(1, nan, 0, 2, 0, 3), symmetric(inf, 0, 1, 2, 0, 3),
                                        symmetric(1, 0, 0, 2, -inf, 3)};
  for (const Eigen::Matrix3d& s : not_finite) CHECK(matches_eigen(s));

  // One at a time (each paired with the zero matrix).
  size_t mismatches = 0;
  for (const Eigen::Matrix3d& s : cases) mismatches += !matches_eigen(s);
  CHECK(mismatches == 0);

  // All at once, in pairs: a matrix's partner, which may take more or fewer
  // QR steps, leaves its bits alone; those that are not finite, here one in
  // every 1001, leave the pairing of the rest to go on across them, and an
  // odd count leaves the last one with the zero matrix.
  for (size_t i = 0; i < cases.size(); i += 1001) cases.insert(cases.begin() + i, not_finite[i % 3]);
  for (const size_t count : {cases.size(), cases.size() - 1}) {
    std::vector<SymmetricLower3> lowers;
    for (size_t i = 0; i < count; ++i) lowers.push_back(lower(cases[i]));
    std::vector<SymmetricEigen3> batch(count);
    symmetric_eigen3(lowers.data(), count, batch.data());
    mismatches = 0;
    for (size_t i = 0; i < count; ++i) mismatches += !matches_eigen(cases[i], batch[i]);
    CHECK(mismatches == 0);
  }
}

TEST_CASE("symmetric_eigen3 finds the eigenpairs of known matrices", "[numerics]") {
  // R diag(−2, 0.5, 3) R^T: ascending eigenvalues, R's columns as eigenvectors (up to sign).
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, -1).normalized()).toRotationMatrix();
  const SymmetricEigen3 e = symmetric_eigen3(r * Eigen::Vector3d(-2, 0.5, 3).asDiagonal() * r.transpose());
  CHECK(e.values[0] == Approx(-2).margin(1e-14));
  CHECK(e.values[1] == Approx(0.5).margin(1e-14));
  CHECK(e.values[2] == Approx(3).margin(1e-14));
  for (int i = 0; i < 3; ++i) {
    CHECK(std::abs(e.vectors.col(i).dot(r.col(i))) == Approx(1).margin(1e-14));
    CHECK(e.vectors.col(i).norm() == Approx(1).margin(1e-14));
  }
  // Already diagonal: the identity's columns, reordered.
  const SymmetricEigen3 d = symmetric_eigen3(symmetric(3, 0, 0, -1, 0, 2));
  CHECK(d.values == Eigen::Vector3d(-1, 2, 3));
  CHECK(d.vectors.col(0).cwiseAbs() == Eigen::Vector3d(0, 1, 0));
  CHECK(d.vectors.col(1).cwiseAbs() == Eigen::Vector3d(0, 0, 1));
  CHECK(d.vectors.col(2).cwiseAbs() == Eigen::Vector3d(1, 0, 0));
}
