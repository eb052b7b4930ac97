#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <utility>
#include <vector>
#include <type_traits>

#include <ccd/ccd.h>

#include <spook/collide/contact_sink.hpp>
#include <spook/collide/detail/feature_clipping.hpp>
#include <spook/collide/supporting_feature.hpp>
#include <spook/core/math.hpp>

namespace spook::detail {

// The libccd bridge: each convex shape lends libccd its support function
// through a stack object that holds the shape and its world pose. libccd is
// built with double, so a float shape converts at this boundary.
//
// libccd's EPA (ccdGJKPenetration) expands its polytope until a support
// point gains less than epa_tolerance and has no cap on its iterations: on
// two cylinders in a near-degenerate pose it ran for minutes (fuzz finding
// tests/fuzz/corpus/finding_epa-endless). Past a budget of support calls both objects answer
// the origin, which gains nothing, so EPA stops on its nearest face; the
// polishing that follows measures the overlap itself.
struct CcdSupportBudget {
  unsigned long limit;
  unsigned long calls = 0;  // counted by the first object (libccd's support1)
};

/// A convex shape as the bridge sees it, whatever its type and scalar: its
/// support function and supporting feature in its own frame, in double.
/// Everything below works on this view, so one copy of the polishing serves
/// every shape pair: compiled per pair, its copies and the continuous
/// sweeps' were nearly half of a program's collider code. The indirect
/// support call costs nothing measurable (libccd calls supports through
/// function pointers anyway).
struct ConvexSupport {
  const void* shape = nullptr;
  Vec3T<double> (*support)(const void* shape, const Vec3T<double>& d) = nullptr;
  /// The shape's supporting feature, or null: sampled (supportingFeature).
  void (*feature)(const void* shape, const Vec3T<double>& d, SupportingFeatureT<double>& out) = nullptr;
  Vec3T<double> centerOfVolume = Vec3T<double>::Zero();  // shape frame (m)
  double size = 0.0;  // the shape's scale (m): its bounding half-diagonal (shapeSize)

  [[nodiscard]] Vec3T<double> supportAlong(const Vec3T<double>& d) const { return support(shape, d); }
};

/// A shape's size (m): the half-diagonal of its bounding box, in its own
/// frame; the scale of the colliders' touching gap and tolerances.
template <class Shape>
[[nodiscard]] double shapeSize(const Shape& shape) {
  return shape.getBoundingBox().halfExtents().template cast<double>().norm();
}

/// The bridge's view of `shape`, which must outlive it. A float shape is
/// asked in float, its answers converted.
template <class Shape>
[[nodiscard]] ConvexSupport convexSupportOf(const Shape& shape) {
  using S = typename Shape::Vec3::Scalar;
  ConvexSupport convex;
  convex.shape = &shape;
  convex.support = [](const void* s, const Vec3T<double>& d) -> Vec3T<double> {
    return static_cast<const Shape*>(s)->support(d.template cast<S>()).template cast<double>();
  };
  if constexpr (requires(SupportingFeatureT<S> & out) { shape.supportingFeature(Vec3T<S>(), out); })
    convex.feature = [](const void* s, const Vec3T<double>& d, SupportingFeatureT<double>& out) {
      SupportingFeatureT<S> local;
      static_cast<const Shape*>(s)->supportingFeature(d.template cast<S>(), local);
      out.count = local.count;
      for (std::size_t k = 0; k < local.count; ++k) out.points[k] = local.points[k].template cast<double>();
      out.radius = double(local.radius);
      out.center = local.center.template cast<double>();
      out.axis = local.axis.template cast<double>();
    };
  convex.centerOfVolume = shape.getCenterOfVolume().template cast<double>();
  convex.size = shapeSize(shape);
  return convex;
}

/// A convex shape at its world pose, as libccd's object: libccd calls
/// `support` and `centerOf` with a pointer to it.
struct CcdObject {
  ConvexSupport convex;
  Mat3T<double> R;     // shape → world rotation
  Vec3T<double> p;     // shape origin in world (m)
  Vec3T<double> center;  // a point inside the shape, world (m)
  double margin = 0.0;   // libccd sees the shape grown by this much (m)
  CcdSupportBudget* budget = nullptr;
  bool countsCalls = false;  // libccd calls support1, then support2

