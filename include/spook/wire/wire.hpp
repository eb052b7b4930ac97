#pragma once

// A wire (agxWire's Wire; PHYSICS.md §3): lumped mass nodes at the wire's
// resolution joined by stretch rows and, over each three consecutive
// points, bend rows, with compliances from its material's wire moduli. It is
// routed with nodes (wire/wire_node.hpp) before it joins a simulation:
//
//   ref_ptr<Wire> wire = new Wire(0.02, 2.0);  // radius 2 cm, 2 nodes per meter
//   wire->add(new BodyFixedNode(nullptr, Vec3(0, 0, 10)));  // fixed to the world
//   wire->add(new FreeNode(0, 0, 5));                       // a free end
//   simulation->add(wire);
//
// Its length is that of the route. Either end may start at a winch
// (wire/wire_winch_controller.hpp) holding more of the wire pulled in:
//
//   wire->add(winch, 50.0);  // first: 50 m on the drum
//
// A row producer (sim/step_extension.hpp) that owns its node store: the
// simulation adds and removes both together.

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <limits>
#include <numbers>
#include <numeric>
#include <optional>
#include <span>
#include <string>
#include <vector>

#include <Eigen/Core>

#include <spook/core/error.hpp>
#include <spook/core/implementation.hpp>
#include <spook/core/math.hpp>
#include <spook/core/observer_ptr.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/scalar.hpp>
#include <spook/core/second_order.hpp>
#include <spook/dynamics/material.hpp>
#include <spook/dynamics/rigid_body.hpp>
#include <spook/sim/step_extension.hpp>
#include <spook/wire/edge_wrap.hpp>
#include <spook/wire/sheave_wrap.hpp>
#include <spook/wire/wire_geometry_contacts.hpp>
#include <spook/wire/wire_link.hpp>
#include <spook/wire/wire_node.hpp>
#include <spook/wire/wire_nodes.hpp>
#include <spook/wire/wire_row_bodies.hpp>
#include <spook/wire/wire_winch_controller.hpp>

namespace spook {

template <Scalar S>
class WireT : public RowProducer {
 public:
  using Vec3 = Vec3T<S>;
  using Node = WireNodeT<S>;
  using Material = MaterialT<S>;
  using Body = RigidBodyT<S>;
  using Winch = WireWinchControllerT<S>;
  using ContactNode = ContactNodeT<S>;
  using SlidingNode = SlidingNodeT<S>;
  using Geometry = GeometryT<S>;
  using Link = WireLinkT<S>;
  using ConnectingNode = ConnectingNodeT<S>;

  /// A contact of the wire with a geometry in the last step.
  struct GeometryContact {
    const Geometry* geometry = nullptr;
    Vec3 point = Vec3::Zero();   ///< world (m)
    Vec3 normal = Vec3::Zero();  ///< unit, from the wire toward the geometry
    S depth = S(0);              ///< penetration (m)
    S distance = S(0);           ///< from the wire's start (m of rest length)
    Vec3 force = Vec3::Zero();   ///< on the geometry (N)
  };

  /// A wire of `radius` (m) and `resolution` lumped nodes per meter, both
  /// finite and > 0, made of `material` (a material of its own, named
  /// "wire", when nullptr).
  WireT(S radius, S resolutionPerUnitLength, ref_ptr<Material> material = nullptr);

  /// Appends a node to the route, before the wire is added to a simulation.
  void add(ref_ptr<Node> node);
  /// Starts (first) or ends (last) the route at a winch holding
  /// `pulledInLength` m (finite, >= 0) of wire on its drum, before the wire
  /// is added to a simulation. Nothing may be routed after an end winch.
  void add(ref_ptr<Winch> winch, S pulledInLength);
  /// Starts (first) or ends (last) the route at `link`, clamped to its body
  /// at `position` (its model frame, m) through a ConnectingNode with the
  /// link's connection properties (WireLinkT::getConnectionProperties).
  void add(ref_ptr<Link> link, const Vec3& position);
  /// The route as given; a winch is there as a body-fixed node at its
  /// position.
  [[nodiscard]] const std::vector<ref_ptr<Node>>& getRoute() const { return route_; }
  /// The winch at the start (`begin`) or end of the wire, or nullptr.
  [[nodiscard]] Winch* getWinch(bool begin) const { return winches_[begin ? 0 : 1].get(); }

  /// Radius (m); setting it changes the wire's mass and stiffness.
  [[nodiscard]] S getRadius() const { return S(radius_); }
  void setRadius(S radius);
  /// Lumped nodes per meter of the route.
  [[nodiscard]] S getResolutionPerUnitLength() const { return S(resolution_); }
  /// Changes the resolution (finite and > 0, at most 1e6 nodes along the
  /// wire), also in a simulation: from the next step, segments split up to
  /// it where the tension lets them (adaptive resolution) and shorter
  /// segments than a quarter of its spacing merge.
  void setResolutionPerUnitLength(S resolutionPerUnitLength);
  /// A stretch of the wire kept at a finer resolution (agxWire's
  /// HighResolutionRange): from `start` to `end` m of rest length from its
  /// begin (`begin`) or its end, `resolutionPerUnitLength` nodes per meter
  /// where that is finer than the wire's; elsewhere the wire's. From a winch
  /// at that end the stretch stays at the winch as the wire pays out and
  /// hauls in. One per end, kept through reverse, cut and merge with its
  /// end; the tension still removes nodes the step cannot resolve.
  /// 0 ≤ start < end finite, resolution finite and > 0; clearHighResolutionRange
  /// removes it.
  void setHighResolutionRange(bool begin, S start, S end, S resolutionPerUnitLength);
  void clearHighResolutionRange(bool begin) { ranges_[begin ? 0 : 1] = HighResolutionRange{}; }
  struct HighResolutionRange {
    S start = S(0), end = S(0);
    S resolution = S(0);  ///< nodes per meter, 0: no range
  };
  [[nodiscard]] const HighResolutionRange& getHighResolutionRange(bool begin) const { return ranges_[begin ? 0 : 1]; }
  /// Reverses the wire: its start becomes its end (route, points, winches,
  /// the sense of its wraps), also in a simulation; its state is kept.
  void reverse();
  /// Cuts the wire in a simulation `distanceFromStart` (m of rest length,
  /// at least a quarter of the node spacing from either end) from its
  /// start: it keeps the part before, with a free end there; the part
  /// after is returned as a new wire (named after this one, " cut"), with
  /// the free end, the contacts and the end attachment or winch beyond the
  /// cut; add it to the simulation to go on simulating it. Rest length,
  /// mass, the nodes' motion and the collision settings are kept.
  [[nodiscard]] ref_ptr<WireT> cut(S distanceFromStart);
  /// Joins `other` to this wire's end: this end and other's start must be
  /// free (no attachment, no winch), both wires of the same radius and
  /// material, both in the same simulation or both not yet in one. A
  /// straight piece of wire as long as the gap joins the two ends (none
  /// when they are closer than a quarter of the node spacing: the end
  /// nodes become one). `other` is left empty: remove it from the
  /// simulation; it cannot be added again.
  void merge(WireT* other);
  /// Frees the begin (`begin`) or the end of the wire from the body, the
  /// world or the winch it is attached to: a lumped node takes its place,
  /// moving with the point it was attached at. A winch keeps the wire that
  /// was on its drum (getPulledInLength) and can be attached again.
  void detach(bool begin);
  /// Attaches the free begin or end of the wire to `node` (a BodyFixedNode
  /// on a body of the wire's simulation or on the world, or a
  /// ConnectingNode on a body of its simulation) through a
  /// straight piece of wire as long as the gap (merged away when shorter
  /// than a quarter of the node spacing).
  void attach(ref_ptr<Node> node, bool begin);
  /// Attaches the free begin or end to `winch` holding `pulledInLength` m
  /// (finite, >= 0) on its drum, as attach(node) does.
  void attach(ref_ptr<Winch> winch, S pulledInLength, bool begin);
  /// Attaches the free begin or end to `link` at `position` (its body's
  /// model frame, m), as attach(node) does.
  void attach(ref_ptr<Link> link, const Vec3& position, bool begin);
  [[nodiscard]] Material* getMaterial() const { return material_.get(); }
  /// Changes the material; its density sets the mass of a wire already
  /// routed into a simulation.
  void setMaterial(ref_ptr<Material> material);

  /// Unstretched length of the wire off the winches' drums (m): at first
  /// the length of the route.
  [[nodiscard]] S getRestLength() const;
  /// Length along the wire now (m): between its points and around the
  /// geometries it wraps.
  [[nodiscard]] S getCurrentLength() const;
  /// Mass (kg): density × πr² × rest length.
  [[nodiscard]] S getMass() const;
  /// Tension (N, > 0 pulling) at `distance` (m of rest length) from the
  /// start, that of the segment there in the last step; 0 before any step.
  [[nodiscard]] S getTension(S distanceFromStart) const;
  /// The point of the wire (world, m) at `distance` (m of rest length,
  /// clamped to the wire) from its start, on the straight part of the
  /// segment there (its wraps' arcs count as their tangent points); the
  /// wire must be in a simulation.
  [[nodiscard]] Vec3 findPoint(S distanceFromStart) const;
  /// The distance (m of rest length) from the start to the point of the
  /// wire closest to `point` (world, m); the wire must be in a simulation.
  [[nodiscard]] S findDistance(const Vec3& point) const;
  /// The point of the wire closest to `point` (world, m), as findPoint
  /// places it; the wire must be in a simulation.
  [[nodiscard]] Vec3 findPoint(const Vec3& point) const { return findPoint(findDistance(point)); }
  /// Tension (N) where the wire is closest to `point` (world, m); the wire
  /// must be in a simulation.
  [[nodiscard]] S getTension(const Vec3& point) const { return getTension(findDistance(point)); }
  /// The wire's points from its start to its end (world, m): attached ends,
  /// lumped nodes and, for each contact node, where the wire meets and
  /// leaves the geometry; for rendering and inspection. Empty until the
  /// wire joins a simulation.
  [[nodiscard]] std::vector<Vec3> getPoints() const;
  /// Number of lumped mass nodes (0 until the wire joins a simulation).
  [[nodiscard]] std::size_t getNumMassNodes() const { return nodes_->numNodes(); }

  /// Whether the wire collides with the geometries of its simulation (on
  /// by default, as agxWire's): each straight segment is a capsule of the wire's radius
  /// between its points (wire/wire_geometry_contacts.hpp), with friction
  /// from the wire material's coefficient. Never with the geometries of
  /// the bodies its ends are attached to (fixed, clamped or at a winch), of
  /// its eye nodes' bodies, of its contact nodes, nor with sensors.
  void setEnableCollisions(bool enable) { collisions_ = enable; }
  [[nodiscard]] bool getEnableCollisions() const { return collisions_; }
  /// Disables (or enables again) the wire's collisions with one geometry.
  void setEnableCollisions(Geometry* geometry, bool enable);
  [[nodiscard]] bool getEnableCollisions(const Geometry* geometry) const;
  /// The wire's contacts with geometries in the last step.
  [[nodiscard]] std::vector<GeometryContact> getGeometryContacts() const;

  // RowProducer.
  void prepare(const StepContext& simulation) override;
  [[nodiscard]] BodyStore* getOwnedStore() override { return nodes_.get(); }
  void beginStep(const StepContext& step) override;
  void writeRows(RowWriter& rows, const StepContext& step) override;
  void readBack(std::span<const double> impulses, const StepContext& step) override;
  void writeProjectionRows(RowWriter& rows, const StepContext& step) override;

 protected:
  ~WireT() override = default;

 private:
  using Vec3d = Eigen::Vector3d;
  /// A point of the built wire: a lumped node, an end fixed to a body or
  /// the world at `local` (the body's model frame, or world), or a contact
  /// (contacts_[contact], on its geometry's body or the world: bodyOf).
  struct Point {
    int node = -1;
    Body* body = nullptr;
    Vec3d local = Vec3d::Zero();
    int contact = -1;
    ConnectingNode* connecting = nullptr;  ///< a ConnectingNode's end (route_ holds it)
  };
  /// A contact or eye node as built: its wrap (an eye's of radius 0), and
  /// its slip (wire sliding over the geometry or through the eye) as a
  /// degree of freedom of the store (a Drum whose free length gathers the
  /// length slid from the segment after to the one before).
  struct Contact {
    SlidingNode* node = nullptr;
    detail::SheaveWrap wrap;
    std::size_t slip = 0;
    double frictionImpulse = 0.0;
    int row = -1;  ///< its friction row's offset in this wire's rows, −1: none
    bool onEdge = false;     ///< over an edge of its geometry's shape (edge_wrap.hpp): an eye sliding along it
    detail::ShapeEdge edge;  ///< that edge in the shape's frame
  };

