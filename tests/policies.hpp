#pragma once

// The three solver policies, for tests that run one scene under each.

#include <string>

#include <spook/solver/solver.hpp>

namespace spook::test {

enum class Policy { DIRECT, HYBRID, ITERATIVE };
inline constexpr Policy kPolicies[] = {Policy::DIRECT, Policy::HYBRID, Policy::ITERATIVE};

inline std::string policyName(Policy p) {
  return p == Policy::DIRECT ? "direct" : p == Policy::HYBRID ? "hybrid" : "iterative";
}

/// A new solver of the policy, with its defaults.
inline ref_ptr<Solver> makeSolver(Policy p) {
  if (p == Policy::DIRECT) return new DirectSolver();
  if (p == Policy::HYBRID) return new HybridSolver();
  return new IterativeSolver();
}

}  // namespace spook::test