  CcdObject(const ConvexSupport& shape, const Mat3T<double>& R_W, const Vec3T<double>& p_W, double grownBy = 0.0)
      : convex(shape), R(R_W), p(p_W), center(R * shape.centerOfVolume + p), margin(grownBy) {}
  template <Scalar S>
  CcdObject(const ConvexSupport& shape, const TransformT<S>& X_W, double grownBy = 0.0)
      : CcdObject(shape, X_W.linear().template cast<double>(), X_W.translation().template cast<double>(), grownBy) {}

  /// The support point along the world direction n_W (not grown), world (m).
  [[nodiscard]] Vec3T<double> supportWorld(const Vec3T<double>& n_W) const {
    return R * convex.supportAlong(R.transpose() * n_W) + p;
  }

  static void support(const void* object, const ccd_vec3_t* direction, ccd_vec3_t* out) {
    const auto& o = *static_cast<const CcdObject*>(object);
    if (o.budget) {
      const unsigned long spent = o.countsCalls ? o.budget->calls++ : o.budget->calls - 1;
      if (spent >= o.budget->limit) {
        for (int i = 0; i < 3; ++i) out->v[i] = 0.0;
        return;
      }
    }
    const Vec3T<double> d_W(direction->v[0], direction->v[1], direction->v[2]);
    Vec3T<double> s_W = o.supportWorld(d_W);
    if (const double length = d_W.norm(); o.margin > 0.0 && length > 0.0) s_W += (o.margin / length) * d_W;
    for (int i = 0; i < 3; ++i) out->v[i] = s_W[i];
  }
  static void centerOf(const void* object, ccd_vec3_t* out) {
    const auto& o = *static_cast<const CcdObject*>(object);
    for (int i = 0; i < 3; ++i) out->v[i] = o.center[i];
  }
};

inline constexpr double kCcdEpaTolerance = 1e-6;  // m

/// Gap, relative to the smaller shape's size, beyond which libccd's GJK is
/// trusted to call two shapes apart.
inline constexpr double kCcdNearMargin = 1e-3;
inline constexpr unsigned long kCcdMaxIterations = 200;
/// Support calls of one ccdGJKPenetration: GJK's kCcdMaxIterations and
/// EPA's expansions (in the collider tests' 526,000 calls, 7 took more than
/// 256, one more than 511). An EPA expansion scans every face of its
/// polytope (ccdPtNearest), so a call costs the square of its support
/// calls: at a budget of 1000, a cylinder of radius 1e100 m under a
/// 392-triangle height field took 1.8 s a step (Release), at 256 0.16 s
/// (tests/fuzz/findings/huge-cylinder-on-triangles, parked).
inline constexpr unsigned long kCcdSupportBudget = 256;

/// libccd's settings for two CcdObjects.
[[nodiscard]] inline ccd_t ccdSettings() {
  ccd_t ccd;
  CCD_INIT(&ccd);
  ccd.support1 = &CcdObject::support;
  ccd.support2 = &CcdObject::support;
  ccd.center1 = &CcdObject::centerOf;
  ccd.center2 = &CcdObject::centerOf;
  ccd.max_iterations = kCcdMaxIterations;
  return ccd;
}
/// Polishing: starts besides libccd's direction, and the gradient
/// (relative to the shapes' size) below which a descent ended on a smooth
/// minimum and needs no simplex search. Polishing only the starts within
/// 1 % of the lowest descent loses 1e-4 m on capsule– and cylinder–triangle
/// pairs; skipping the simplex search where the descent ends smooth loses
/// nothing and makes the capsule, sphere and smooth hull pairs five times
/// faster.
inline constexpr std::size_t kStarts = 10;
inline constexpr double kSmoothGradient = 1e-9;
/// A simplex search whose best vertex comes within this angle of a
/// minimum already polished, no lower than it, stops: most starts that
/// stall on a kink walk down the same crease to the same minimum, and
/// following each to 1e-10 rad took two thirds of the bridge's time. At
/// 1e-3 rad depths lost up to 2.5e-5 m (two creases meet that close); at
/// 1e-5 rad, with snapToFrameAxis, the libccd tests' worst depth errors
/// stay below 5e-7 m as before (but hull pairs: 4.8e-7 m, were 1.6e-7 m;
/// they allow 1e-4 m), the mesh tests measure what they did, and calls are
/// 1.4-2 times faster (box–cylinder 314 → 180-200 µs, box–hull 503 → 252
/// µs in Release).
inline constexpr double kJoinAngle = 1e-5;  // rad

/// A polished direction and its overlap f.
struct PolishedMinimum {
  double f;
  Vec3T<double> n;
};

/// Whether direction d with overlap f lies within the angle of cosine
/// `cosine` of a known minimum no higher than f.
inline bool joinsKnownMinimum(const std::vector<PolishedMinimum>& known, const Vec3T<double>& d, double f,
                              double cosine) {
  for (const PolishedMinimum& m : known)
    if (d.dot(m.n) > cosine && f >= m.f) return true;
  return false;
}

/// Where a descent from one start ended: f, the direction, and whether on a
/// smooth minimum.
struct Descent {
  double f;
  Vec3T<double> n;
  bool smooth;
};

/// Lowest f first; of equal overlaps the smooth minimum first, so that a
/// kinked descent that ended on it joins it at once. (Not a template: one
/// sort for every shape pair, which keeps the colliders' compile time.)
inline void sortDescents(std::vector<Descent>& descents) {
  std::stable_sort(descents.begin(), descents.end(), [](const Descent& x, const Descent& y) {
    return x.f < y.f || (x.f == y.f && x.smooth && !y.smooth);
  });
}

/// The overlap of the projections of a and b onto the unit direction n
/// (from a toward b): f(n) = h_a(n) + h_b(−n), with h the support function.
/// By the separating axis theorem the penetration depth is min f over unit
/// n, and by Danskin's theorem ∇f = s_a(n) − s_b(−n) =: w.
struct ProjectionOverlap {
  const CcdObject& a;
  const CcdObject& b;