  template <class T>
  [[nodiscard]] Error error(const char* what, const T& value) const {
    return detail::makeError("Wire", getName(), what, value);
  }
  [[nodiscard]] Error error(const char* what) const { return detail::makeError("Wire", getName(), what); }
  [[nodiscard]] bool built() const { return !points_.empty(); }
  void checkRoute(const StepContext& simulation) const;
  void build(const StepContext& simulation);
  void feedTaut(const StepContext& simulation);
  /// The node spacing the step can resolve (m): the wire's (1/resolution)
  /// and no less than the distance a node falls in a step, |g|h². Shorter
  /// segments turn by more than a radian in a step where one end is held
  /// and the other falls, far past the first order in that angle to which
  /// the velocity-level step keeps their length (a 6 m steel wire of 7 cm
  /// segments, fixed at one end and released level at h = 0.2 s, swung
  /// above its pivot; of 38 cm, its length held within 0.02%).
  [[nodiscard]] double spacing(const StepContext& step) const;
  /// The node spacing wanted over [from, to] (m of rest length from the
  /// start): `spacing`, or finer where a high resolution range overlaps it,
  /// never under `floor` (|g|h²).
  [[nodiscard]] double spacingOver(double from, double to, double spacing, double floor) const;
  void updateMasses();
  /// Adaptive resolution (beginStep): nodes the step cannot resolve leave,
  /// and return where the tension allows.
  void removeNode(std::size_t point);
  /// A node that would pass a contact beside it within the step leaves (beginStep).
  bool leaveBeforeContacts(double timeStep);
  /// Splits segment k with a new node `fraction` (0, 1) along its straight part.
  void splitSegment(std::size_t segment, double fraction = 0.5);
  /// A segment that touched a geometry away from its ends gains a node there.
  bool splitAtGeometryContacts(double spacing);
  void renumberNodes();
  [[nodiscard]] double linearDensity() const;
  /// E·A of the stretch rows (N).
  [[nodiscard]] double stretchStiffness() const {
    return double(material_->getWireMaterial()->getYoungsModulusStretch()) * std::numbers::pi * radius_ * radius_;
  }
  /// A segment's stretch compliance l/(E·A) (m/N) from its rest length
  /// (none below 0: a wrap's arc can take more than its straight part).
  [[nodiscard]] double segmentCompliance(std::size_t segment, double stretchStiffness) const {
    return std::max(restLengths_[segment], 0.0) / stretchStiffness;
  }
  /// Where the wire is at point p (a contact: the material point C of its
  /// wrap), where it arrives at p and leaves it (a contact: the tangent
  /// points), and the velocity of p's body there.
  [[nodiscard]] Vec3d worldPosition(const Point& p) const;
  [[nodiscard]] Vec3d arrival(const Point& p) const;
  [[nodiscard]] Vec3d departure(const Point& p) const;
  [[nodiscard]] Vec3d worldVelocity(const Point& p) const;
  /// The body p moves with: a fixed end's, a contact's geometry's (as it is
  /// now), nullptr for the world and for lumped nodes.
  [[nodiscard]] const Body* bodyOf(const Point& p) const {
    return p.contact >= 0 ? contacts_[std::size_t(p.contact)].node->getRigidBody() : p.body;
  }
  /// Length of segment k along the wire now (m): its straight part and the
  /// arcs of the wraps at its ends.
  [[nodiscard]] double segmentLength(std::size_t k) const;
  /// The arcs of segment k (m): its length along the wraps at its ends.
  [[nodiscard]] double wrapped(std::size_t k) const;
  [[nodiscard]] bool nextToContact(std::size_t point) const {
    return (point > 0 && points_[point - 1].contact >= 0) ||
           (point + 1 < points_.size() && points_[point + 1].contact >= 0);
  }
  /// The sheave's plane now from its geometry's frame.
  void placePlane(const ContactNode& node, detail::SheaveWrap& wrap) const;
  /// The edge of the node's polyhedral shape it runs over (edge_wrap.hpp);
  /// none for a cylinder (a sheave) or a shape without edges.
  [[nodiscard]] std::optional<detail::ShapeEdge> edgeOf(const ContactNode& node) const;
  /// Where the wire from `from` to `to` runs over the edge of an edge contact now (world).
  [[nodiscard]] Vec3d edgePoint(const Contact& contact, const Vec3d& from, const Vec3d& to) const;
  /// A contact's wrap now, the wire arriving from `from` and leaving towards
  /// `to`: a sheave's tangents in its plane, an eye's point and deflection.
  [[nodiscard]] detail::SheaveWrap wrapNow(const Contact& contact, const Vec3d& from, const Vec3d& to) const;
  /// Contacts at the start of a step: their slip moves rest length across
  /// them, their tangents follow the points beside them, C returns to the
  /// bisector.
  void updateContacts();
  void recenterNode(std::size_t point);
  void leave(std::size_t point);
  /// Point k goes: its two segments become one (their rest lengths add).
  void erasePoint(std::size_t point);
  /// The segment `distance` (m of rest length, clamped) from the start and
  /// how far into it.
  void locate(double distance, std::size_t& segment, double& along) const;
  /// The point `along` (m of rest length) into segment k, on its straight part.
  [[nodiscard]] Vec3d pointOn(std::size_t segment, double along) const;
  /// Winch segments' rest lengths from their drums (restLengths_ holds the
  /// drums' free lengths between beginStep and the solve only).
  void syncWinchSegments();
  /// Gives each contact's slip and winch's drum a place in the store anew:
  /// their indices are into `drums` (winch `end`'s into `winchDrums[end]`).
  void placeDrums(const std::vector<detail::WireNodes::Drum>& drums,
                  const std::vector<detail::WireNodes::Drum>* winchDrums[2]);
  /// The contacts the points refer to, renumbered from 0 (contacts left
  /// behind by a wire that unwrapped are dropped).
  void keepContactsOf(const std::vector<Contact>& contacts);
  /// Where the wire's `end` is attached: a body-fixed point of the wire's
  /// simulation; throws unless that end is free.
  void checkFreeEnd(int end) const;
  /// Attaches the free `end` to `node` (body-fixed, on a body of the
  /// wire's simulation).
  void attachEnd(int end, ref_ptr<Node> node);
  void clearState();
  void shareRestLength(std::size_t point);
  /// The segment at the winch of end 0 (begin) or 1, when there is one.
  [[nodiscard]] std::size_t winchSegment(int end) const { return end == 0 ? 0 : restLengths_.size() - 1; }
  /// Rest length of segment k now: a winch's segment follows its drum.
  [[nodiscard]] double restLength(std::size_t k) const;
  void addDrums();
  /// Whether an inner node may leave: two winches keep a segment each.
  [[nodiscard]] bool removable() const { return !(winches_[0] && winches_[1] && restLengths_.size() <= 2); }
  /// Whether inner point k's segments may merge into one whose stretch row
  /// couples at most three bodies (writeRows): a segment between contacts
  /// on two bodies, or from a contact on a body to a winch, would couple four.
  [[nodiscard]] bool joinable(std::size_t k) const;
  /// The geometry a contact node routes the wire over; nullptr for an eye.
  [[nodiscard]] static const Geometry* routedGeometry(const Contact& contact) {
    return contact.node->getType() == Node::Type::CONTACT ? static_cast<const ContactNode&>(*contact.node).getGeometry()
                                                          : nullptr;
  }
  /// Whether lumped node k lies on the wire between two contact nodes on
  /// one geometry, with only lumped nodes between them (a wire over two
  /// edges of a box, along its top).
  [[nodiscard]] bool betweenContactsOnOneGeometry(std::size_t k) const;
  /// state_ for the points as they are now.
  void measurePoints(const StepContext& step);
  void limitNodeSpeeds(const StepContext& step);
  /// `stretchStiffness`: E·A of the wire (N).
  void writeWinchRows(RowWriter& rows, const StepContext& step, std::size_t firstRow, double stretchStiffness);
  void writeFrictionRows(RowWriter& rows, std::size_t firstRow);
  /// Young's modulus of the bend across the connection at end point k (Pa).
  [[nodiscard]] double connectionBendModulus(const ConnectingNode& node) const;
  /// Accumulates the twist of the connections' bodies over the last step.
  void measureTwist();
  /// The unit direction from end point k into the wire (its first segment).
  [[nodiscard]] Vec3d intoWire(std::size_t endPoint) const;

  /// Whether the wire may touch `geometry` now (setEnableCollisions).
  [[nodiscard]] bool touches(const Geometry& geometry) const;
  void writeGeometryContactRows(RowWriter& rows, const StepContext& step, std::size_t firstRow);

  /// Post-stabilization's threshold: a segment's length error as a share of
  /// its rest length (writeProjectionRows).
  static constexpr double kProjectionTolerance = 1e-3;
  /// The shortest free length a winch keeps, and the least length of wire a
  /// node weighs, as a share of the node spacing 1/resolution.
  static constexpr double kShortestSegment = 0.01;
  /// The bend rows' stiffness E I at most this many times E A l̄² (writeRows).
  static constexpr double kStiffestBend = 10.0;
  /// Lumped nodes a wire may reach (length × resolution): a longer route,
  /// or an end attached that far away, is refused.
  static constexpr double kMostNodes = 1e6;

