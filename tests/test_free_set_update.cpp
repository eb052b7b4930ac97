#include <doctest/doctest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include <spook/solver/body_space_solve.hpp>
#include <spook/solver/free_set_update.hpp>

using namespace spook;

namespace {

using SparseMatrix = Eigen::SparseMatrix<double>;

// A random sparse symmetric positive definite matrix of n rows, each
// coupled to a few others (a pile's normals: rows sharing a body).
SparseMatrix randomSpd(std::mt19937& rng, int n) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> pick(0, n - 1);
  std::vector<Eigen::Triplet<double>> entries;
  std::vector<double> rowSum(static_cast<std::size_t>(n), 0.0);
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < 3; ++c) {
      const int j = pick(rng);
      if (j == i) continue;
      const double a = u(rng);
      entries.emplace_back(i, j, a);
      entries.emplace_back(j, i, a);
      rowSum[static_cast<std::size_t>(i)] += std::abs(a);
      rowSum[static_cast<std::size_t>(j)] += std::abs(a);
    }
  // Diagonally dominant by a random margin, from 1e-3 to 1 of the row's sum.
  for (int i = 0; i < n; ++i)
    entries.emplace_back(
        i, i, rowSum[static_cast<std::size_t>(i)] * (1.0 + std::pow(10.0, -3.0 + 3.0 * std::abs(u(rng)))) + 1e-3);
  SparseMatrix A(n, n);
  A.setFromTriplets(entries.begin(), entries.end());
  return A;
}

// The identity-row form of DirectSolve: the clamped rows and columns of A
// made the identity's, its lower triangle.
SparseMatrix withClamped(const SparseMatrix& A, const std::vector<int>& freeIndex) {
  SparseMatrix B = A;
  for (int col = 0; col < B.outerSize(); ++col)
    for (SparseMatrix::InnerIterator it(B, col); it; ++it) {
      const bool freeRow = freeIndex[static_cast<std::size_t>(it.row())] >= 0;
      const bool freeCol = freeIndex[static_cast<std::size_t>(col)] >= 0;
      if (it.row() == col)
        it.valueRef() = freeCol ? it.value() : 1.0;
      else if (!(freeRow && freeCol))
        it.valueRef() = 0.0;
    }
  return SparseMatrix(B.triangularView<Eigen::Lower>());
}

std::vector<int> freeIndexOf(const std::vector<char>& isFree) {
  std::vector<int> index(isFree.size(), -1);
  int next = 0;
  for (std::size_t k = 0; k < isFree.size(); ++k)
    if (isFree[k]) index[k] = next++;
  return index;
}

}  // namespace