  [[nodiscard]] Vec3T<double> gradient(const Vec3T<double>& n) const { return a.supportWorld(n) - b.supportWorld(-n); }
};

/// Where f has a kink (an edge or a corner of a box-like shape is involved)
/// its minimum may sit at the bottom of a narrow crease, which neither the
/// gradient nor a fixed pattern of steps can follow; a Nelder–Mead simplex
/// over the tangent plane of n (Nelder & Mead 1965) stretches along the
/// crease and walks down it, to 1e-10 rad.
inline double polishBySimplexSearch(const ProjectionOverlap& overlap, Vec3T<double>& n, double f, double size,
                                    double turn, const std::vector<PolishedMinimum>& known, bool& joined) {
  static const double joinCosine = std::cos(kJoinAngle);
  const Vec3T<double> n0 = n, u = n0.unitOrthogonal(), w = n0.cross(u);
  const Vec3T<double> t1 = std::cos(turn) * u + std::sin(turn) * w, t2 = n0.cross(t1);
  const auto direction = [&](const Eigen::Vector2d& x) { return Vec3T<double>((n0 + x[0] * t1 + x[1] * t2).normalized()); };
  const auto value = [&](const Eigen::Vector2d& x) {
    const Vec3T<double> d = direction(x);
    return d.dot(overlap.gradient(d));
  };
  std::array<Eigen::Vector2d, 3> x = {Eigen::Vector2d(0, 0), Eigen::Vector2d(size, 0), Eigen::Vector2d(0, size)};
  std::array<double, 3> fx = {f, value(x[1]), value(x[2])};
  for (int iteration = 0; iteration < 400; ++iteration) {
    // Order best, middle, worst.
    for (int i = 0; i < 2; ++i)
      for (int j = 0; j < 2 - i; ++j)
        if (fx[j + 1] < fx[j]) {
          std::swap(fx[j], fx[j + 1]);
          std::swap(x[j], x[j + 1]);
        }
    if ((x[1] - x[0]).norm() + (x[2] - x[0]).norm() < 1e-10) break;
    if (iteration % 4 == 0) {
      const Vec3T<double> d = direction(x[0]);
      joined = joinsKnownMinimum(known, d, fx[0], joinCosine);
      if (joined) break;
    }
    const Eigen::Vector2d centroid = 0.5 * (x[0] + x[1]);
    const Eigen::Vector2d reflected = centroid + (centroid - x[2]);
    const double fr = value(reflected);
    if (fr < fx[0]) {
      const Eigen::Vector2d expanded = centroid + 2.0 * (centroid - x[2]);
      const double fe = value(expanded);
      if (fe < fr) {
        x[2] = expanded;
        fx[2] = fe;
      } else {
        x[2] = reflected;
        fx[2] = fr;
      }
    } else if (fr < fx[1]) {
      x[2] = reflected;
      fx[2] = fr;
    } else {
      const Eigen::Vector2d contracted = centroid + 0.5 * (x[2] - centroid);
      const double fc = value(contracted);
      if (fc < fx[2]) {
        x[2] = contracted;
        fx[2] = fc;
      } else {
        for (int i = 1; i < 3; ++i) {
          x[i] = x[0] + 0.5 * (x[i] - x[0]);
          fx[i] = value(x[i]);
        }
      }
    }
  }
  const int best = fx[0] <= fx[1] ? (fx[0] <= fx[2] ? 0 : 2) : (fx[1] <= fx[2] ? 1 : 2);
  if (fx[best] < f) {
    n = direction(x[best]);
    f = fx[best];
  }
  return f;
}

/// Descends f on the unit sphere from n (Barzilai–Borwein steps with
/// backtracking): libccd's EPA stops some 1e-4 to 1e-3 short of the
/// boundary on curved shapes. Returns f at the final direction, an upper
/// bound on the depth that is exact at the minimum; `smooth` tells whether
/// the descent ended where the gradient vanishes (a smooth minimum, done)
/// rather than on a kink of f, where the simplex search must take over.
inline double descend(const ProjectionOverlap& overlap, Vec3T<double>& n, double scale, bool& smooth) {
  Vec3T<double> w = overlap.gradient(n);
  double f = n.dot(w);
  Vec3T<double> g = w - n.dot(w) * n;
  double step = 1.0 / scale;
  for (int iteration = 0; iteration < 64 && g.norm() > 1e-13 * scale && step > 1e-12 / scale; ++iteration) {
    const Vec3T<double> trial = (n - step * g).normalized();
    const Vec3T<double> wTrial = overlap.gradient(trial);
    const double fTrial = trial.dot(wTrial);
    if (!(fTrial < f)) {
      step *= 0.5;
      continue;
    }
    const Vec3T<double> gTrial = wTrial - trial.dot(wTrial) * trial;
    const Vec3T<double> sStep = trial - n, yStep = gTrial - g;
    const double curvature = sStep.dot(yStep);
    step = curvature > 0.0 ? sStep.squaredNorm() / curvature : 2.0 * step;
    n = trial;
    w = wTrial;
    f = fTrial;
    g = gTrial;
  }
  smooth = g.norm() <= kSmoothGradient * scale;
  return f;
}

/// Restarts of the simplex search with fresh, turned simplices: the usual
/// cure for one that collapsed across a crease. Stops where a search joins
/// one of the `known` minima (kJoinAngle).
inline double polishOnKinks(const ProjectionOverlap& overlap, Vec3T<double>& n, double f, double scale,
                            const std::vector<PolishedMinimum>& known) {
  for (int restart = 0; restart < 6; ++restart) {
    const double before = f;
    bool joined = false;
    f = polishBySimplexSearch(overlap, n, f, restart % 2 ? 0.1 : 0.02, 0.5 * restart, known, joined);
    if (joined || (restart > 0 && !(f < before - 1e-15 * scale))) break;
  }
  return f;
}

/// Starting directions for the polishing: libccd's, then the most promising
/// of the line of centers, each shape's frame axes and their cross products
/// (both signs) and a coarse lattice of directions, lowest overlap first. libccd's EPA sometimes returns a poor
/// direction on deep or curved overlaps, and f may have several local
/// minima; for box-like and cylindrical shapes the true minimum lies on or
/// near one of these axes (face normals and edge–edge directions, as in the
/// separating axis theorem).
inline std::vector<Vec3T<double>> startingDirections(const CcdObject& a, const CcdObject& b,
                                                     const Vec3T<double>& fromCcd, std::size_t count) {
  const ProjectionOverlap overlap{a, b};
  std::vector<std::pair<double, Vec3T<double>>> candidates;
  const auto consider = [&](const Vec3T<double>& direction) {
    const double length = direction.norm();
    if (!(length > 1e-9)) return;
    for (const double sign : {1.0, -1.0}) {
      const Vec3T<double> d = direction * (sign / length);
      candidates.emplace_back(d.dot(overlap.gradient(d)), d);
    }
  };
  consider(b.center - a.center);
  for (int i = 0; i < 3; ++i) {
    consider(a.R.col(i));
    consider(b.R.col(i));
    for (int j = 0; j < 3; ++j) consider(a.R.col(i).cross(b.R.col(j)));
  }
  // And a coarse, even spread (a Fibonacci lattice of 48 pairs ±d, some
  // 0.25 rad apart) so that no basin of f is far from a start.
  constexpr int kLattice = 96;
  const double golden = 3.141592653589793 * (3.0 - std::sqrt(5.0));
  for (int i = 0; i < kLattice; ++i) {
    const double z = 1.0 - (i + 0.5) / kLattice, rho = std::sqrt(1.0 - z * z), phi = golden * i;
    consider(Vec3T<double>(rho * std::cos(phi), rho * std::sin(phi), z));
  }
  std::sort(candidates.begin(), candidates.end(), [](const auto& x, const auto& y) { return x.first < y.first; });
  std::vector<Vec3T<double>> starts{fromCcd};
  for (const auto& [f, d] : candidates) {
    if (starts.size() > count) break;
    if (std::none_of(starts.begin(), starts.end(), [&d = d](const Vec3T<double>& s) { return s.dot(d) > 0.999; }))
      starts.push_back(d);
  }
  return starts;
}

/// A shape's supporting feature along the unit direction n, world (m): its
/// points, their mean and how far they spread from the support at n.
struct SupportingFeature {
  Vec3T<double> center;  // mean of the points, world (m)
  double spread = 0.0;   // largest distance of a point from the support at n (m)
  std::vector<Vec3T<double>> samples;
  FeatureClipping::Disc disc;  // a round face (radius > 0), world
};
/// Tilt of the sampled features (shapes without supportingFeature).
inline constexpr double kFeatureTilt = 1e-3;  // rad

/// The supporting feature of a shape along n: the shape's own
/// supportingFeature (a face, an edge or a point within the feature angle,
/// SupportingFeatureT) or, for a shape without one, sampled: its support at
/// n and at n tilted by kFeatureTilt toward eight directions of the tangent
/// plane, which spread over a face or an edge (its corners or ends) that is
/// within that tilt of supporting and stay together otherwise.
inline SupportingFeature supportingFeature(const CcdObject& object, const Vec3T<double>& n) {
  const auto toWorld = [&](const Vec3T<double>& p) { return Vec3T<double>(object.R * p + object.p); };
  SupportingFeature feature{Vec3T<double>::Zero(), 0.0, {}, {}};
  if (object.convex.feature) {
    SupportingFeatureT<double> local;
    object.convex.feature(object.convex.shape, object.R.transpose() * n, local);
    for (std::size_t k = 0; k < local.count; ++k) feature.samples.push_back(toWorld(local.points[k]));
    if (local.radius > 0.0) feature.disc = {toWorld(local.center), object.R * local.axis, local.radius};
  } else {
    const Vec3T<double> t1 = n.unitOrthogonal(), t2 = n.cross(t1);
    feature.samples.push_back(object.supportWorld(n));
    for (int k = 0; k < 8; ++k) {
      const double angle = k * 0.7853981633974483;
      feature.samples.push_back(object.supportWorld(n + kFeatureTilt * (std::cos(angle) * t1 + std::sin(angle) * t2)));
    }
  }
  const Vec3T<double> atN = object.supportWorld(n);
  for (const Vec3T<double>& p : feature.samples) {
    feature.center += p;
    feature.spread = std::max(feature.spread, (p - atN).norm());
  }
  feature.center /= double(feature.samples.size());
  return feature;
}

/// The contact point of a penetration of the given depth along n (from a
/// toward b): in the overlap, half the depth inside both surfaces, at the
/// middle of the narrower of the two supporting features (the curved or the
/// smaller shape's), or between both middles where they are alike (two
/// faces of one size). Never a support point chosen among a wide face's
/// corners, whose lever arm would spin the body that rests on it.
inline Vec3T<double> contactPointInOverlap(const SupportingFeature& onA, const SupportingFeature& onB, const Vec3T<double>& n,
                                    double depth) {
  const Vec3T<double> fromA = onA.center - 0.5 * depth * n, fromB = onB.center + 0.5 * depth * n;
  if (onA.spread < 0.5 * onB.spread) return fromA;
  if (onB.spread < 0.5 * onA.spread) return fromB;
  return 0.5 * (fromA + fromB);
}

/// The contacts of a penetration of `depth` along n (from a toward b): the
/// corners of the overlap of the two supporting features (FeatureClipping:
/// a resting face, cylinder side or cap gets its manifold in one step), or,
/// where the features do not overlap, one point by contactPointInOverlap.
/// Points closer than 4·kFeatureTilt·size are one point (the spread a
/// sampled curved surface leaves).
inline std::vector<FeatureClipping::Contact> contactsOfFeatures(const CcdObject& a, const CcdObject& b,
                                                                const Vec3T<double>& n, double depth) {
  const SupportingFeature onA = supportingFeature(a, n), onB = supportingFeature(b, -n);
  const auto size = [](const CcdObject& object) { return object.convex.size; };
  const FeatureClipping clipping(n);
  std::vector<FeatureClipping::Contact> contacts =
      clipping.contacts({onA.samples, 4.0 * kFeatureTilt * size(a), onA.disc},
                        {onB.samples, 4.0 * kFeatureTilt * size(b), onB.disc}, depth,
                        kTouchingGap * std::min(size(a), size(b)));
  if (contacts.empty()) {
    // A point feature (a vertex, a curved surface's support) is the contact
    // itself; two extended ones that miss each other on the contact plane
    // (a cap's inscribed polygon, round-off at a rim) meet where they come
    // nearest.
    if (onA.samples.size() == 1 || onB.samples.size() == 1)
      contacts.push_back({contactPointInOverlap(onA, onB, n, depth), depth});
    else
      contacts.push_back(clipping.nearest({onA.samples, 4.0 * kFeatureTilt * size(a), onA.disc},
                                          {onB.samples, 4.0 * kFeatureTilt * size(b), onB.disc}, depth));
  }
  return contacts;
}

/// A frame axis of either shape within kSnapAngle of the polished n takes
/// its place where its overlap is no larger: a face resting on a face (the
/// commonest contact) is a sharp kink of f, where a simplex search cut
/// short by kJoinAngle ended 4e-4 m deep beside a 500 m box (8.6e-7 of its
/// size; the exact depth 2.8e-17 of it after the snap).
inline constexpr double kSnapAngle = 1e-3;  // rad

inline void snapToFrameAxis(const ProjectionOverlap& overlap, Vec3T<double>& n, double& f) {
  static const double snapCosine = std::cos(kSnapAngle);
  for (const Mat3T<double>* R : {&overlap.a.R, &overlap.b.R})
    for (int i = 0; i < 3; ++i)
      for (const double sign : {1.0, -1.0}) {
        const Vec3T<double> axis = sign * R->col(i);
        if (!(axis.dot(n) > snapCosine)) continue;
        const double fAxis = axis.dot(overlap.gradient(axis));
        if (fAxis <= f) {
          f = fAxis;
          n = axis;
        }
      }
}

/// True when one of the directions ±(axes of a's and b's frames) or ±(the
/// line between their centers) has a projection overlap f below `below`:
/// the shapes are apart by at least −below along it.
inline bool separatedAlongFrameAxes(const ProjectionOverlap& overlap, double below) {
  const auto apart = [&](const Vec3T<double>& direction) {
    const double length = direction.norm();
    if (!(length > 0.0)) return false;
    for (const double sign : {1.0, -1.0}) {
      const Vec3T<double> d = direction * (sign / length);
      if (d.dot(overlap.gradient(d)) < below) return true;
    }
    return false;
  };
  if (apart(overlap.b.center - overlap.a.center)) return true;
  for (int i = 0; i < 3; ++i)
    if (apart(overlap.a.R.col(i)) || apart(overlap.b.R.col(i))) return true;
  return false;
}

/// Contacts of a penetration along the unit normal n (from a toward b).
struct CcdPenetration {
  Vec3T<double> n = Vec3T<double>::UnitZ();
  std::vector<FeatureClipping::Contact> contacts;  // none: apart
};

/// Penetration of two convex shapes by GJK + EPA (libccd), polished as
/// above: the direction that separates b from a, with the contacts of
/// contactsOfFeatures (not libccd's point, a midpoint of support points
/// that may lie on a far corner of a large face), or only the deepest of
/// them when `manifold` is false (triangle pairs of two meshes, one contact
/// per intersecting pair).
inline CcdPenetration penetrationByCcd(const ConvexSupport& a, const Mat3T<double>& R_WA, const Vec3T<double>& p_WA,
                                       const ConvexSupport& b, const Mat3T<double>& R_WB, const Vec3T<double>& p_WB,
                                       bool manifold) {
  // libccd sees a grown by kTouchingGap of the smaller shape's size, so
  // that shapes placed exactly touching (a body set down on a ground) are
  // found touching, not left to fall a step; the polishing below measures
  // the true overlap, and a gap within the margin is a contact of depth 0.
  const double sizeA = a.size, sizeB = b.size;
  // libccd dereferences a null polytope face when its supports overflow.
  if (!std::isfinite(sizeA) || !std::isfinite(sizeB)) return {};
  CcdSupportBudget budget{kCcdSupportBudget};
  CcdObject objectA(a, R_WA, p_WA, kTouchingGap * std::min(sizeA, sizeB));
  CcdObject objectB(b, R_WB, p_WB);
  objectA.budget = objectB.budget = &budget;
  objectA.countsCalls = true;
  ccd_t ccd = ccdSettings();
  ccd.epa_tolerance = kCcdEpaTolerance;
  ccd_real_t depth = 0;
  ccd_vec3_t direction, position;
  const ProjectionOverlap overlap{objectA, objectB};
  const int penetration = ccdGJKPenetration(&objectA, &objectB, &ccd, &depth, &direction, &position);
  objectA.budget = objectB.budget = nullptr;
  if (penetration != 0) {
    // libccd's GJK misses a few shallow overlaps of a small shape on a large
    // one (0.7 % of those 1e-9..1e-4 m deep on boxes of 0.5..500 m, each a
    // step of free fall through a resting contact): "apart" stands when a
    // grown by kCcdNearMargin is still apart, or with a separating axis
    // among the shapes' axes and the line between their centers; otherwise
    // the polishing below decides.
    const CcdObject grownA(a, R_WA, p_WA, kCcdNearMargin * std::min(sizeA, sizeB));
    if (!ccdGJKIntersect(&grownA, &objectB, &ccd) || separatedAlongFrameAxes(overlap, -objectA.margin)) return {};
    direction = {{0.0, 0.0, 0.0}};
  }
  // libccd reports a penetration far smaller than the shapes (within the
  // margin) as touching, without a direction: the polishing below finds it
  // from its other starts.
  Vec3T<double> n(direction.v[0], direction.v[1], direction.v[2]);
  if (const double length = n.norm(); length > 0.0 && std::isfinite(length))
    n /= length;
  else
    n = Vec3T<double>::UnitZ();
  const double scale = sizeA + sizeB;
  // f may have several local minima: descend from several starts, then
  // search the kinks where a descent stalled, the lowest first.
  std::vector<Descent> descents;
  for (Vec3T<double> start : startingDirections(objectA, objectB, n, kStarts)) {
    bool smooth = false;
    const double f = descend(overlap, start, scale, smooth);
    descents.push_back({f, start, smooth});
  }
  sortDescents(descents);
  std::vector<PolishedMinimum> known;
  double refined = std::numeric_limits<double>::infinity();
  for (Descent& descent : descents) {
    if (!descent.smooth) descent.f = polishOnKinks(overlap, descent.n, descent.f, scale, known);
    known.push_back({descent.f, descent.n});
    if (descent.f < refined) {
      refined = descent.f;
      n = descent.n;
    }
  }
  snapToFrameAxis(overlap, n, refined);
  if (!(refined >= -objectA.margin)) return {};  // the polished direction separates them
  CcdPenetration result{n, contactsOfFeatures(objectA, objectB, n, std::max(refined, 0.0))};
  if (!manifold) {
    const auto deepest = std::max_element(result.contacts.begin(), result.contacts.end(),
                                          [](const auto& x, const auto& y) { return x.depth < y.depth; });
    result.contacts = {*deepest};
  }
  return result;
}

/// penetrationByCcd for shapes a and b at their world poses, into the sink.
template <Scalar S, class A, class B>
void collideByCcd(const A& a, const TransformT<S>& X_WA, const B& b, const TransformT<S>& X_WB, ContactSinkT<S>& sink,
                  bool manifold = true) {
  const CcdPenetration penetration = penetrationByCcd(
      convexSupportOf(a), X_WA.linear().template cast<double>(), X_WA.translation().template cast<double>(),
      convexSupportOf(b), X_WB.linear().template cast<double>(), X_WB.translation().template cast<double>(), manifold);
  for (const FeatureClipping::Contact& contact : penetration.contacts)
    sink.add(contact.point.cast<S>(), penetration.n.cast<S>(), S(contact.depth));
}

}  // namespace spook::detail