  double radius_;
  double resolution_;
  ref_ptr<Material> material_;
  std::vector<ref_ptr<Node>> route_;
  ref_ptr<detail::WireNodes> nodes_ = new detail::WireNodes();
  std::vector<Point> points_;
  std::vector<double> restLengths_;    ///< per segment (points_[k], points_[k+1])
  std::vector<double> stretchImpulse_;  ///< per segment, last step (N·s)
  std::vector<double> bendImpulse_;     ///< two per inner point, last step (N·s)
  std::vector<char> bent_;              ///< per point: its bend rows were written this step
  std::vector<double> tension_;         ///< per segment (N)
  ref_ptr<Winch> winches_[2];           ///< at the begin and end, or none
  HighResolutionRange ranges_[2];       ///< from the begin and from the end
  std::vector<Contact> contacts_;
  /// A winch's rows of the last step: offsets in this wire's rows (−1:
  /// none) and impulses (N·s). `allIn` keeps some wire off the drum,
  /// `allOut` some on it.
  struct WinchRows {
    int motor = -1, allIn = -1, allOut = -1;
    double motorImpulse = 0.0, brakeImpulse = 0.0, allInImpulse = 0.0, allOutImpulse = 0.0;
  };
  WinchRows winchRows_[2];
  int twistRow_[2] = {-1, -1};  ///< a connection's twist row: offset in this wire's rows, −1: none
  /// writeRows' per-point scratch: where the wire arrives and leaves (the
  /// same but at a contact), velocity, lever arms of those from the body's
  /// center of mass, centripetal acceleration, solver index, and the
  /// solver index of a contact's slip (−1: none).
  struct PointState {
    Vec3d in, out, v, armIn, armOut, centripetal;
    int index = -1, slip = -1;
    bool broken = false;
  };
  std::vector<PointState> state_;
  bool collisions_ = true;
  std::vector<observer_ptr<Geometry>> noCollisions_;
  detail::WireGeometryContacts<S> geometryContacts_;
  std::vector<typename detail::WireGeometryContacts<S>::Segment> segments_;
  int geometryContactRow_ = -1;  ///< the first row of geometryContacts_ in this wire's rows
};

template <Scalar S>
WireT<S>::WireT(S radius, S resolutionPerUnitLength, ref_ptr<Material> material)
    : radius_(double(radius)), resolution_(double(resolutionPerUnitLength)),
      material_(material ? std::move(material) : ref_ptr<Material>(new Material("wire"))) {
  if (!(std::isfinite(radius) && radius > S(0))) throw error("radius must be finite and > 0 m", radius);
  if (!(std::isfinite(resolutionPerUnitLength) && resolutionPerUnitLength > S(0)))
    throw error("resolution must be finite and > 0 nodes per m", resolutionPerUnitLength);
}

template <Scalar S>
void WireT<S>::add(ref_ptr<Node> node) {
  if (!node) throw error("cannot route a null node", "nullptr");
  if (built()) throw error("is in a simulation: its route is fixed", route_.size());
  if (winches_[1]) throw error("ends at a winch: nothing may be routed after it", route_.size());
  route_.push_back(std::move(node));
}

template <Scalar S>
void WireT<S>::add(ref_ptr<Winch> winch, S pulledInLength) {
  if (!winch) throw error("cannot route a null winch", "nullptr");
  if (built()) throw error("is in a simulation: its route is fixed", route_.size());
  if (winches_[1]) throw error("ends at a winch: nothing may be routed after it", route_.size());
  if (winch->wire_) throw error("cannot route a winch that is already routed in a wire", winch->getName());
  if (!(std::isfinite(pulledInLength) && pulledInLength >= S(0)))
    throw error("pulled-in length must be finite and >= 0 m", pulledInLength);
  winches_[route_.empty() ? 0 : 1] = winch;
  route_.push_back(new BodyFixedNodeT<S>(winch->getRigidBody(), winch->getPosition()));
  winch->wire_ = this;
  winch->pulledIn_ = double(pulledInLength);
}

template <Scalar S>
void WireT<S>::add(ref_ptr<Link> link, const Vec3& position) {
  if (!link) throw error("cannot route a null link", "nullptr");
  add(link->makeConnection(position));
}

template <Scalar S>
void WireT<S>::setRadius(S radius) {
  if (!(std::isfinite(radius) && radius > S(0))) throw error("radius must be finite and > 0 m", radius);
  radius_ = double(radius);
  updateMasses();
}

template <Scalar S>
void WireT<S>::setMaterial(ref_ptr<Material> material) {
  if (!material) throw error("cannot use a null material", "nullptr");
  material_ = std::move(material);
  updateMasses();
}

template <Scalar S>
double WireT<S>::linearDensity() const {
  return double(material_->getBulkMaterial()->getDensity()) * std::numbers::pi * radius_ * radius_;
}

template <Scalar S>
S WireT<S>::getRestLength() const {
  double length = 0.0;
  if (built()) {
    for (std::size_t k = 0; k < restLengths_.size(); ++k) length += restLength(k);
  } else {
    for (std::size_t k = 0; k + 1 < route_.size(); ++k)
      length += (route_[k + 1]->getWorldPosition() - route_[k]->getWorldPosition()).template cast<double>().norm();
  }
  return S(length);
}

template <Scalar S>
S WireT<S>::getCurrentLength() const {
  double length = 0.0;
  for (std::size_t k = 0; k + 1 < points_.size(); ++k) length += segmentLength(k);
  return built() ? S(length) : getRestLength();
}

template <Scalar S>
S WireT<S>::getMass() const {
  return S(linearDensity() * double(getRestLength()));
}

template <Scalar S>
S WireT<S>::getTension(S distanceFromStart) const {
  if (tension_.empty()) return S(0);
  double along = double(distanceFromStart);
  std::size_t k = 0;
  while (k + 1 < tension_.size() && along > restLength(k)) along -= restLength(k++);
  return S(tension_[k]);
}

template <Scalar S>
auto WireT<S>::findPoint(S distanceFromStart) const -> Vec3 {
  if (!built()) throw error("is not in a simulation: it has no points yet");
  std::size_t k = 0;
  double along = 0.0;
  locate(double(distanceFromStart), k, along);
  return pointOn(k, along).template cast<S>();
}

template <Scalar S>
S WireT<S>::findDistance(const Vec3& point) const {
  if (!built()) throw error("is not in a simulation: it has no points yet");
  const Vec3d p = point.template cast<double>();
  double best = std::numeric_limits<double>::infinity(), distance = 0.0, start = 0.0;
  for (std::size_t k = 0; k + 1 < points_.size(); ++k) {
    const Vec3d a = departure(points_[k]), b = arrival(points_[k + 1]);
    const double span = (b - a).squaredNorm();
    const double t = span > 0.0 ? std::clamp((p - a).dot(b - a) / span, 0.0, 1.0) : 0.0;
    const double gap = (a + t * (b - a) - p).norm();
    if (gap < best) {
      best = gap;
      // Rest length in proportion to the length now, arcs included.
      const double length = segmentLength(k), rest = restLength(k);
      const double before = points_[k].contact >= 0 ? contacts_[std::size_t(points_[k].contact)].wrap.arcOut() : 0.0;
      const double at = before + t * (length - wrapped(k));
      distance = start + (length > 0.0 ? rest * at / length : 0.0);
    }
    start += restLength(k);
  }
  return S(distance);
}

template <Scalar S>
void WireT<S>::setResolutionPerUnitLength(S resolutionPerUnitLength) {
  if (!(std::isfinite(resolutionPerUnitLength) && resolutionPerUnitLength > S(0)))
    throw error("resolution must be finite and > 0 nodes per m", resolutionPerUnitLength);
  const double nodes = double(getRestLength()) * double(resolutionPerUnitLength);
  if (!(nodes <= kMostNodes)) throw error("would have more than 1e6 lumped nodes (length x resolution)", nodes);
  resolution_ = double(resolutionPerUnitLength);
}

template <Scalar S>
void WireT<S>::setHighResolutionRange(bool begin, S start, S end, S resolutionPerUnitLength) {
  if (!(std::isfinite(start) && std::isfinite(end) && start >= S(0) && start < end))
    throw error("high resolution range needs 0 <= start < end, finite m; got start", start);
  if (!(std::isfinite(resolutionPerUnitLength) && resolutionPerUnitLength > S(0)))
    throw error("high resolution range's resolution must be finite and > 0 nodes per m", resolutionPerUnitLength);
  const double nodes = (double(end) - double(start)) * double(resolutionPerUnitLength);
  if (!(nodes <= 1e6)) throw error("high resolution range would hold more than 1e6 lumped nodes", nodes);
  ranges_[begin ? 0 : 1] = HighResolutionRange{start, end, resolutionPerUnitLength};
}

template <Scalar S>
double WireT<S>::spacingOver(double from, double to, double spacing, double floor) const {
  const double length = double(getRestLength());
  for (int end = 0; end < 2; ++end) {
    const HighResolutionRange& range = ranges_[end];
    if (!(range.resolution > S(0))) continue;
    const double a = end == 0 ? double(range.start) : length - double(range.end);
    const double b = end == 0 ? double(range.end) : length - double(range.start);
    if (from < b && to > a) spacing = std::min(spacing, std::max(1.0 / double(range.resolution), floor));
  }
  return spacing;
}

template <Scalar S>
void WireT<S>::reverse() {
  std::reverse(route_.begin(), route_.end());
  std::swap(winches_[0], winches_[1]);
  std::swap(ranges_[0], ranges_[1]);
  if (!built()) return;
  std::swap(winchRows_[0], winchRows_[1]);
  std::reverse(points_.begin(), points_.end());
  std::reverse(restLengths_.begin(), restLengths_.end());
  std::reverse(stretchImpulse_.begin(), stretchImpulse_.end());
  std::reverse(tension_.begin(), tension_.end());
  std::reverse(bent_.begin(), bent_.end());
  bendImpulse_.assign(bendImpulse_.size(), 0.0);  // their directions follow the geometry anew
  geometryContacts_.clear();                        // their places along the wire were from the other end
  nodes_->reverseNodes();
  renumberNodes();
  // A wrap turns the other way; its slip, pending and moving, the other way along the wire.
  for (Contact& contact : contacts_) {
    detail::SheaveWrap& wrap = contact.wrap;
    wrap.sense = -wrap.sense;
    std::swap(wrap.in, wrap.out);
    detail::WireNodes::Drum& slip = nodes_->drum(contact.slip);
    slip.freeLength = -slip.freeLength;
    slip.speed = -slip.speed;
    contact.frictionImpulse = -contact.frictionImpulse;
  }
}

template <Scalar S>
double WireT<S>::restLength(std::size_t k) const {
  for (int end = 0; end < 2; ++end)
    if (winches_[end] && k == winchSegment(end)) return nodes_->drum(winches_[end]->drum_).freeLength;
  return restLengths_[k];
}

template <Scalar S>
auto WireT<S>::getPoints() const -> std::vector<Vec3> {
  std::vector<Vec3> points;
  points.reserve(points_.size() + contacts_.size());
  for (const Point& p : points_) {
    points.push_back(arrival(p).template cast<S>());
    if (p.contact >= 0 && contacts_[std::size_t(p.contact)].wrap.radius > 0.0)
      points.push_back(departure(p).template cast<S>());
  }
  return points;
}

template <Scalar S>
auto WireT<S>::worldPosition(const Point& p) const -> Vec3d {
  if (p.node >= 0) return nodes_->position(std::size_t(p.node));
  if (p.contact >= 0) {
    const detail::SheaveWrap& wrap = contacts_[std::size_t(p.contact)].wrap;
    return wrap.point(wrap.anchor);
  }
  if (p.body) return p.body->getFrame()->transformPointToWorld(p.local.template cast<S>()).template cast<double>();
  return p.local;
}

template <Scalar S>
auto WireT<S>::arrival(const Point& p) const -> Vec3d {
  if (p.contact < 0) return worldPosition(p);
  const detail::SheaveWrap& wrap = contacts_[std::size_t(p.contact)].wrap;
  return wrap.point(wrap.in);
}

template <Scalar S>
auto WireT<S>::departure(const Point& p) const -> Vec3d {
  if (p.contact < 0) return worldPosition(p);
  const detail::SheaveWrap& wrap = contacts_[std::size_t(p.contact)].wrap;
  return wrap.point(wrap.out);
}

template <Scalar S>
auto WireT<S>::worldVelocity(const Point& p) const -> Vec3d {
  if (p.node >= 0) return nodes_->velocity(std::size_t(p.node));
  if (const Body* body = bodyOf(p))
    return body->getVelocityAtPoint(worldPosition(p).template cast<S>()).template cast<double>();
  return Vec3d::Zero();
}

template <Scalar S>
double WireT<S>::segmentLength(std::size_t k) const {
  return (arrival(points_[k + 1]) - departure(points_[k])).norm() + wrapped(k);
}

template <Scalar S>
double WireT<S>::wrapped(std::size_t k) const {
  double arcs = 0.0;
  if (points_[k].contact >= 0) arcs += contacts_[std::size_t(points_[k].contact)].wrap.arcOut();
  if (points_[k + 1].contact >= 0) arcs += contacts_[std::size_t(points_[k + 1].contact)].wrap.arcIn();
  return arcs;
}

template <Scalar S>
void WireT<S>::placePlane(const ContactNode& node, detail::SheaveWrap& wrap) const {
  const GeometryT<S>& geometry = *node.getGeometry();
  const auto& cylinder = geometry.getShapes().front();
  const auto X = geometry.getTransform() * cylinder.transform;  // cylinder → world
  wrap.radius = double(static_cast<const CylinderT<S>&>(*cylinder.shape).getRadius());
  wrap.center = X.translation().template cast<double>();
  wrap.axis = (X.linear() * Vec3::UnitY()).template cast<double>();
  wrap.e1 = (X.linear() * Vec3::UnitX()).template cast<double>();
  wrap.e2 = (X.linear() * -Vec3::UnitZ()).template cast<double>();
}

template <Scalar S>
std::optional<detail::ShapeEdge> WireT<S>::edgeOf(const ContactNode& node) const {
  const auto& placed = node.getGeometry()->getShapes().front();
  const Vec3d local = (placed.transform.inverse() * node.getPosition()).template cast<double>();
  return detail::nearestShapeEdge(*placed.shape, local);
}

template <Scalar S>
auto WireT<S>::edgePoint(const Contact& contact, const Vec3d& from, const Vec3d& to) const -> Vec3d {
  const GeometryT<S>& geometry = *static_cast<const ContactNode&>(*contact.node).getGeometry();
  const auto X = geometry.getTransform() * geometry.getShapes().front().transform;  // shape → world
  const Vec3d a = (X * contact.edge.from.template cast<S>()).template cast<double>();
  const Vec3d b = (X * contact.edge.to.template cast<S>()).template cast<double>();
  return detail::shortestOverEdge(a, b, from, to);
}

template <Scalar S>
detail::SheaveWrap WireT<S>::wrapNow(const Contact& contact, const Vec3d& from, const Vec3d& to) const {
  detail::SheaveWrap wrap = contact.wrap;
  if (contact.node->getType() == Node::Type::EYE) {
    wrap.eye(contact.node->getWorldPosition().template cast<double>(), from, to);
  } else if (contact.onEdge) {
    wrap.eye(edgePoint(contact, from, to), from, to);
  } else {
    placePlane(static_cast<const ContactNode&>(*contact.node), wrap);
    wrap.place(from, to);
  }
  return wrap;
}

template <Scalar S>
void WireT<S>::checkRoute(const StepContext& simulation) const {
  if (route_.size() < 2) throw error("needs at least two route nodes", route_.size());
  for (std::size_t k = 0; k < route_.size(); ++k) {
    const Node& node = *route_[k];
    if (node.getType() == Node::Type::BODY_FIXED && k != 0 && k + 1 != route_.size())
      throw error("a BodyFixedNode may only be the first or last route node; it is node", k);
    if (node.getType() == Node::Type::CONNECTING) {
      if (k != 0 && k + 1 != route_.size())
        throw error("a ConnectingNode may only be the first or last route node; it is node", k);
      const Body& body = *node.getRigidBody();
      const bool bends = connectionBendModulus(static_cast<const ConnectingNode&>(node)) > 0.0;
      if (bends &&
          !((node.getWorldPosition() - body.getCmPosition()).norm() > S(1e-6) * (S(1) + node.getPosition().norm())))
        throw error("a ConnectingNode that holds the bend must be away from its body's center of mass; it is at",
                    node.getPosition());
    }
    if (node.getType() == Node::Type::EYE && (k == 0 || k + 1 == route_.size()))
      throw error("an EyeNode may not be the first or last route node; it is node", k);
    if (node.getType() == Node::Type::CONTACT) {
      if (k == 0 || k + 1 == route_.size()) throw error("a ContactNode may not be the first or last route node; it is node", k);
      const auto* contact = static_cast<const ContactNode*>(&node);
      const auto* shape = contact->getGeometry()->getShape();
      const bool sheave = shape && shape->getType() == ShapeType::CYLINDER;
      const auto edge = shape && !sheave ? edgeOf(*contact) : std::nullopt;
      if (!shape || contact->getGeometry()->getShapes().size() != 1 || (!sheave && !edge))
        throw error(
            "a ContactNode's geometry must hold one cylinder, box, convex, trimesh or height field (the shapes "
            "wires run over); node",
            k);
      if (!sheave && contact->getTurns() != 0) throw error("a ContactNode on an edge cannot take turns; node", k);
      if (k + 1 < route_.size() && route_[k + 1]->getType() == Node::Type::CONTACT &&
          static_cast<const ContactNode*>(route_[k + 1].get())->getGeometry() == contact->getGeometry() &&
          (sheave || edge->from == edgeOf(*static_cast<const ContactNode*>(route_[k + 1].get()))->from))
        throw error("consecutive ContactNodes on one cylinder or one edge (route it once); node", k);
    }
    if (node.getRigidBody() && simulation.indexOf(*node.getRigidBody()) < 0)
      throw error(("route node " + std::to_string(k) + " is fixed to a body not in the simulation").c_str(),
                  node.getRigidBody()->getName());
    if (k > 0 && !((node.getWorldPosition() - route_[k - 1]->getWorldPosition()).norm() > S(0)))
      throw error("consecutive route nodes coincide at", node.getWorldPosition());
  }
  if (winches_[0] && winches_[1] && route_.size() == 2 && double(getRestLength()) * resolution_ <= 1.0 + 1e-9)
    throw error("needs at least two segments between its two winches (length x resolution)",
                double(getRestLength()) * resolution_);
  // Hostile resolutions would allocate without bound.
  const double nodes = double(getRestLength()) * resolution_ + double(route_.size());
  if (!(nodes <= kMostNodes)) throw error("would have more than 1e6 lumped nodes (length x resolution)", nodes);
}

template <Scalar S>
void WireT<S>::prepare(const StepContext& simulation) {
  checkRoute(simulation);
  if (built()) return;
  const std::vector<ref_ptr<Node>> routed = route_;
  double pulledIn[2] = {0.0, 0.0};
  for (int end = 0; end < 2; ++end)
    if (winches_[end]) pulledIn[end] = winches_[end]->pulledIn_;
  try {
    build(simulation);
    feedTaut(simulation);
  } catch (...) {
    // Refused: the wire stays as routed (its store is not in the simulation yet).
    clearState();
    nodes_ = new detail::WireNodes();
    route_ = routed;
    for (int end = 0; end < 2; ++end) {
      if (!winches_[end]) continue;
      winches_[end]->pulledIn_ = pulledIn[end];
      winches_[end]->store_ = nullptr;
    }
    throw;
  }
}

// Auto-feed (WireWinchController::setEnableAutoFeed): between two held ends
// the routing points (free nodes) are dropped, the wire is built straight
// between the rest of its route, and its auto-feeding winches take in the
// length that made it slack (or pay out what the taut route needs more), in
// equal shares; the wire's length, free and on the drums, is unchanged.
template <Scalar S>
void WireT<S>::feedTaut(const StepContext& simulation) {
  const bool feeds[2] = {winches_[0] && winches_[0]->autoFeed_, winches_[1] && winches_[1]->autoFeed_};
  const auto held = [&](const Node& node) { return node.getType() != Node::Type::FREE; };
  if (!(feeds[0] || feeds[1]) || !held(*route_.front()) || !held(*route_.back())) return;
  std::vector<ref_ptr<Node>> taut;
  for (const auto& node : route_)
    if (held(*node)) taut.push_back(node);
  if (taut.size() == route_.size()) return;
  const double routedLength = double(getRestLength());
  clearState();
  nodes_ = new detail::WireNodes();
  route_ = std::move(taut);
  checkRoute(simulation);
  build(simulation);
  const double share = (routedLength - double(getRestLength())) / double(int(feeds[0]) + int(feeds[1]));
  for (int end = 0; end < 2; ++end) {
    if (!feeds[end]) continue;
    Winch& winch = *winches_[end];
    if (!(winch.pulledIn_ + share >= 0.0))
      throw error("auto-feed: the taut route needs more wire than the winch holds; m lacking",
                  -(winch.pulledIn_ + share));
    winch.pulledIn_ += share;
    nodes_->drum(winch.drum_).pulledIn = winch.pulledIn_;
  }
}

template <Scalar S>
double WireT<S>::spacing(const StepContext& step) const {
  const Vec3d start = points_.empty() ? route_.front()->getWorldPosition().template cast<double>()
                                      : worldPosition(points_.front());
  const double h = step.getTimeStep(), fall = step.gravity(start).norm() * h * h;
  return std::isfinite(fall) ? std::max(1.0 / resolution_, fall) : 1.0 / resolution_;
}

template <Scalar S>
void WireT<S>::build(const StepContext& simulation) {
  const double spacing = this->spacing(simulation);
  const auto world = [&](std::size_t k) -> Vec3d { return route_[k]->getWorldPosition().template cast<double>(); };
  // Contacts first: their wraps from the route, so that the wire between
  // route nodes runs along their tangents.
  std::vector<int> contactOf(route_.size(), -1);
  for (std::size_t k = 1; k + 1 < route_.size(); ++k) {
    const auto type = route_[k]->getType();
    if (type != Node::Type::CONTACT && type != Node::Type::EYE) continue;
    Contact contact;
    contact.node = static_cast<SlidingNode*>(route_[k].get());
    if (type == Node::Type::EYE) {
      contact.wrap.eye(world(k), world(k - 1), world(k + 1));
    } else if (const auto edge = edgeOf(static_cast<const ContactNode&>(*contact.node))) {
      contact.onEdge = true;
      contact.edge = *edge;
      contact.wrap.eye(edgePoint(contact, world(k - 1), world(k + 1)), world(k - 1), world(k + 1));
    } else {
      const auto& sheave = static_cast<const ContactNode&>(*contact.node);
      placePlane(sheave, contact.wrap);
      contact.wrap.route(world(k - 1), world(k), world(k + 1), sheave.getTurns());
    }
    contactOf[k] = int(contacts_.size());
    contacts_.push_back(contact);
  }
  const auto routePoint = [&](std::size_t k) {
    Point p;
    const Node& node = *route_[k];
    if (node.getType() == Node::Type::BODY_FIXED || node.getType() == Node::Type::CONNECTING) {
      p.body = node.getRigidBody();
      p.local = node.getPosition().template cast<double>();
      if (node.getType() == Node::Type::CONNECTING) {
        p.connecting = static_cast<ConnectingNode*>(route_[k].get());
        p.connecting->twist_ = p.connecting->twistImpulse_ = p.connecting->twistStep_ = 0.0;
      }
    } else if (contactOf[k] >= 0) {
      p.contact = contactOf[k];
    } else {
      p.node = int(nodes_->add(world(k), 0.0));
    }
    return p;
  };
  points_.push_back(routePoint(0));
  for (std::size_t k = 0; k + 1 < route_.size(); ++k) {
    const Vec3d a = departure(points_.back());
    const int contact = contactOf[k + 1];
    const Vec3d b = contact >= 0 ? contacts_[std::size_t(contact)].wrap.point(contacts_[std::size_t(contact)].wrap.in)
                                 : world(k + 1);
    // A mass node beside each contact keeps every row within three bodies;
    // two winches keep a segment each.
    const bool winchToWinch = winches_[0] && winches_[1] && route_.size() == 2;
    const int fewest = contactOf[k] >= 0 || contactOf[k + 1] >= 0 || winchToWinch ? 2 : 1;
    // The tangent points of a wrap can lie far from the routed points (a huge sheave).
    const double span = (b - a).norm() / spacing;
    if (!(span <= kMostNodes)) throw error("would have more than 1e6 lumped nodes on a span of its route; nodes", span);
    const int segments = std::max(fewest, int(std::ceil(span - 1e-9)));
    for (int i = 1; i < segments; ++i) {
      Point p;
      p.node = int(nodes_->add(a + (b - a) * (double(i) / segments), 0.0));
      points_.push_back(p);
    }
    points_.push_back(routePoint(k + 1));
  }
  for (std::size_t k = 1; k + 1 < points_.size(); ++k) {
    if (points_[k].contact < 0) continue;
    Contact& contact = contacts_[std::size_t(points_[k].contact)];
    contact.wrap = wrapNow(contact, departure(points_[k - 1]), arrival(points_[k + 1]));
    contact.wrap.reanchor();
    contact.node->wrap_ = contact.wrap.wrap;
  }
  for (std::size_t k = 0; k + 1 < points_.size(); ++k) restLengths_.push_back(segmentLength(k));
  stretchImpulse_.assign(restLengths_.size(), 0.0);
  bendImpulse_.assign(2 * points_.size(), 0.0);
  bent_.assign(points_.size(), 0);
  tension_.assign(restLengths_.size(), 0.0);
  updateMasses();
  addDrums();
}

// A drum's inertia is that of one node's length of wire, which moves with
// it through the winch; its free length is the winch segment's. A contact's
// slip has the same inertia: the wire sliding over the geometry.
template <Scalar S>
void WireT<S>::addDrums() {
  for (Contact& contact : contacts_) {
    detail::WireNodes::Drum slip;
    slip.mass = linearDensity() / resolution_;
    slip.winch = false;
    contact.slip = nodes_->addDrum(slip);
  }
  for (int end = 0; end < 2; ++end) {
    Winch* winch = winches_[end].get();
    if (!winch) continue;
    detail::WireNodes::Drum drum;
    drum.freeLength = restLengths_[winchSegment(end)];
    drum.pulledIn = winch->pulledIn_;
    drum.mass = linearDensity() / resolution_;
    winch->drum_ = nodes_->addDrum(drum);
    winch->store_ = nodes_;
  }
}

// A lumped node carries half of each segment beside it (ends fixed to a body
// or the world carry theirs into it).
template <Scalar S>
void WireT<S>::updateMasses() {
  if (!built()) return;
  const double density = linearDensity();
  for (std::size_t k = 0; k < points_.size(); ++k) {
    if (points_[k].node < 0) continue;
    double length = 0.0;
    if (k > 0) length += 0.5 * restLengths_[k - 1];
    if (k < restLengths_.size()) length += 0.5 * restLengths_[k];
    // Segments hauled in or slid over a contact to (almost) nothing leave a
    // node the mass of the shortest free length a winch keeps, not none.
    nodes_->setMass(std::size_t(points_[k].node), density * std::max(length, kShortestSegment / resolution_));
  }
}

// Adaptive resolution (agxWire's dynamic resolution; PHYSICS.md §3.3). A
// node of mass m between segments of length L under tension T is a
// transverse spring the velocity-level step integrates explicitly (the
// stretch rows turn with the geometry of the step's start); the wire's
// fastest mode, the zig-zag, has ω² = 4T/(L m), unstable once h²ω² > 4.
// A node with ρ = h²(T₁/L₁ + T₂/L₂)/m > 2 (that zig-zag bound) leaves: its
// two segments merge (rest lengths add), its mass and momentum go to its
// neighbours. A node beside a contact stays (the segment from a contact is
// not projected, writeProjectionRows: a crane's hook hung from its sheave
// on one segment settled 0.4% off m g), unless the wire runs from there
// to a contact on the same geometry (over two edges of a box, along its
// top, with which it does not collide: the nodes a slack wire gained there
// sank into the box and were flung off it by the next jolt of tension, a
// 1 kg load stopped at an edge with 100 kg bouncing on the wire).
// A segment longer than the wire's resolution asks for splits
// again where the node it would gain has ρ < 1 (hysteresis). The
// geometric-stiffness rows of writeRows hold what is left over (a node that
// cannot leave: next to both ends, or a tension that jumps within a step).
// A segment shorter than a quarter of the node spacing (wire hauled in at a
// winch, slid over a contact) loses a node; the node beside a contact stays
// and moves to the middle of its neighbours instead.
template <Scalar S>
void WireT<S>::beginStep(const StepContext& step) {
  if (points_.size() < 2) return;
  measureTwist();
  for (int end = 0; end < 2; ++end)
    if (winches_[end]) restLengths_[winchSegment(end)] = restLength(winchSegment(end));
  for (std::size_t k = 1; k + 1 < points_.size(); ++k) {
    if (points_[k].contact < 0) continue;
    detail::WireNodes::Drum& slip = nodes_->drum(contacts_[std::size_t(points_[k].contact)].slip);
    // No more than the segment it slides from holds (a failed solve's slip).
    const double travel = std::clamp(slip.freeLength, -restLengths_[k - 1], restLengths_[k]);
    restLengths_[k - 1] += travel;
    restLengths_[k] -= travel;
    slip.freeLength = 0.0;
  }
  bool changed = leaveBeforeContacts(step.getTimeStep());
  const double h2 = step.getTimeStep() * step.getTimeStep();
  const auto pull = [&](std::size_t segment) {
    const double length = segmentLength(segment);
    return length > 0.0 ? std::max(tension_[segment], 0.0) / length : 0.0;
  };
  // A node on a segment that touched a geometry stays: without it the
  // straight segment across its neighbours would cut into the geometry.
  double before = 0.0;  // of point k − 1, from the start (m of rest length)
  for (std::size_t k = 1; k + 1 < points_.size(); ++k) {
    const Point& p = points_[k];
    const double at = before + restLengths_[k - 1], after = at + restLengths_[k];
    const bool touched = geometryContacts_.touchedBetween(before, after);
    before = at;
    if (p.node < 0 || touched || (nextToContact(k) && !betweenContactsOnOneGeometry(k))) continue;
    const double rho = h2 * (pull(k - 1) + pull(k)) / nodes_->mass(std::size_t(p.node));
    if (rho > 2.0 && removable() && joinable(k)) {
      removeNode(k);
      changed = true;
      before = after;
    }
  }
  const double target = spacing(step), density = linearDensity();
  const double floor = std::min(target, step.gravity(worldPosition(points_.front())).norm() * h2);
  const bool ranged = ranges_[0].resolution > S(0) || ranges_[1].resolution > S(0);
  // Segment k's wanted spacing, `from` its start (m of rest length).
  const auto wanted = [&](std::size_t k, double from) {
    return ranged ? spacingOver(from, from + restLengths_[k], target, floor) : target;
  };
  double from = 0.0;
  for (std::size_t k = 0; k + 1 < points_.size(); from += restLengths_[k], ++k) {
    // A wrap's arc holds no node: the straight part is split.
    const double straight = restLengths_[k] - wrapped(k);
    if (straight < 1.999 * wanted(k, from) || !std::isfinite(segmentLength(k))) continue;
    // The node a split would add: mass ρ_l L/2, between halves of L/2.
    const double rho = h2 * 4.0 * std::max(tension_[k], 0.0) / straight / (density * straight / 2.0);
    if (rho < 1.0) {
      splitSegment(k);
      changed = true;
      from += restLengths_[k];
      ++k;
    }
  }
  changed = splitAtGeometryContacts(target) || changed;
  const auto innerNode = [&](std::size_t k) { return k > 0 && k + 1 < points_.size() && points_[k].node >= 0; };
  from = 0.0;
  for (std::size_t k = 0; k + 1 < points_.size(); from += restLengths_[k], ++k) {
    if (restLengths_[k] - wrapped(k) >= 0.25 * wanted(k, from)) continue;
    // A node not beside a contact goes (the segments beside it merge);
    // else the one beside a contact moves to the middle of its neighbours
    // (it would stay bunched up with a node before it).
    bool mended = false;
    for (const std::size_t end : {k + 1, k}) {
      if (mended || !innerNode(end) || nextToContact(end) || !removable()) continue;
      removeNode(end);
      mended = true;
    }
    for (const std::size_t end : {k + 1, k}) {
      if (mended || !innerNode(end) || !nextToContact(end)) continue;
      recenterNode(end);
      mended = true;
    }
    changed = changed || mended;
    // Segments merged or moved: segment k + 1 starts where the ones before it end.
    if (mended && ranged) from = std::accumulate(restLengths_.begin(), restLengths_.begin() + std::ptrdiff_t(k), 0.0);
  }
  if (changed) updateMasses();
  updateContacts();
  for (int end = 0; end < 2; ++end)
    if (winches_[end]) nodes_->drum(winches_[end]->drum_).freeLength = restLengths_[winchSegment(end)];
}

// A lumped node closing on a contact beside it by more than half their gap
// in one step leaves (its segments merge) before it reaches the contact.
// Nothing else stops it there: the stretch row holds the segment's length,
// not its sense, and the slip carries rest length across the contact
// freely, so a node that passes the contact's point within a step turns
// the wire around the edge the wrong way (a wire running at 3 m/s down a
// sloped top over an edge 1/5 m from its last node: the wrap jumped from
// 1.37 to 1.77 rad and the loads were thrown, then blew up).
template <Scalar S>
bool WireT<S>::leaveBeforeContacts(double timeStep) {
  bool changed = false;
  for (std::size_t k = 1; k + 1 < points_.size(); ++k) {
    if (points_[k].node < 0 || !removable() || !joinable(k)) continue;
    const Vec3d position = nodes_->position(std::size_t(points_[k].node));
    const Vec3d velocity = nodes_->velocity(std::size_t(points_[k].node));
    for (const std::size_t c : {k - 1, k + 1}) {
      if (points_[c].contact < 0) continue;
      const Vec3d gap = (c > k ? arrival(points_[c]) : departure(points_[c])) - position;
      const double closing = (velocity - worldVelocity(points_[c])).dot(gap);
      if (!(closing * timeStep > 0.5 * gap.squaredNorm())) continue;
      removeNode(k--);
      changed = true;
      break;
    }
  }
  return changed;
}

// Contact-driven resolution: a straight segment cannot bend around the
// geometry it touches (under tension its nodes leave, and the segment
// between the ones left cuts into the geometry). Where a segment touched a
// geometry in the last step away from its ends, it gains a node at that
// point, unless a piece would be shorter than a third of the node spacing
// (the short-segment pass merges pieces under a quarter).
template <Scalar S>
bool WireT<S>::splitAtGeometryContacts(double spacing) {
  bool changed = false;
  const double shortest = spacing / 3.0;
  for (const auto& touch : geometryContacts_.points()) {
    if (!geometryContacts_.touching(touch)) continue;
    std::size_t k = 0;
    double along = 0.0;
    locate(touch.distance, k, along);
    if (points_[k].contact >= 0 || points_[k + 1].contact >= 0) continue;
    const double rest = restLength(k);
    if (!(along > shortest && rest - along > shortest)) continue;
    splitSegment(k, along / rest);
    changed = true;
  }
  return changed;
}

template <Scalar S>
void WireT<S>::updateContacts() {
  for (std::size_t k = 1; k + 1 < points_.size(); ++k) {
    if (points_[k].contact < 0) continue;
    Contact& contact = contacts_[std::size_t(points_[k].contact)];
    detail::SheaveWrap wrap = wrapNow(contact, departure(points_[k - 1]), arrival(points_[k + 1]));
    if (wrap.radius > 0.0) {
      const auto end = [](const Point& p) { return p.node < 0 && p.contact < 0; };
      if (k == 1 && end(points_[0])) wrap.holdEnd(contact.wrap, worldPosition(points_[0]), true);
      if (k + 2 == points_.size() && end(points_.back()))
        wrap.holdEnd(contact.wrap, worldPosition(points_.back()), false);
    }
    // Beside a body whose state is not finite (frozen), the wrap stays as it was.
    if (!(std::isfinite(wrap.in) && std::isfinite(wrap.out) && wrap.center.allFinite() && wrap.e1.allFinite() &&
          wrap.e2.allFinite()))
      continue;
    contact.wrap = wrap;
    if (contact.wrap.wrap < 0.0) {
      leave(k--);
      continue;
    }
    const double moved = contact.wrap.reanchor();
    restLengths_[k - 1] -= moved;
    restLengths_[k] += moved;
    contact.node->wrap_ = contact.wrap.wrap;
  }
}

// The wire has unwrapped past the tangent line: it no longer touches the
// geometry. The contact's segments merge (their rest lengths add) and it
// leaves the wire for good (a wire is not yet put back on a geometry it
// meets again); its slip stops.
template <Scalar S>
void WireT<S>::leave(std::size_t k) {
  Contact& contact = contacts_[std::size_t(points_[k].contact)];
  contact.node->wrap_ = 0.0;
  contact.row = -1;
  nodes_->drum(contact.slip).speed = 0.0;
  erasePoint(k);
}

template <Scalar S>
bool WireT<S>::joinable(std::size_t k) const {
  // What a stretch row from point k − 1 to point k + 1 moves: each end's
  // node or body (a contact's: its geometry's), a contact's slip, a winch's drum.
  std::array<const void*, 6> coupled{};
  std::size_t count = 0;
  const auto couple = [&](const void* thing) {
    if (thing && std::find(coupled.begin(), coupled.begin() + std::ptrdiff_t(count), thing) ==
                     coupled.begin() + std::ptrdiff_t(count))
      coupled[count++] = thing;
  };
  for (const std::size_t end : {k - 1, k + 1}) {
    const Point& p = points_[end];
    couple(p.node >= 0 ? static_cast<const void*>(&p) : bodyOf(p));
    if (p.contact >= 0) couple(&contacts_[std::size_t(p.contact)]);
  }
  if (winches_[0] && k == 1) couple(winches_[0].get());
  if (winches_[1] && k + 2 == points_.size()) couple(winches_[1].get());
  return count <= 3;
}

template <Scalar S>
bool WireT<S>::betweenContactsOnOneGeometry(std::size_t k) const {
  std::size_t first = k, last = k;
  while (first > 0 && points_[first].node >= 0) --first;
  while (last + 1 < points_.size() && points_[last].node >= 0) ++last;
  const auto geometryOf = [&](const Point& p) {
    return p.contact >= 0 ? routedGeometry(contacts_[std::size_t(p.contact)]) : nullptr;
  };
  const Geometry* geometry = geometryOf(points_[first]);
  return geometry && geometry == geometryOf(points_[last]);
}

template <Scalar S>
void WireT<S>::erasePoint(std::size_t k) {
  restLengths_[k - 1] += restLengths_[k];
  restLengths_.erase(restLengths_.begin() + std::ptrdiff_t(k));
  stretchImpulse_.erase(stretchImpulse_.begin() + std::ptrdiff_t(k));
  tension_.erase(tension_.begin() + std::ptrdiff_t(k));
  bendImpulse_.erase(bendImpulse_.begin() + std::ptrdiff_t(2 * k), bendImpulse_.begin() + std::ptrdiff_t(2 * k + 2));
  bent_.erase(bent_.begin() + std::ptrdiff_t(k));
  points_.erase(points_.begin() + std::ptrdiff_t(k));
}

// Splits the rest length of the segments beside point k in proportion to
// their lengths now, so that both are stretched alike.
template <Scalar S>
void WireT<S>::shareRestLength(std::size_t k) {
  const double total = restLengths_[k - 1] + restLengths_[k];
  const double before = segmentLength(k - 1), after = segmentLength(k);
  const bool measured = std::isfinite(before + after) && before + after > 0.0;
  restLengths_[k - 1] = measured ? total * before / (before + after) : 0.5 * total;
  restLengths_[k] = total - restLengths_[k - 1];
}

template <Scalar S>
void WireT<S>::recenterNode(std::size_t k) {
  const std::size_t node = std::size_t(points_[k].node);
  const Vec3d middle = 0.5 * (departure(points_[k - 1]) + arrival(points_[k + 1]));
  if (middle.allFinite()) nodes_->setPosition(node, middle);
  shareRestLength(k);
}

template <Scalar S>
void WireT<S>::removeNode(std::size_t k) {
  // Half of the node's mass and momentum goes to each neighbouring node (the
  // half towards a body's or the world's end is lost): the rest of this
  // pass judges the neighbours with those masses, and updateMasses then
  // gives each its exact share of the merged segment.
  const std::size_t node = std::size_t(points_[k].node);
  const double mass = nodes_->mass(node);
  const Vec3d momentum = 0.5 * mass * nodes_->velocity(node);
  for (const std::size_t other : {k - 1, k + 1}) {
    if (points_[other].node < 0) continue;
    const std::size_t n = std::size_t(points_[other].node);
    nodes_->setVelocity(n, (nodes_->mass(n) * nodes_->velocity(n) + momentum) / (nodes_->mass(n) + 0.5 * mass));
    nodes_->setMass(n, nodes_->mass(n) + 0.5 * mass);
  }
  stretchImpulse_[k - 1] = 0.5 * (stretchImpulse_[k - 1] + stretchImpulse_[k]);
  tension_[k - 1] = 0.5 * (tension_[k - 1] + tension_[k]);
  nodes_->erase(node);
  erasePoint(k);
  renumberNodes();
}

template <Scalar S>
void WireT<S>::splitSegment(std::size_t k, double fraction) {
  std::size_t node = 0;  // the new node's index: the mass nodes before it
  for (std::size_t i = 0; i <= k; ++i) node += points_[i].node >= 0 ? 1 : 0;
  const Vec3d position = (1.0 - fraction) * departure(points_[k]) + fraction * arrival(points_[k + 1]);
  const Vec3d velocity = (1.0 - fraction) * worldVelocity(points_[k]) + fraction * worldVelocity(points_[k + 1]);
  nodes_->insert(node, position, velocity, 0.0);
  Point p;
  p.node = int(node);
  points_.insert(points_.begin() + std::ptrdiff_t(k + 1), p);
  restLengths_.insert(restLengths_.begin() + std::ptrdiff_t(k + 1), 0.0);
  stretchImpulse_.insert(stretchImpulse_.begin() + std::ptrdiff_t(k + 1), stretchImpulse_[k]);
  tension_.insert(tension_.begin() + std::ptrdiff_t(k + 1), tension_[k]);
  bendImpulse_.insert(bendImpulse_.begin() + std::ptrdiff_t(2 * (k + 1)), 2, 0.0);
  bent_.insert(bent_.begin() + std::ptrdiff_t(k + 1), 0);
  renumberNodes();
  shareRestLength(k + 1);
}

template <Scalar S>
void WireT<S>::renumberNodes() {
  int next = 0;
  for (Point& p : points_)
    if (p.node >= 0) p.node = next++;
}

template <Scalar S>
void WireT<S>::measurePoints(const StepContext& step) {
  const std::size_t n = points_.size();
  state_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const Point& p = points_[k];
    PointState& s = state_[k];
    s.in = arrival(p);
    s.out = departure(p);
    s.v = worldVelocity(p);
    s.armIn.setZero();
    s.armOut.setZero();
    s.centripetal.setZero();
    s.index = -1;
    s.slip = p.contact >= 0 ? step.indexOf(*nodes_, nodes_->numNodes() + contacts_[std::size_t(p.contact)].slip) : -1;
    if (p.node >= 0) {
      s.index = step.indexOf(*nodes_, std::size_t(p.node));
    } else if (const Body* body = bodyOf(p)) {
      s.index = step.indexOf(*body);
      if (s.index < 0) throw error("is fixed to or wraps a body that left the simulation", body->getName());
      const Vec3d center = body->getCmPosition().template cast<double>();
      s.armIn = s.in - center;
      s.armOut = s.out - center;
      // The point's radial drop over the step, r(1 − cos φ) for the turn
      // φ = |ω|h, as an acceleration: ω×(ω×r) scaled by (1 − cos φ)/(φ²/2),
      // 1 for small turns, bounded (≤ 4/φ²) for a body spinning a radian
      // or more in a step, where the Taylor term alone grows as φ².
      const Vec3d w = body->getAngularVelocity().template cast<double>();
      s.centripetal = detail::turnShare(w.norm(), step.getTimeStep()) * w.cross(w.cross(s.armOut));
    }
    // A body whose state is not finite (the simulation freezes it) holds
    // nothing: rows at it are written empty, so that they keep their places.
    s.broken = !(s.in.allFinite() && s.out.allFinite() && s.v.allFinite() && s.centripetal.allFinite() &&
                 s.armIn.allFinite() && s.armOut.allFinite());
    if (s.broken) s.index = -1;
  }
}

