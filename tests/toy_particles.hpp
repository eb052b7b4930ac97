#pragma once

// Toy extensions of the step (sim/step_extension.hpp) for the tests: a store
// of point masses held in arrays (no RigidBody, no Frame), and two producers
// over it: a beaded string (stretch and three-node bend rows) and
// sphere-sphere / sphere-plane contacts. They use only the public doors.

#include <array>
#include <cmath>
#include <cstdint>
#include <unordered_map>
#include <vector>

#include <spook/spook.hpp>

namespace toy {

using Vec3d = Eigen::Vector3d;
using spook::detail::Row;
using spook::detail::SolverBody;
using spook::detail::Vec6d;

inline Vec6d linear(const Vec3d& v) {
  Vec6d J = Vec6d::Zero();
  J.head<3>() = v;
  return J;
}

/// Point masses that do not turn: position, velocity, mass, radius.
class ParticleStore : public spook::BodyStore {
 public:
  std::size_t add(const Vec3d& position, double mass, double radius, bool fixed = false) {
    position_.push_back(position);
    velocity_.push_back(Vec3d::Zero());
    mass_.push_back(mass);
    radius_.push_back(radius);
    fixed_.push_back(fixed ? 1 : 0);
    return position_.size() - 1;
  }
  [[nodiscard]] std::size_t size() const override { return position_.size(); }
  [[nodiscard]] const Vec3d& position(std::size_t i) const { return position_[i]; }
  Vec3d& position(std::size_t i) { return position_[i]; }
  [[nodiscard]] const Vec3d& velocity(std::size_t i) const { return velocity_[i]; }
  [[nodiscard]] double radius(std::size_t i) const { return radius_[i]; }
  [[nodiscard]] double mass(std::size_t i) const { return mass_[i]; }
  [[nodiscard]] bool fixed(std::size_t i) const { return fixed_[i] != 0; }
  /// Gravity on or off for the store's particles.
  void setGravity(bool on) { gravity_ = on; }

  void writeSolverBodies(std::span<SolverBody> bodies, const spook::StepContext& step) const override {
    const double h = step.getTimeStep();
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      SolverBody& b = bodies[i];
      if (fixed_[i]) continue;
      b.dynamic = true;
      b.velocity.head<3>() = velocity_[i];
      b.freeVelocity.head<3>() = velocity_[i] + (gravity_ ? Vec3d(h * step.gravity(position_[i])) : Vec3d::Zero());
      b.inverseMass = Eigen::Matrix3d::Identity() / mass_[i];
    }
  }
  void move(std::span<const SolverBody> bodies, const spook::StepContext& step) override {
    for (std::size_t i = 0; i < bodies.size(); ++i) {
      if (fixed_[i]) continue;
      velocity_[i] = bodies[i].freeVelocity.head<3>();
      position_[i] += step.getTimeStep() * velocity_[i];
    }
  }
  void displace(std::span<const SolverBody> bodies) override {
    for (std::size_t i = 0; i < bodies.size(); ++i)
      if (!fixed_[i]) position_[i] += bodies[i].displacement.head<3>();
  }

 private:
  std::vector<Vec3d> position_, velocity_;
  std::vector<double> mass_, radius_;
  std::vector<char> fixed_;
  bool gravity_ = true;
};

/// Beads 0..n−1 of a store joined in order by stretch rows (rest length
/// `restLength`, compliance `stretchCompliance` m/N) and, at each inner
/// bead, two bend rows across the string: g = e·(x_{i−1} − 2x_i + x_{i+1})
/// for the two directions e across `axis`, compliance `bendCompliance`.
class BeadedString : public spook::RowProducer {
 public:
  BeadedString(spook::ref_ptr<ParticleStore> store, double restLength, double stretchCompliance,
               double bendCompliance, const Vec3d& axis)
      : store_(std::move(store)), restLength_(restLength), stretchCompliance_(stretchCompliance),
        bendCompliance_(bendCompliance) {
    across_[0] = axis.unitOrthogonal();
    across_[1] = axis.normalized().cross(across_[0]);
  }
  double damping = 1e-4;  ///< τ of every row (s)