// The update against a fresh factorization: random sparse SPD systems,
// factorized at one free set, solved at free sets that differ from it in
// 1 to 32 rows, rows freed and clamped, then walked on as a pivoting does
// (each set a few rows from the last, the factor kept).
TEST_CASE("solving a changed free set with the factor in hand matches a fresh factorization") {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst = 0.0;
  int updated = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const int n = 20 + 13 * trial;
    const SparseMatrix A = randomSpd(rng, n);
    std::vector<char> isFree(static_cast<std::size_t>(n));
    for (auto& f : isFree) f = u(rng) > -0.4;
    std::vector<int> freeIndex = freeIndexOf(isFree);
    SparseMatrix factored = withClamped(A, freeIndex);
    Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> ldlt(factored);
    REQUIRE(ldlt.info() == Eigen::Success);
    detail::FreeSetUpdate update;
    update.reset(freeIndex);
    const auto factorSolve = [&](const Eigen::VectorXd& v) { return Eigen::VectorXd(ldlt.solve(v)); };

    std::uniform_int_distribution<int> pick(0, n - 1);
    for (int step = 0; step < 8; ++step) {
      const int flips = 1 + trial % 4;
      for (int f = 0; f < flips; ++f) isFree[static_cast<std::size_t>(pick(rng))] ^= 1;
      freeIndex = freeIndexOf(isFree);
      const SparseMatrix current = withClamped(A, freeIndex);
      Eigen::VectorXd b(n);
      for (int k = 0; k < n; ++k) b[k] = freeIndex[static_cast<std::size_t>(k)] >= 0 ? u(rng) : 0.0;
      const Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> fresh(current);
      const Eigen::VectorXd expected = fresh.solve(b);

      Eigen::VectorXd x;
      const double enough = 1e-12 * b.cwiseAbs().maxCoeff();
      if (!update.solve(A, current, freeIndex, b, enough, factorSolve, x)) continue;
      ++updated;
      const Eigen::VectorXd residual = b - current.selfadjointView<Eigen::Lower>() * x;
      CHECK(residual.cwiseAbs().maxCoeff() <= enough);
      double difference = 0.0;
      for (int k = 0; k < n; ++k)
        if (freeIndex[static_cast<std::size_t>(k)] >= 0)
          difference = std::max(difference, std::abs(x[k] - expected[k]));
      worst = std::max(worst, difference / expected.cwiseAbs().maxCoeff());
    }
  }
  MESSAGE(updated << " of 320 changed free sets solved by the update; worst difference " << worst
                  << " of the largest unknown");
  CHECK(updated > 250);
  CHECK(worst < 1e-9);
}

TEST_CASE("a free set changed in more rows than the update takes is left to a new factorization") {
  std::mt19937 rng(9);
  const int n = 200;
  const SparseMatrix A = randomSpd(rng, n);
  std::vector<char> isFree(static_cast<std::size_t>(n), 1);
  std::vector<int> freeIndex = freeIndexOf(isFree);
  const SparseMatrix factored = withClamped(A, freeIndex);
  const Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> ldlt(factored);
  detail::FreeSetUpdate update;
  update.reset(freeIndex);
  const auto factorSolve = [&](const Eigen::VectorXd& v) { return Eigen::VectorXd(ldlt.solve(v)); };
  for (int k = 0; k < detail::FactoredFreeSet::kMaxChangedRows + 1; ++k) isFree[static_cast<std::size_t>(3 * k)] = 0;
  freeIndex = freeIndexOf(isFree);
  const SparseMatrix current = withClamped(A, freeIndex);
  Eigen::VectorXd b = Eigen::VectorXd::Ones(n), x;
  for (int k = 0; k < n; ++k)
    if (freeIndex[static_cast<std::size_t>(k)] < 0) b[k] = 0.0;
  CHECK_FALSE(update.solve(A, current, freeIndex, b, 1e-12, factorSolve, x));
  // One row fewer is within reach.
  isFree[0] = 1;
  freeIndex = freeIndexOf(isFree);
  const SparseMatrix nearer = withClamped(A, freeIndex);
  b[0] = 1.0;
  REQUIRE(update.solve(A, nearer, freeIndex, b, 1e-12, factorSolve, x));
  const Eigen::SimplicialLDLT<SparseMatrix, Eigen::Lower> fresh(nearer);
  const Eigen::VectorXd expected = fresh.solve(b);
  for (int k = 0; k < n; ++k)
    if (freeIndex[static_cast<std::size_t>(k)] >= 0) CHECK(x[k] == doctest::Approx(expected[k]).epsilon(1e-9));
}