// No part of a wire moves against its neighbours faster than a stretch
// wave runs along it, c = √(E/ρ) (5 km/s in steel): a swinging or whipping
// wire's transverse waves are slower by √strain. What breaks that bound is a
// step that cannot hold the wire (a kinematic body spinning a sheave the
// wire wraps at 1.2 rad a step, a body tearing a stiff wire): its nodes,
// shot out by stretch rows linearized at the step's start, left farther each
// step, to inf in 10 to 30 steps (fuzz findings). The node store keeps them
// to c, so that such a wire stays finite; its tension is then whatever its
// stretch says.
template <Scalar S>
void WireT<S>::limitNodeSpeeds(const StepContext& step) {
  const double c = std::sqrt(stretchStiffness() / linearDensity());
  std::vector<Vec3d>& references = nodes_->speedReferences();
  std::fill(references.begin(), references.end(), Vec3d::Zero());
  const std::size_t n = points_.size();
  for (std::size_t k = 0; k < n; ++k) {
    if (points_[k].node < 0) continue;
    Vec3d sum = Vec3d::Zero();
    int count = 0;
    for (const std::size_t j : {k - 1, k + 1}) {
      if (j >= n || !state_[j].v.allFinite()) continue;  // k − 1 wraps past 0 at the first point
      sum += state_[j].v;
      ++count;
    }
    references[std::size_t(points_[k].node)] =
        count > 0 ? Vec3d(sum / count) : nodes_->velocity(std::size_t(points_[k].node));
  }
  nodes_->limitSpeeds(std::isfinite(c) && c > 0.0 ? c : 0.0, step.getTimeStep());
}

