#pragma once

#include <type_traits>

#include <ccd/ccd.h>

#include <spook/collide/contact_sink.hpp>
#include <spook/core/math.hpp>

namespace spook::detail {

// The libccd bridge: each convex shape lends libccd its support function
// through a stack object that holds the shape and its world pose. libccd is
// built with double, so a float shape converts at this boundary.
template <class Shape>
struct CcdObject {
  using S = typename Shape::Vec3::Scalar;
  const Shape* shape;
  Mat3<double> R;     // shape → world rotation
  Vec3<double> p;     // shape origin in world (m)
  Vec3<double> center;  // a point inside the shape, world (m)

  CcdObject(const Shape& s, const Transform<S>& X_W)
      : shape(&s),
        R(X_W.linear().template cast<double>()),
        p(X_W.translation().template cast<double>()),
        center(R * s.getCenterOfVolume().template cast<double>() + p) {}

  static void support(const void* object, const ccd_vec3_t* direction, ccd_vec3_t* out) {
    const auto& o = *static_cast<const CcdObject*>(object);
    const Vec3<double> d_W(direction->v[0], direction->v[1], direction->v[2]);
    const Vec3<S> d_local = (o.R.transpose() * d_W).template cast<S>();
    const Vec3<double> s_W = o.R * o.shape->support(d_local).template cast<double>() + o.p;
    for (int i = 0; i < 3; ++i) out->v[i] = s_W[i];
  }
  static void centerOf(const void* object, ccd_vec3_t* out) {
    const auto& o = *static_cast<const CcdObject*>(object);
    for (int i = 0; i < 3; ++i) out->v[i] = o.center[i];
  }
};

inline constexpr double kCcdEpaTolerance = 1e-6;  // m
inline constexpr unsigned long kCcdMaxIterations = 200;

/// The overlap of the projections of a and b onto the unit direction n
/// (from a toward b): f(n) = h_a(n) + h_b(−n), with h the support function.
/// By the separating axis theorem the penetration depth is min f over unit
/// n, and by Danskin's theorem ∇f = s_a(n) − s_b(−n) =: w.
template <class A, class B>
struct ProjectionOverlap {
  const CcdObject<A>& a;
  const CcdObject<B>& b;

  [[nodiscard]] Vec3<double> supportOf(const auto& object, const Vec3<double>& n_W) const {
    using S = typename std::remove_cvref_t<decltype(object)>::S;
    const Vec3<S> d = (object.R.transpose() * n_W).template cast<S>();
    return object.R * object.shape->support(d).template cast<double>() + object.p;
  }
  [[nodiscard]] Vec3<double> gradient(const Vec3<double>& n) const { return supportOf(a, n) - supportOf(b, -n); }
};

/// Polishes libccd's direction: libccd's EPA stops some 1e-4 to 1e-3 short
/// of the boundary on curved shapes, so the direction is refined by descent
/// of f on the unit sphere (Barzilai–Borwein steps with backtracking) and
/// the depth is taken as f at the final direction, an upper bound that is
/// exact at the minimum. On polytopes, where the minimum sits on a kink of
/// f and EPA is already exact, the descent stops at once.
template <class A, class B>
double refinePenetration(const CcdObject<A>& a, const CcdObject<B>& b, Vec3<double>& n, double scale) {
  const ProjectionOverlap<A, B> overlap{a, b};
  Vec3<double> w = overlap.gradient(n);
  double f = n.dot(w);
  Vec3<double> g = w - n.dot(w) * n;
  double step = 1.0 / scale;
  for (int iteration = 0; iteration < 64 && g.norm() > 1e-13 * scale && step > 1e-12 / scale; ++iteration) {
    const Vec3<double> trial = (n - step * g).normalized();
    const Vec3<double> wTrial = overlap.gradient(trial);
    const double fTrial = trial.dot(wTrial);
    if (!(fTrial < f)) {
      step *= 0.5;
      continue;
    }
    const Vec3<double> gTrial = wTrial - trial.dot(wTrial) * trial;
    const Vec3<double> sStep = trial - n, yStep = gTrial - g;
    const double curvature = sStep.dot(yStep);
    step = curvature > 0.0 ? sStep.squaredNorm() / curvature : 2.0 * step;
    n = trial;
    w = wTrial;
    f = fTrial;
    g = gTrial;
  }
  return f;
}

/// Penetration of two convex shapes by GJK + EPA (libccd), polished as
/// above: one contact at libccd's point, with the direction that separates
/// b from a.
template <Scalar S, class A, class B>
void collideByCcd(const A& a, const Transform<S>& X_WA, const B& b, const Transform<S>& X_WB, ContactSinkT<S>& sink) {
  const CcdObject<A> objectA(a, X_WA);
  const CcdObject<B> objectB(b, X_WB);
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = &CcdObject<A>::support;
  ccd.support2 = &CcdObject<B>::support;
  ccd.center1 = &CcdObject<A>::centerOf;
  ccd.center2 = &CcdObject<B>::centerOf;
  ccd.max_iterations = kCcdMaxIterations;
  ccd.epa_tolerance = kCcdEpaTolerance;
  ccd_real_t depth = 0;
  ccd_vec3_t direction, position;
  if (ccdGJKPenetration(&objectA, &objectB, &ccd, &depth, &direction, &position) != 0) return;
  Vec3<double> n(direction.v[0], direction.v[1], direction.v[2]);
  const double length = n.norm();
  if (!(length > 0.0)) return;  // touching at a single point: no direction to push along
  n /= length;
  const double scale = (a.getBoundingBox().halfExtents().template cast<double>().norm() +
                        b.getBoundingBox().halfExtents().template cast<double>().norm());
  const double refined = refinePenetration(objectA, objectB, n, scale);
  if (!(refined >= 0.0)) return;  // the polished direction separates them
  const Vec3<double> point(position.v[0], position.v[1], position.v[2]);
  sink.add(point.cast<S>(), n.cast<S>(), S(refined));
}

}  // namespace spook::detail