namespace {

// Compliant rows between random pairs of `numBodies` bodies (some against
// the world), twice as many as the bodies' degrees of freedom: a contact
// island in body-space form (mass matrices given).
detail::IslandProblem compliantIsland(std::mt19937& rng, int numBodies) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> pick(0, numBodies - 1);
  detail::IslandProblem problem;
  problem.numBodies = numBodies;
  std::vector<double> inverseMass(static_cast<std::size_t>(numBodies));
  for (auto& m : inverseMass) {
    m = 0.01 + std::abs(u(rng));
    problem.mass.push_back(detail::Mat6d::Identity() / m);
  }
  for (int i = 0; i < 12 * numBodies; ++i) {
    auto& e = problem.rows.emplace_back();
    e.body1 = pick(rng);
    e.body2 = u(rng) > -0.6 ? pick(rng) : -1;
    if (e.body2 == e.body1) e.body2 = -1;
    for (int k = 0; k < 6; ++k) {
      e.J1[k] = u(rng);
      e.J2[k] = e.body2 >= 0 ? u(rng) : 0.0;
    }
    e.W1 = e.J1 * inverseMass[static_cast<std::size_t>(e.body1)];
    if (e.body2 >= 0) e.W2 = e.J2 * inverseMass[static_cast<std::size_t>(e.body2)];
    e.sigma = std::pow(10.0, -5.0 + 3.0 * std::abs(u(rng)));
    e.diagonal = problem.mobility(e) + e.sigma;
  }
  return problem;
}

}  // namespace

// The body-space form's update (Woodbury over the changed rows) against a
// fresh factorization of M + GᵀΣ⁻¹G: islands of 5-40 bodies with twelve
// compliant rows per body, free sets walked a few rows at a time.
TEST_CASE("the body-space solve of a changed free set with the factor in hand matches a fresh factorization") {
  std::mt19937 rng(13);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst = 0.0;
  int updated = 0, steps = 0;
  for (int trial = 0; trial < 24; ++trial) {
    const detail::IslandProblem problem = compliantIsland(rng, 5 + trial * 35 / 23);
    const int n = static_cast<int>(problem.rows.size());
    std::vector<int> all(static_cast<std::size_t>(n));
    for (int i = 0; i < n; ++i) all[static_cast<std::size_t>(i)] = i;
    std::vector<char> isFree(static_cast<std::size_t>(n));
    for (auto& f : isFree) f = u(rng) > -0.5;
    detail::BodySpaceSolve kept;
    kept.analyze(problem, all);
    REQUIRE(kept.factorize(problem, all, freeIndexOf(isFree)));
    REQUIRE_FALSE(kept.updated());
    std::uniform_int_distribution<int> pick(0, n - 1);
    for (int step = 0; step < 6; ++step, ++steps) {
      for (int f = 0; f < 1 + trial % 5; ++f) isFree[static_cast<std::size_t>(pick(rng))] ^= 1;
      const std::vector<int> freeIndex = freeIndexOf(isFree);
      const int numFree = static_cast<int>(std::count(isFree.begin(), isFree.end(), 1));
      Eigen::VectorXd rhs(numFree), x = Eigen::VectorXd::Zero(n), expected = Eigen::VectorXd::Zero(n);
      for (int f = 0; f < numFree; ++f) rhs[f] = u(rng);
      kept.analyze(problem, all);
      REQUIRE(kept.factorize(problem, all, freeIndex));
      updated += kept.updated() ? 1 : 0;
      kept.solve(problem, all, freeIndex, rhs, x);
      detail::BodySpaceSolve fresh;
      fresh.analyze(problem, all);
      REQUIRE(fresh.factorize(problem, all, freeIndex));
      fresh.solve(problem, all, freeIndex, rhs, expected);
      double difference = 0.0;
      for (int k = 0; k < n; ++k)
        if (isFree[static_cast<std::size_t>(k)]) difference = std::max(difference, std::abs(x[k] - expected[k]));
      worst = std::max(worst, difference / expected.cwiseAbs().maxCoeff());
    }
  }
  MESSAGE(updated << " of " << steps << " changed free sets solved by the update; worst difference " << worst
                  << " of the largest unknown");
  CHECK(updated > steps / 2);
  // Both forms lose the digits x = Σ⁻¹(r − Gy) cancels (Σ down to 1e-5 of
  // the mobilities); DirectSolve refines them back.
  CHECK(worst < 1e-9);
}