template <Scalar S>
void WireT<S>::writeRows(RowWriter& rows, const StepContext& step) {
  if (!built()) return;  // merged into another wire
  const std::size_t n = points_.size(), firstRow = rows.size();
  measurePoints(step);
  limitNodeSpeeds(step);
  const auto drumIndex = [&](std::size_t segment) {
    for (int end = 0; end < 2; ++end)
      if (winches_[end] && segment == winchSegment(end))
        return step.indexOf(*nodes_, nodes_->numNodes() + winches_[end]->drum_);
    return -1;
  };
  const typename Material::WireMaterial& wire = *material_->getWireMaterial();
  const double stretchStiffness = this->stretchStiffness();
  // Stretch: g = l_k − L_k, L_k the length along the wire (with the arcs of
  // wraps at its ends): written so that a tension is a positive impulse,
  // which a contact's friction row follows (RowWriter::setFriction). At a
  // winch, l_k is the drum's degree of freedom (∂g/∂l = 1); a contact's slip
  // moves rest length from the segment after it to the one before
  // (∂g/∂s = 1 before, −1 after). Across a wrap, the length's derivative is
  // the tangent's direction at the tangent point (which the geometry's body
  // carries with C).
  // An end fixed to a body is pulled at a point that turns with it: a
  // light body hung off its center at high tension is a stiff spring
  // (solver/geometric_stiffness.hpp).
  const auto fixedToBody = [&](std::size_t i) { return points_[i].node < 0 && points_[i].contact < 0; };
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const Vec3d d = state_[k + 1].in - state_[k].out;
    const double straight = d.norm();
    const double violation = restLengths_[k] - segmentLength(k);
    if (state_[k].broken || state_[k + 1].broken || !std::isfinite(straight) || !std::isfinite(violation)) {
      detail::Row& r = rows.add(stretchImpulse_[k]);
      r.compliance = segmentCompliance(k, stretchStiffness);
      continue;
    }
    const Vec3d u = straight > 0.0 ? Vec3d(d / straight) : Vec3d::UnitX();
    detail::WireRowBodies bodies;
    bodies.add(state_[k].index, u, state_[k].armOut, fixedToBody(k));
    bodies.add(state_[k + 1].index, -u, state_[k + 1].armIn, fixedToBody(k + 1));
    bodies.add(drumIndex(k), Vec3d::UnitX(), Vec3d::Zero());
    bodies.add(state_[k].slip, -Vec3d::UnitX(), Vec3d::Zero());
    bodies.add(state_[k + 1].slip, Vec3d::UnitX(), Vec3d::Zero());
    if (bodies.overflow) throw error("has a segment whose row would couple more than three bodies; segment", k);
    detail::Row& r = rows.add(stretchImpulse_[k]);
    bodies.write(rows, r);
    r.violation = violation;
    r.compliance = segmentCompliance(k, stretchStiffness);
    r.damping = double(wire.getDampingStretch());
    // κ = ½vᵀ∇²g v = ½(|ḋ⊥|²/|d| + u·(p̈_b − p̈_a)) with the body points'
    // centripetal accelerations ω×(ω×r) (SecondOrder::curvature): a segment
    // turning at speed lengthens at second order, which the step then holds.
    // The turning term as the exact lengthening of a segment whose ends part
    // across it at |ḋ⊥| for a step, √(|d|² + s²) − |d| = s²/(√(|d|² + s²) + |d|)
    // with s = |ḋ⊥|h, over h²: the Taylor term |ḋ⊥|²/(2|d|) for turns well
    // below a radian. Beyond, no motion along the step's start direction u
    // keeps the length, and the term's pull along u only shoots the nodes (a
    // body spinning at 25 rad/s dragging a wire from 1.3 m off its center:
    // its 6 cm segment at the body would turn 9 rad, and the Taylor term's
    // 140 m/s of shortening tripled the body's energy in one step, then blew
    // it up): the step's second-order change h²κ stays within half the
    // segment's length.
    if (straight > 0.0 && points_[k].contact < 0 && points_[k + 1].contact < 0) {
      const double h = step.getTimeStep();
      const Vec3d rate = state_[k + 1].v - state_[k].v;
      const Vec3d across = rate - u * u.dot(rate);
      const double turning = detail::partingCurvature(across.norm(), straight, h);
      const double relative = u.dot(state_[k + 1].centripetal - state_[k].centripetal);
      const double curvature = -detail::halfLengthBound(turning + 0.5 * relative, straight, h);
      if (std::isfinite(curvature)) rows.setCurvature(rows.size() - 1, curvature);
    }
  }
  // Bend: g = e·(t₂ − t₁) for the two directions e across the mean tangent;
  // ½(EI/l̄)|t₂ − t₁|² is the bending energy of the turn (curvature |t₂ − t₁|/l̄
  // over the length l̄), so the compliance is l̄/(E I). A clamped end
  // (ConnectingNode) bends between the line from its body's center of mass
  // and the wire, over l̄ = half its segment (none of the wire inside the body).
  // A bend is at most ten times as stiff as the stretch over its length l̄:
  // E I ≤ 10 E A l̄² (a node's transverse bend stiffness ~4EI/l³ at most
  // forty times its segments' axial EA/l; for equal moduli, any node spacing
  // above a sixth of the radius). Stiffer, the linearized bend rows turn
  // segments about their nodes faster than the stretch rows hold their
  // lengths and the wire grows step by step: a rubber-soft stretch modulus
  // (1e3 Pa) under a bend modulus of 1e8 Pa or more grew a 2 m wire released
  // level past 100 m (the node spacing, 0.1 m, twice the radius: EI 6e3 to
  // 2e6 times EA l̄²; fine at 600 times).
  const double areaMoment = std::numbers::pi * std::pow(radius_, 4) / 4.0;
  const double bendStiffness = double(wire.getYoungsModulusBend()) * areaMoment;
  const auto bendCompliance = [&](double length, double stiffness) {
    return length / std::min(stiffness, kStiffestBend * stretchStiffness * length * length);
  };
  struct BendPoint {
    int index;
    Vec3d arm;
  };
  const auto writeBend = [&](std::size_t k, const Vec3d& d1, const Vec3d& d2, const BendPoint& before,
                             const BendPoint& at, const BendPoint& after, double compliance) {
    const double l1 = d1.norm(), l2 = d2.norm();
    const Vec3d t1 = d1 / l1, t2 = d2 / l2;
    const Vec3d mean = t1 + t2;
    const Vec3d axis = mean.norm() > 1e-6 ? Vec3d(mean.normalized()) : t1;
    const Vec3d turn = (t2 - t1) - axis * axis.dot(t2 - t1);
    const Vec3d inPlane = turn.norm() > 1e-9 ? Vec3d(turn.normalized()) : Vec3d(axis.unitOrthogonal());
    const Vec3d outOfPlane = axis.cross(inPlane);
    for (std::size_t i = 0; i < 2; ++i) {
      const Vec3d& e = i == 0 ? inPlane : outOfPlane;
      const Vec3d a0 = (e - t1 * t1.dot(e)) / l1, a2 = (e - t2 * t2.dot(e)) / l2;
      detail::WireRowBodies bodies;
      bodies.add(at.index, -(a0 + a2), at.arm);
      bodies.add(before.index, a0, before.arm);
      bodies.add(after.index, a2, after.arm);
      detail::Row& r = rows.add(bendImpulse_[2 * k + i]);
      bodies.write(rows, r);
      r.violation = e.dot(t2 - t1);
      r.compliance = compliance;
      r.damping = double(wire.getDampingBend());
    }
  };
  for (std::size_t k = 0; k < n; ++k) {
    bent_[k] = 0;
    if (!(bendStiffness > 0.0) || n < 2) continue;
    const bool inner = k > 0 && k + 1 < n;
    if (inner) {
      const Vec3d d1 = state_[k].in - state_[k - 1].out, d2 = state_[k + 1].in - state_[k].out;
      // A contact shapes the wire around its geometry: no bend rows there.
      const double length = 0.5 * (restLengths_[k - 1] + restLengths_[k]);
      if (!(d1.norm() > 0.0 && d2.norm() > 0.0 && length > 0.0) || points_[k].contact >= 0 || state_[k - 1].broken ||
          state_[k].broken || state_[k + 1].broken)
        continue;
      bent_[k] = 1;
      writeBend(k, d1, d2, {state_[k - 1].index, state_[k - 1].armOut}, {state_[k].index, state_[k].armIn},
                {state_[k + 1].index, state_[k + 1].armIn}, bendCompliance(length, bendStiffness));
      continue;
    }
    const std::size_t other = k == 0 ? 1 : k - 1;
    const ConnectingNode* connecting = points_[k].connecting;
    if (!connecting || state_[k].broken || state_[other].broken || state_[k].index < 0) continue;
    const double connectionStiffness = connectionBendModulus(*connecting) * areaMoment;
    if (!(connectionStiffness > 0.0)) continue;
    const Vec3d center = state_[k].out - state_[k].armOut;  // the body's center of mass
    const Vec3d socket = k == 0 ? Vec3d(state_[k].out - center) : Vec3d(center - state_[k].in);
    const Vec3d wireSide = k == 0 ? Vec3d(state_[1].in - state_[0].out) : Vec3d(state_[k].in - state_[other].out);
    const double length = 0.5 * restLengths_[k == 0 ? 0 : k - 1];
    if (!(socket.norm() > 1e-9 && wireSide.norm() > 0.0 && length > 0.0)) continue;
    bent_[k] = 1;
    const double compliance = bendCompliance(length, connectionStiffness);
    const BendPoint body{state_[k].index, Vec3d::Zero()}, end{state_[k].index, state_[k].armOut};
    const BendPoint beside{state_[other].index, k == 0 ? state_[other].armIn : state_[other].armOut};
    if (k == 0)
      writeBend(k, socket, wireSide, body, end, beside, compliance);
    else
      writeBend(k, wireSide, socket, beside, end, body, compliance);
  }
  // Geometric stiffness (Tournier et al., SIGGRAPH 2015; Andrews et al.
  // 2017): a segment under tension T resists its ends' motion across it
  // with stiffness K = (T/L)(I − uuᵀ). The stretch row turns with the step's
  // start geometry, which integrates that stiffness explicitly: unstable
  // once h²K/m passes ~1, for nodes that beginStep could not remove. Its
  // implicit part −h²K v⁺ is two velocity rows across the segment, target
  // 0, viscosity L/(hT) (row.hpp: force −G v⁺/γ), from last step's tension:
  // backward Euler in the geometry, which damps only the ends' relative
  // motion across the segment. Weighted by max(0, 1 − 1/ρ),
  // ρ = h²(T/L)(1/m_a + 1/m_b), as solver/geometric_stiffness.hpp does for
  // rigid bodies: a segment the explicit step resolves keeps its undamped
  // dynamics.
  const double h = step.getTimeStep();
  const auto inverseMass = [&](const Point& p) {
    if (p.node >= 0) return 1.0 / nodes_->mass(std::size_t(p.node));
    const Body* body = bodyOf(p);
    if (body && body->getMotionControl() == Body::MotionControl::DYNAMICS)
      return 1.0 / double(body->getMassProperties()->getMass());
    return 0.0;
  };
  for (std::size_t k = 0; k + 1 < n; ++k) {
    const Vec3d d = state_[k + 1].in - state_[k].out;
    const double length = d.norm(), tension = tension_[k];
    if (!(length > 0.0 && tension > 0.0) || state_[k].broken || state_[k + 1].broken) continue;
    const double rho = h * h * tension / length * (inverseMass(points_[k]) + inverseMass(points_[k + 1]));
    if (!(rho > 1.0)) continue;
    const double weight = 1.0 - 1.0 / rho;
    const Vec3d u = d / length, e1 = u.unitOrthogonal(), e2 = u.cross(e1);
    for (const Vec3d& e : {e1, e2}) {
      detail::WireRowBodies bodies;
      bodies.add(state_[k].index, -e, state_[k].armOut);
      bodies.add(state_[k + 1].index, e, state_[k + 1].armIn);
      if (bodies.count == 0) continue;
      detail::Row& r = rows.add();
      bodies.write(rows, r);
      r.holonomic = false;
      r.speed = 0.0;
      r.compliance = length / (weight * h * tension);
    }
  }
  // Twist at a connection: g = φ, the body's rotation about the wire since
  // it was connected (measureTwist), against the torsional stiffness G J/L of
  // the whole wire (J = πr⁴/2), its far end held.
  const double twistRigidity = std::numbers::pi * std::pow(radius_, 4) / 2.0 / double(getRestLength());
  for (int end = 0; end < 2; ++end) {
    twistRow_[end] = -1;
    const std::size_t k = end == 0 ? 0 : n - 1;
    ConnectingNode* connecting = points_[k].connecting;
    if (!connecting) continue;
    connecting->twistStep_ = h;
    const double stiffness = double(connecting->getTwistStiffness()) * twistRigidity;
    const Vec3d axis = intoWire(k);
    if (!(stiffness > 0.0) || state_[k].index < 0 || !axis.allFinite()) continue;
    twistRow_[end] = int(rows.size() - firstRow);
    detail::Row& r = rows.add(connecting->twistImpulse_);
    r.body1 = state_[k].index;
    r.J1 << 0.0, 0.0, 0.0, axis.x(), axis.y(), axis.z();
    r.violation = connecting->twist_;
    r.compliance = 1.0 / stiffness;
    r.damping = double(wire.getDampingBend());
  }
  writeWinchRows(rows, step, firstRow, stretchStiffness);
  writeFrictionRows(rows, firstRow);
  writeGeometryContactRows(rows, step, firstRow);
}