  void writeRows(spook::RowWriter& rows, const spook::StepContext& step) override {
    const std::size_t n = store_->size();
    impulses_.resize(3 * n, 0.0);
    const auto index = [&](std::size_t i) { return step.indexOf(*store_, i); };
    for (std::size_t i = 0; i + 1 < n; ++i) {
      const Vec3d d = store_->position(i + 1) - store_->position(i);
      const Vec3d u = d.normalized();
      Row& r = rows.add(impulses_[3 * i]);
      r.body1 = index(i);
      r.body2 = index(i + 1);
      r.J1 = linear(-u);
      r.J2 = linear(u);
      r.violation = d.norm() - restLength_;
      r.compliance = stretchCompliance_;
      r.damping = damping;
    }
    if (!(bendCompliance_ > 0.0)) return;
    for (std::size_t i = 1; i + 1 < n; ++i) {
      const Vec3d second = store_->position(i - 1) - 2.0 * store_->position(i) + store_->position(i + 1);
      for (std::size_t k = 0; k < 2; ++k) {
        Row& r = rows.add(impulses_[3 * i + 1 + k]);
        r.body1 = index(i - 1);
        r.body2 = index(i);
        rows.setThirdBody(rows.size() - 1, index(i + 1), linear(across_[k]));
        r.J1 = linear(across_[k]);
        r.J2 = linear(-2.0 * across_[k]);
        r.violation = across_[k].dot(second);
        r.compliance = bendCompliance_;
        r.damping = damping;
      }
    }
  }
  void readBack(std::span<const double> impulses, const spook::StepContext& step) override {
    const std::size_t n = store_->size();
    std::size_t k = 0;
    for (std::size_t i = 0; i + 1 < n; ++i) impulses_[3 * i] = impulses[k++];
    if (bendCompliance_ > 0.0)
      for (std::size_t i = 1; i + 1 < n; ++i)
        for (std::size_t a = 0; a < 2; ++a) impulses_[3 * i + 1 + a] = impulses[k++];
    tension_ = n > 1 ? impulses_[0] / step.getTimeStep() : 0.0;
  }
  /// The force in the first segment (N, > 0 pulling its beads together).
  [[nodiscard]] double tension() const { return -tension_; }

 private:
  spook::ref_ptr<ParticleStore> store_;
  double restLength_, stretchCompliance_, bendCompliance_;
  std::array<Vec3d, 2> across_;
  std::vector<double> impulses_;
  double tension_ = 0.0;
};

/// Frictional contacts between the particles of a store and with the planes
/// n·x = d (inward normals): a normal row (compliance, damping, impulse ≥ 0)
/// and two friction rows bounded by μ times the normal impulse, warm started
/// from the same pair's impulses last step.
class ParticleContacts : public spook::RowProducer {
 public:
  struct Plane {
    Vec3d normal;
    double offset;
  };
  ParticleContacts(spook::ref_ptr<ParticleStore> store, std::vector<Plane> planes)
      : store_(std::move(store)), planes_(std::move(planes)) {}
  double compliance = 1e-7;  ///< m/N
  double damping = 0.05;     ///< s
  double friction = 0.3;
  double margin = 0.01;  ///< contacts are kept from this gap on (m)
  spook::SolveType solveType = spook::SolveType::ITERATIVE;