template <Scalar S>
double WireT<S>::connectionBendModulus(const ConnectingNode& node) const {
  const double wire = double(material_->getWireMaterial()->getYoungsModulusBend());
  return node.hasBendStiffness() ? std::min(double(node.getBendStiffness()), wire) : wire;
}

template <Scalar S>
auto WireT<S>::intoWire(std::size_t k) const -> Vec3d {
  const Vec3d d = k == 0 ? Vec3d(arrival(points_[1]) - departure(points_[0]))
                         : Vec3d(departure(points_[k - 1]) - arrival(points_[k]));
  const double length = d.norm();
  return length > 0.0 ? Vec3d(d / length) : Vec3d::Constant(std::numeric_limits<double>::quiet_NaN());
}

// The body's angular velocity of the last step turned it by hω about the
// wire; summed, that is its twist (the wire's direction changes slowly
// against the body's spin about it).
template <Scalar S>
void WireT<S>::measureTwist() {
  for (const std::size_t k : {std::size_t(0), points_.size() - 1}) {
    ConnectingNode* connecting = points_[k].connecting;
    if (!connecting || !(connecting->twistStep_ > 0.0)) continue;
    const Vec3d axis = intoWire(k);
    const double turn = connecting->twistStep_ * points_[k].body->getAngularVelocity().template cast<double>().dot(axis);
    if (std::isfinite(turn)) connecting->twist_ += turn;
  }
}

template <Scalar S>
void WireT<S>::setEnableCollisions(Geometry* geometry, bool enable) {
  if (!geometry) throw error("cannot enable or disable collisions with a null geometry", "nullptr");
  std::erase_if(noCollisions_, [&](const observer_ptr<Geometry>& g) { return !g || g.get() == geometry; });
  if (!enable) noCollisions_.emplace_back(geometry);
}

template <Scalar S>
bool WireT<S>::getEnableCollisions(const Geometry* geometry) const {
  return std::none_of(noCollisions_.begin(), noCollisions_.end(),
                      [&](const observer_ptr<Geometry>& g) { return g && g.get() == geometry; });
}

template <Scalar S>
auto WireT<S>::getGeometryContacts() const -> std::vector<GeometryContact> {
  std::vector<GeometryContact> contacts;
  for (const auto& p : geometryContacts_.points()) {
    if (!geometryContacts_.touching(p)) continue;
    GeometryContact c;
    c.geometry = p.geometry;
    c.point = p.point.template cast<S>();
    c.normal = p.normal.template cast<S>();
    c.depth = S(p.depth);
    c.distance = S(p.distance);
    c.force = p.force.template cast<S>();
    contacts.push_back(c);
  }
  return contacts;
}

template <Scalar S>
bool WireT<S>::touches(const Geometry& geometry) const {
  if (!getEnableCollisions(&geometry)) return false;
  if (const Body* body = geometry.getRigidBody()) {
    for (const Point* end : {&points_.front(), &points_.back()})
      if (end->body == body) return false;
    for (const Contact& contact : contacts_)
      if (contact.node->getType() == Node::Type::EYE && contact.node->getRigidBody() == body) return false;
  }
  for (const Contact& contact : contacts_)
    if (routedGeometry(contact) == &geometry) return false;
  return true;
}