  void writeRows(spook::RowWriter& rows, const spook::StepContext& step) override {
    pairs_.clear();
    const std::size_t n = store_->size();
    double largest = 0.0;
    for (std::size_t i = 0; i < n; ++i) largest = std::max(largest, store_->radius(i));
    // A uniform grid of cells of the largest diameter plus the margin.
    const double cell = 2.0 * largest + margin;
    std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> grid;
    const auto key = [&](long x, long y, long z) {
      return (std::uint64_t(x + (1 << 20)) << 42) | (std::uint64_t(y + (1 << 20)) << 21) | std::uint64_t(z + (1 << 20));
    };
    const auto cellOf = [&](const Vec3d& p) {
      return std::array<long, 3>{long(std::floor(p.x() / cell)), long(std::floor(p.y() / cell)),
                                 long(std::floor(p.z() / cell))};
    };
    for (std::size_t i = 0; i < n; ++i) {
      const auto c = cellOf(store_->position(i));
      grid[key(c[0], c[1], c[2])].push_back(std::uint32_t(i));
    }
    for (std::size_t i = 0; i < n; ++i) {
      const auto c = cellOf(store_->position(i));
      for (long dx = -1; dx <= 1; ++dx)
        for (long dy = -1; dy <= 1; ++dy)
          for (long dz = -1; dz <= 1; ++dz) {
            const auto it = grid.find(key(c[0] + dx, c[1] + dy, c[2] + dz));
            if (it == grid.end()) continue;
            for (std::uint32_t j : it->second) {
              if (j <= i) continue;
              const Vec3d d = store_->position(j) - store_->position(i);
              const double gap = d.norm() - store_->radius(i) - store_->radius(j);
              if (gap < margin && d.norm() > 0.0) addContact(rows, step, i, j, d.normalized(), gap);
            }
          }
      for (std::size_t p = 0; p < planes_.size(); ++p) {
        const double gap = planes_[p].normal.dot(store_->position(i)) - planes_[p].offset - store_->radius(i);
        if (gap < margin) addContact(rows, step, i, n + p, -planes_[p].normal, gap);
      }
    }
  }
  void readBack(std::span<const double> impulses, const spook::StepContext&) override {
    last_.clear();
    for (std::size_t k = 0; k < pairs_.size(); ++k)
      last_[pairs_[k]] = {impulses[3 * k], impulses[3 * k + 1], impulses[3 * k + 2]};
  }
  /// Contacts written in the last step.
  [[nodiscard]] std::size_t numContacts() const { return pairs_.size(); }

 private:
  // A contact of particle i with particle j (j < n) or plane j − n, the
  // normal n pointing from i towards the other.
  void addContact(spook::RowWriter& rows, const spook::StepContext& step, std::size_t i, std::size_t j,
                  const Vec3d& n, double gap) {
    const std::uint64_t pair = (std::uint64_t(i) << 32) | j;
    const auto last = last_.find(pair);
    const std::array<double, 3> warm = last == last_.end() ? std::array<double, 3>{} : last->second;
    const int bodyI = step.indexOf(*store_, i);
    const int bodyJ = j < store_->size() ? step.indexOf(*store_, j) : -1;
    const std::size_t normalRow = rows.size();
    Row& normal = rows.add(warm[0]);
    normal.body1 = bodyI;
    normal.body2 = bodyJ;
    normal.J1 = linear(-n);
    normal.J2 = linear(n);
    normal.violation = gap;
    normal.compliance = compliance;
    normal.damping = damping;
    normal.lower = 0.0;
    normal.solveType = solveType;
    const Vec3d t1 = n.unitOrthogonal();
    const std::array<Vec3d, 2> tangents{t1, n.cross(t1)};
    for (std::size_t k = 0; k < 2; ++k) {
      const Vec3d& t = tangents[k];
      Row& r = rows.add(warm[1 + k]);
      r.body1 = bodyI;
      r.body2 = bodyJ;
      r.J1 = linear(-t);
      r.J2 = linear(t);
      r.holonomic = false;
      r.compliance = 1e-9;
      r.upper = friction * std::max(warm[0], 0.0) / step.getTimeStep();  // from last step's normal impulse
      r.lower = -r.upper;
      r.solveType = solveType;
      rows.setFriction(rows.size() - 1, normalRow, friction, spook::detail::FrictionBound::SCALED_BOX);
    }
    pairs_.push_back(pair);
  }

  spook::ref_ptr<ParticleStore> store_;
  std::vector<Plane> planes_;
  std::vector<std::uint64_t> pairs_;
  std::unordered_map<std::uint64_t, std::array<double, 3>> last_;
};

}  // namespace toy