template <Scalar S>
void WireT<S>::writeGeometryContactRows(RowWriter& rows, const StepContext& step, std::size_t firstRow) {
  geometryContactRow_ = -1;
  segments_.clear();
  if (!collisions_ || points_.size() < 2) {
    geometryContacts_.clear();
    return;
  }
  double start = 0.0;
  bool previous = false;
  for (std::size_t k = 0; k + 1 < points_.size(); ++k) {
    const double rest = restLength(k);
    if (!state_[k].broken && !state_[k + 1].broken) {
      typename detail::WireGeometryContacts<S>::Segment segment;
      segment.a = state_[k].out;
      segment.b = state_[k + 1].in;
      segment.indexA = state_[k].index;
      segment.indexB = state_[k + 1].index;
      segment.armA = state_[k].armOut;
      segment.armB = state_[k + 1].armIn;
      segment.start = start;
      segment.rest = rest;
      segment.sharedStart = previous && points_[k].contact < 0;
      segments_.push_back(segment);
      previous = true;
    } else {
      previous = false;
    }
    start += rest;
  }
  // The margin: the radius and as far as a node moves in a step, up to the
  // node spacing (a node faster than that is beyond the wire's resolution;
  // a larger margin would only add rows).
  double fastest = 0.0;
  for (const PointState& s : state_)
    if (!s.broken) fastest = std::max(fastest, s.v.norm());
  const double margin = radius_ + std::min(fastest * step.getTimeStep(), 1.0 / resolution_);
  geometryContactRow_ = int(rows.size() - firstRow);
  geometryContacts_.writeRows(rows, step, segments_, radius_, margin, *material_, 0.5 / resolution_,
                              [this](const Geometry& geometry) { return touches(geometry); });
}

// Post-stabilization (the direct and hybrid solvers' default): the
// velocity-level step keeps a segment's length to first order in the angle
// φ it turns by within the step only (it comes out longer by about l·φ²/2),
// and the next step's stabilization, restoring that length, pushes the
// nodes apart: energy in. A segment that turned far in a step (a large
// time step, a free end falling past a fixed one) and is longer than its
// tension stretches it to, c·T with c = L/(E·A), or shorter than its rest
// length, by more than kProjectionTolerance of its rest length, is
// projected back to that length; never out to its stretch (a jerk's
// tension asks for far more than the wire's elastic stretch: projected to
// it, the wire dragged by a spinning body grew to 8 times its length, each
// projection's stretch pulling back harder in the next step). Positions
// only (the store's displace keeps the nodes' velocities), nodes and
// bodies moving (drums and slips stay). The segments beside it are not
// held in that projection: holding all of a wire's segments let its
// linearization overshoot (a level wire released at h = 0.2 s then rose
// 13 cm above its start). Segments at a contact, whose tangents are those
// of the step's start, are left to the next step.
template <Scalar S>
void WireT<S>::writeProjectionRows(RowWriter& rows, const StepContext& step) {
  if (!built()) return;
  measurePoints(step);
  const double stretchStiffness = this->stretchStiffness();
  for (std::size_t k = 0; k + 1 < points_.size(); ++k) {
    if (points_[k].contact >= 0 || points_[k + 1].contact >= 0 || state_[k].broken || state_[k + 1].broken) continue;
    const Vec3d d = state_[k + 1].in - state_[k].out;
    const double length = d.norm(), rest = restLength(k);
    const double stretched = -rest * tension_[k] / stretchStiffness, violation = rest - length;
    const double target = violation > 0.0 ? 0.0 : stretched;
    if (!(length > 0.0 && std::isfinite(violation) && std::isfinite(target)) ||
        !(std::abs(violation - target) > kProjectionTolerance * rest) || (violation <= 0.0 && violation > target))
      continue;
    const Vec3d u = d / length;
    detail::WireRowBodies bodies;
    bodies.add(state_[k].index, u, state_[k].armOut);
    bodies.add(state_[k + 1].index, -u, state_[k + 1].armIn);
    if (bodies.count == 0) continue;
    detail::Row& r = rows.add();
    bodies.write(rows, r);
    r.violation = violation;
    r.speed = target;
  }
}

// A contact's friction along the wire (the capstan law, PHYSICS.md §7): the
// slip's force is the difference of the tensions before and after it; the
// wire holds while the higher tension is within e^{μθ} of the lower, so the
// slip row is a friction row bounded by (e^{μθ} − 1)·T_low, T_low the
// tension of the stretch row on the low side (RowWriter::setFriction) in the
// same solve: a bound from the last step's tensions lagged a step, and a
// winch hauling over a fixed sheave alternated between stalled (the bound
// of a tight step held the wire while the other side went slack) and
// yanked (a slack step's bound let it run). The low side is the one with
// the lower tension in the last step (before the first, the one before).
// The row is exact (no least compliance): the slip's small inertia (one
// node's length of wire) turned contact friction's floor into a creep of
// 1.6 cm/s under a 2.5:1 load.
template <Scalar S>
void WireT<S>::writeFrictionRows(RowWriter& rows, std::size_t firstRow) {
  for (std::size_t k = 1; k + 1 < points_.size(); ++k) {
    if (points_[k].contact < 0) continue;
    Contact& contact = contacts_[std::size_t(points_[k].contact)];
    contact.row = -1;
    // The wire slides towards the high side: forward when it is after the node.
    const std::size_t low = tension_[k] < tension_[k - 1] ? k : k - 1;
    const auto direction = low == k - 1 ? SlidingNode::Direction::FORWARD : SlidingNode::Direction::BACKWARD;
    const double mu = contact.node->hasFrictionCoefficient(direction)
                          ? double(contact.node->getFrictionCoefficient(direction))
                          : double(material_->getWireMaterial()->getFrictionCoefficient());
    const double coefficient = std::expm1(mu * std::max(contact.wrap.wrap, 0.0));
    if (!(coefficient > 0.0) || !std::isfinite(coefficient)) continue;
    contact.row = int(rows.size() - firstRow);
    detail::Row& r = rows.add(contact.frictionImpulse);
    r.body1 = state_[k].slip;
    r.J1 = detail::Vec6d::Unit(0);
    r.holonomic = false;
    r.speed = 0.0;
    // The first of the direct solver's friction passes starts from the last
    // step's bound: a slip that accelerates converges in a few passes
    // (from an unbounded start, 8 passes left a slipping capstan at μ 0.5
    // 10 % short of e^{μθ}).
    const double start = coefficient * std::max(0.0, tension_[low]);
    r.lower = -start;
    r.upper = start;
    rows.setFriction(rows.size() - 1, firstRow + low, coefficient, detail::FrictionBound::SCALED_BOX, -1, true);
  }
  // The slip moves rest length from the segment after the node to the one
  // before (beginStep); neither may run out: an end or a load that reaches
  // the node stops there (without them, the segment left held nothing and
  // its end passed through the node and blew up).
  const double shortest = kShortestSegment / resolution_, stretchStiffness = this->stretchStiffness();
  for (std::size_t k = 1; k + 1 < points_.size(); ++k) {
    if (points_[k].contact < 0 || state_[k].slip < 0) continue;
    for (const std::size_t segment : {k - 1, k}) {
      // Only near the limit; one routed shorter is kept from shortening further.
      const double straight = restLengths_[segment] - wrapped(segment);
      if (!(straight < 1.0 / resolution_)) continue;
      detail::Row& r = rows.add();
      r.body1 = state_[k].slip;
      r.J1 = segment == k ? detail::Vec6d(-detail::Vec6d::Unit(0)) : detail::Vec6d(detail::Vec6d::Unit(0));
      r.violation = std::max(straight - shortest, 0.0);
      r.compliance = segmentCompliance(segment, stretchStiffness);
      r.lower = 0.0;
    }
  }
}

// A winch's rows on its drum (the free length l of its segment, l̇ the rate
// wire leaves it): the motor drives l̇ to the winch's speed within its force
// range; at speed 0 the brake adds its range to the motor's; l stays above
// a hundredth of the node spacing (the wire is all hauled in) and the
// pulled-in length above 0 (the drum is empty).
template <Scalar S>
void WireT<S>::writeWinchRows(RowWriter& rows, const StepContext& step, std::size_t firstRow,
                              double stretchStiffness) {
  const auto offset = [&] { return int(rows.size() - firstRow); };
  for (int end = 0; end < 2; ++end) {
    WinchRows& written = winchRows_[end];
    written.motor = written.allIn = written.allOut = -1;
    const Winch* winch = winches_[end].get();
    if (!winch) continue;
    const detail::WireNodes::Drum& drum = nodes_->drum(winch->drum_);
    const int index = step.indexOf(*nodes_, nodes_->numNodes() + winch->drum_);
    const double compliance = segmentCompliance(winchSegment(end), stretchStiffness);
    const bool braking = winch->getSpeed() == S(0);
    const double lower = double(winch->getForceRangeLower()) + (braking ? double(winch->getBrakeForceRangeLower()) : 0.0);
    const double upper = double(winch->getForceRangeUpper()) + (braking ? double(winch->getBrakeForceRangeUpper()) : 0.0);
    if (lower < 0.0 || upper > 0.0) {
      written.motor = offset();
      detail::Row& r = rows.add(written.motorImpulse + written.brakeImpulse);
      r.body1 = index;
      r.J1 = detail::Vec6d::Unit(0);
      r.holonomic = false;
      r.speed = double(winch->getSpeed());
      r.lower = lower;
      r.upper = upper;
    }
    const double shortest = kShortestSegment / resolution_;
    written.allIn = offset();
    detail::Row& allIn = rows.add(written.allInImpulse);
    allIn.body1 = index;
    allIn.J1 = detail::Vec6d::Unit(0);
    allIn.violation = drum.freeLength - shortest;
    allIn.compliance = compliance;
    allIn.lower = 0.0;
    written.allOut = offset();
    detail::Row& allOut = rows.add(written.allOutImpulse);
    allOut.body1 = index;
    allOut.J1 = -detail::Vec6d::Unit(0);
    allOut.violation = drum.pulledIn;
    allOut.compliance = compliance;
    allOut.lower = 0.0;
  }
}

template <Scalar S>
void WireT<S>::readBack(std::span<const double> impulses, const StepContext& step) {
  const double h = step.getTimeStep();
  const std::size_t segments = restLengths_.size();
  for (std::size_t k = 0; k < segments; ++k) {
    stretchImpulse_[k] = impulses[k];
    tension_[k] = impulses[k] / h;
  }
  std::size_t next = segments;
  for (std::size_t k = 0; k < points_.size(); ++k) {
    if (!bent_[k]) continue;
    bendImpulse_[2 * k] = impulses[next++];
    bendImpulse_[2 * k + 1] = impulses[next++];
  }
  for (int end = 0; end < 2; ++end) {
    Winch* winch = winches_[end].get();
    if (!winch) continue;
    WinchRows& written = winchRows_[end];
    const double total = written.motor >= 0 ? impulses[std::size_t(written.motor)] : 0.0;
    // At speed 0 one row holds both: the motor's share is what its range allows.
    const double motor = winch->getSpeed() == S(0)
                             ? std::clamp(total, double(winch->getForceRangeLower()) * h,
                                          double(winch->getForceRangeUpper()) * h)
                             : total;
    written.motorImpulse = motor;
    written.brakeImpulse = total - motor;
    written.allInImpulse = impulses[std::size_t(written.allIn)];
    written.allOutImpulse = impulses[std::size_t(written.allOut)];
    winch->motorForce_ = motor / h;
    winch->brakeForce_ = (total - motor) / h;
  }
  for (int end = 0; end < 2; ++end)
    if (twistRow_[end] >= 0) points_[end == 0 ? 0 : points_.size() - 1].connecting->twistImpulse_ = impulses[std::size_t(twistRow_[end])];
  for (Contact& contact : contacts_) {
    contact.frictionImpulse = contact.row >= 0 ? impulses[std::size_t(contact.row)] : 0.0;
    // The slip row's impulse is T_after − T_before (times h); on the wire along it, the other way.
    contact.node->frictionForce_ = -contact.frictionImpulse / h;
  }
  if (geometryContactRow_ >= 0 && geometryContacts_.rowsWritten() > 0)
    geometryContacts_.readBack(impulses.subspan(std::size_t(geometryContactRow_)), h);
}

}  // namespace spook

#include <spook/wire/wire_operations.hpp>

namespace spook {

SPOOK_COMPILED_ONCE(class, WireT)

using Wire = WireT<double>;
using WireRef = ref_ptr<Wire>;
namespace f32 {
using Wire = WireT<float>;
using WireRef = ref_ptr<Wire>;
}  // namespace f32

}  // namespace spook
