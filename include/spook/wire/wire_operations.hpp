#pragma once

// WireT's operations on a wire already routed (wire/wire.hpp): cut, merge,
// detach and attach, and the helpers they share with findPoint. Included by
// wire.hpp only.

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <utility>
#include <vector>

#include <spook/sim/membership.hpp>
#include <spook/wire/wire.hpp>

namespace spook {

template <Scalar S>
void WireT<S>::locate(double distance, std::size_t& segment, double& along) const {
  along = std::clamp(distance, 0.0, double(getRestLength()));
  segment = 0;
  while (segment + 1 < restLengths_.size() && along > restLength(segment)) along -= restLength(segment++);
}

template <Scalar S>
auto WireT<S>::pointOn(std::size_t k, double along) const -> Vec3d {
  // Along the segment's length now: arc, straight part, arc.
  const double rest = restLength(k), length = segmentLength(k);
  const double before = points_[k].contact >= 0 ? contacts_[std::size_t(points_[k].contact)].wrap.arcOut() : 0.0;
  const double straight = length - wrapped(k);
  const double t = straight > 0.0 ? std::clamp((along * (rest > 0.0 ? length / rest : 1.0) - before) / straight, 0.0, 1.0)
                                  : 0.0;
  const Vec3d a = departure(points_[k]), b = arrival(points_[k + 1]);
  return a + t * (b - a);
}

template <Scalar S>
void WireT<S>::syncWinchSegments() {
  for (int end = 0; end < 2; ++end)
    if (winches_[end]) restLengths_[winchSegment(end)] = restLength(winchSegment(end));
}

template <Scalar S>
void WireT<S>::placeDrums(const std::vector<detail::WireNodes::Drum>& drums,
                          const std::vector<detail::WireNodes::Drum>* winchDrums[2]) {
  for (Contact& contact : contacts_) contact.slip = nodes_->addDrum(drums[contact.slip]);
  for (int end = 0; end < 2; ++end) {
    Winch* winch = winches_[end].get();
    if (!winch) continue;
    detail::WireNodes::Drum drum = (*winchDrums[end])[winch->drum_];
    drum.freeLength = restLengths_[winchSegment(end)];
    winch->drum_ = nodes_->addDrum(drum);
    winch->store_ = nodes_;
    winch->wire_ = this;
  }
}

template <Scalar S>
void WireT<S>::keepContactsOf(const std::vector<Contact>& contacts) {
  contacts_.clear();
  for (Point& p : points_) {
    if (p.contact < 0) continue;
    contacts_.push_back(contacts[std::size_t(p.contact)]);
    p.contact = int(contacts_.size()) - 1;
  }
}

template <Scalar S>
void WireT<S>::clearState() {
  points_.clear();
  restLengths_.clear();
  stretchImpulse_.clear();
  bendImpulse_.clear();
  bent_.clear();
  tension_.clear();
  contacts_.clear();
  state_.clear();
  winchRows_[0] = winchRows_[1] = WinchRows{};
  geometryContacts_.clear();
  segments_.clear();
  geometryContactRow_ = -1;
}

// The cut segment's two parts share its rest length as the cut point shares
// it (both stretched alike); the new free ends move as the wire did there.
// The tension of both parts starts from 0: the cut released it.
template <Scalar S>
auto WireT<S>::cut(S distanceFromStart) -> ref_ptr<WireT> {
  if (!built()) throw error("is not in a simulation: there is nothing to cut yet");
  const double distance = double(distanceFromStart), quarter = 0.25 / resolution_;
  if (!(std::isfinite(distance) && distance >= quarter && distance <= double(getRestLength()) - quarter))
    throw error("can only be cut at least a quarter of its node spacing from either end; m from the start",
                distanceFromStart);
  std::size_t k = 0;
  double along = 0.0;
  locate(distance, k, along);
  const Vec3d position = pointOn(k, along);
  const double t = restLength(k) > 0.0 ? along / restLength(k) : 0.5;
  const Vec3d velocity = (1.0 - t) * worldVelocity(points_[k]) + t * worldVelocity(points_[k + 1]);
  if (!(position.allFinite() && velocity.allFinite()))
    throw error("cannot be cut where its state is not finite; m from the start", distanceFromStart);
  syncWinchSegments();

  ref_ptr<WireT> other = new WireT(S(radius_), S(resolution_), material_);
  other->setName(getName() + " cut");
  other->collisions_ = collisions_;
  other->noCollisions_ = noCollisions_;
  other->ranges_[1] = ranges_[1];
  ranges_[1] = HighResolutionRange{};
  // The contacts' places along the wire were those before the cut.
  geometryContacts_.clear();
  std::size_t kept = 0;  // mass nodes before the cut
  for (std::size_t i = 0; i <= k; ++i) kept += points_[i].node >= 0 ? 1 : 0;
  other->nodes_->add(position, 0.0);
  other->nodes_->setVelocity(0, velocity);
  nodes_->moveNodesTo(kept, *other->nodes_);
  nodes_->insert(kept, position, velocity, 0.0);

  // Per point and per segment: entries from `from` on go to the end of `to`.
  const auto moveTail = [](auto& mine, std::size_t from, auto& to) {
    to.insert(to.end(), mine.begin() + std::ptrdiff_t(from), mine.end());
    mine.erase(mine.begin() + std::ptrdiff_t(from), mine.end());
  };
  Point start, end;
  start.node = 0;
  end.node = int(kept);
  other->points_ = {start};
  moveTail(points_, k + 1, other->points_);
  points_.push_back(end);
  other->restLengths_ = {(1.0 - t) * restLengths_[k]};
  moveTail(restLengths_, k + 1, other->restLengths_);
  restLengths_[k] *= t;
  other->stretchImpulse_ = {0.0};
  moveTail(stretchImpulse_, k + 1, other->stretchImpulse_);
  stretchImpulse_[k] = 0.0;
  other->tension_ = {0.0};
  moveTail(tension_, k + 1, other->tension_);
  tension_[k] = 0.0;
  other->bendImpulse_ = {0.0, 0.0};
  moveTail(bendImpulse_, 2 * (k + 1), other->bendImpulse_);
  bendImpulse_.insert(bendImpulse_.end(), 2, 0.0);
  other->bent_ = {0};
  moveTail(bent_, k + 1, other->bent_);
  bent_.push_back(0);
  renumberNodes();
  other->renumberNodes();

  const std::vector<Contact> contacts = contacts_;
  keepContactsOf(contacts);
  other->keepContactsOf(contacts);
  other->winches_[1] = std::move(winches_[1]);
  other->winchRows_[1] = std::exchange(winchRows_[1], WinchRows{});
  const std::vector<detail::WireNodes::Drum> drums = nodes_->takeDrums();
  const std::vector<detail::WireNodes::Drum>* winchDrums[2] = {&drums, &drums};
  placeDrums(drums, winchDrums);
  other->placeDrums(drums, winchDrums);

  // The routes: the ends and the contacts of each part.
  std::vector<ref_ptr<Node>> route{route_.front()}, otherRoute{new FreeNodeT<S>(position.template cast<S>())};
  for (const Contact& c : contacts_) route.push_back(c.node);
  route.push_back(new FreeNodeT<S>(position.template cast<S>()));
  for (const Contact& c : other->contacts_) otherRoute.push_back(c.node);
  otherRoute.push_back(route_.back());
  route_ = std::move(route);
  other->route_ = std::move(otherRoute);
  updateMasses();
  other->updateMasses();
  return other;
}

template <Scalar S>
void WireT<S>::checkFreeEnd(int end) const {
  const char* which = end == 0 ? "is attached at its begin: detach it first" : "is attached at its end: detach it first";
  if (winches_[end]) throw error(which, winches_[end]->getName());
  if (built()) {
    const Point& p = end == 0 ? points_.front() : points_.back();
    if (p.node < 0) throw error(which, p.body ? p.body->getName() : std::string("world"));
  } else if (!route_.empty()) {
    const Node& node = end == 0 ? *route_.front() : *route_.back();
    if (node.getType() != Node::Type::FREE) throw error(which, node.getRigidBody() ? node.getRigidBody()->getName() : std::string("world"));
  }
}

template <Scalar S>
void WireT<S>::merge(WireT* other) {
  if (!other) throw error("cannot merge a null wire", "nullptr");
  if (other == this) throw error("cannot merge with itself", getName());
  if (built() != other->built() || getSimulationHandle() != other->getSimulationHandle())
    throw error("can only merge a wire of its own simulation (or both in none); not", other->getName());
  if (other->radius_ != radius_) throw error("cannot merge a wire of another radius (m)", other->getRadius());
  if (other->material_ != material_) throw error("cannot merge a wire of another material", other->material_->getName());
  if (!built() && (route_.empty() || other->route_.empty()))
    throw error("cannot merge a wire that has no route; wire", route_.empty() ? getName() : other->getName());
  checkFreeEnd(1);
  other->checkFreeEnd(0);
  if (!built()) {
    ranges_[1] = other->ranges_[1];
    other->ranges_[0] = other->ranges_[1] = HighResolutionRange{};
    // Ends routed at one point meet there; else the route runs straight between them.
    const bool meet = (other->route_.front()->getWorldPosition() - route_.back()->getWorldPosition()).norm() == S(0);
    route_.insert(route_.end(), other->route_.begin() + (meet ? 1 : 0), other->route_.end());
    other->route_.clear();
    winches_[1] = std::move(other->winches_[1]);
    if (winches_[1]) winches_[1]->wire_ = this;
    return;
  }
  syncWinchSegments();
  other->syncWinchSegments();
  const std::size_t ownNodes = nodes_->numNodes(), ownContacts = contacts_.size();
  const std::size_t last = std::size_t(points_.back().node), first = ownNodes;
  const Vec3d gap = nodes_->position(last) - other->nodes_->position(0);
  other->nodes_->moveNodesTo(0, *nodes_);
  for (Point p : other->points_) {
    if (p.contact >= 0) p.contact += int(ownContacts);
    points_.push_back(p);
  }
  contacts_.insert(contacts_.end(), other->contacts_.begin(), other->contacts_.end());
  const double length = gap.norm();
  std::vector<double> restLengths = std::move(other->restLengths_), stretch = std::move(other->stretchImpulse_),
                      tension = std::move(other->tension_), bend = std::move(other->bendImpulse_);
  std::vector<char> bent = std::move(other->bent_);
  if (std::isfinite(length) && length < 0.25 / resolution_) {
    // One node: its mass (updateMasses) and momentum both ends'.
    const double ma = nodes_->mass(last), mb = nodes_->mass(first), total = ma + mb;
    if (total > 0.0) nodes_->setVelocity(last, (ma * nodes_->velocity(last) + mb * nodes_->velocity(first)) / total);
    nodes_->setPosition(last, 0.5 * (nodes_->position(last) + nodes_->position(first)));
    nodes_->erase(first);
    points_.erase(points_.begin() + std::ptrdiff_t(points_.size() - other->points_.size()));
    bend.erase(bend.begin(), bend.begin() + 2);
    bent.erase(bent.begin());
  } else {
    restLengths_.push_back(std::isfinite(length) ? length : 0.0);
    stretchImpulse_.push_back(0.0);
    tension_.push_back(0.0);
  }
  restLengths_.insert(restLengths_.end(), restLengths.begin(), restLengths.end());
  stretchImpulse_.insert(stretchImpulse_.end(), stretch.begin(), stretch.end());
  tension_.insert(tension_.end(), tension.begin(), tension.end());
  bendImpulse_.insert(bendImpulse_.end(), bend.begin(), bend.end());
  bent_.insert(bent_.end(), bent.begin(), bent.end());
  renumberNodes();

  const std::vector<detail::WireNodes::Drum> ownDrums = nodes_->takeDrums(), otherDrums = other->nodes_->takeDrums();
  winches_[1] = std::move(other->winches_[1]);
  winchRows_[1] = other->winchRows_[1];
  // placeDrums reads each slip's index in its own wire's drums.
  const std::vector<Contact> contacts = contacts_;
  contacts_.resize(ownContacts);
  const std::vector<detail::WireNodes::Drum>* winchDrums[2] = {&ownDrums, &otherDrums};
  placeDrums(ownDrums, winchDrums);
  for (std::size_t c = ownContacts; c < contacts.size(); ++c) {
    contacts_.push_back(contacts[c]);
    contacts_.back().slip = nodes_->addDrum(otherDrums[contacts[c].slip]);
  }
  route_.insert(route_.end(), other->route_.begin(), other->route_.end());
  other->route_.clear();
  other->winches_[0] = nullptr;
  other->clearState();
  ranges_[1] = other->ranges_[1];
  other->ranges_[0] = other->ranges_[1] = HighResolutionRange{};
  updateMasses();
}

template <Scalar S>
void WireT<S>::detach(bool begin) {
  const int end = begin ? 0 : 1;
  const char* which = begin ? "is not attached at its begin" : "is not attached at its end";
  if (!built()) {
    if (route_.empty()) throw error(which, "no route");
    ref_ptr<Node>& node = begin ? route_.front() : route_.back();
    if (node->getType() != Node::Type::BODY_FIXED && node->getType() != Node::Type::CONNECTING)
      throw error(which, "a free node");
    node = new FreeNodeT<S>(node->getWorldPosition());
    if (winches_[end]) winches_[end]->wire_ = nullptr;
    winches_[end] = nullptr;
    return;
  }
  const std::size_t k = begin ? 0 : points_.size() - 1;
  if (points_[k].node >= 0) throw error(which, "a free end");
  const Vec3d position = worldPosition(points_[k]), velocity = worldVelocity(points_[k]);
  if (!(position.allFinite() && velocity.allFinite()))
    throw error("cannot detach from a body whose state is not finite", points_[k].body->getName());
  syncWinchSegments();
  if (Winch* winch = winches_[end].get()) {
    std::vector<detail::WireNodes::Drum> drums = nodes_->takeDrums();
    winch->pulledIn_ = drums[winch->drum_].pulledIn;
    winch->store_ = nullptr;
    winch->wire_ = nullptr;
    winch->motorForce_ = winch->brakeForce_ = 0.0;
    winches_[end] = nullptr;
    winchRows_[end] = WinchRows{};
    const std::vector<detail::WireNodes::Drum>* winchDrums[2] = {&drums, &drums};
    placeDrums(drums, winchDrums);
  }
  nodes_->insert(begin ? 0 : nodes_->numNodes(), position, velocity, 0.0);
  points_[k] = Point{};
  points_[k].node = 0;
  renumberNodes();
  (begin ? route_.front() : route_.back()) = new FreeNodeT<S>(position.template cast<S>());
  updateMasses();
}

// The free end stays a lumped node: a straight segment as long as the gap
// joins it to the attachment (the next step merges it when shorter than a
// quarter of the node spacing).
template <Scalar S>
void WireT<S>::attachEnd(int end, ref_ptr<Node> node) {
  checkFreeEnd(end);
  if (!built()) {
    route_.insert(end == 0 ? route_.begin() : route_.end(), std::move(node));
    return;
  }
  Body* body = node->getRigidBody();
  if (body && detail::SimulationMembership::simulationOf(*body) != getSimulationHandle())
    throw error("can only attach to a body of its simulation; not", body->getName());
  Point attached;
  attached.body = body;
  attached.local = node->getPosition().template cast<double>();
  if (node->getType() == Node::Type::CONNECTING) {
    attached.connecting = static_cast<ConnectingNode*>(node.get());
    attached.connecting->twist_ = attached.connecting->twistImpulse_ = attached.connecting->twistStep_ = 0.0;
  }
  syncWinchSegments();
  const std::size_t k = end == 0 ? 0 : points_.size() - 1;
  const double gap = (worldPosition(attached) - worldPosition(points_[k])).stableNorm();
  if (!std::isfinite(gap))
    throw error("cannot attach an end across a gap that is not finite (the end or the attachment point is not); gap",
                gap);
  // A wire flung far by a step that could not hold it would split that gap
  // into nodes, twice as many each step.
  const double nodes = (double(getRestLength()) + gap) * resolution_ + double(points_.size());
  if (!(nodes <= kMostNodes))
    throw error("would have more than 1e6 lumped nodes (length x resolution) once attached there", nodes);
  const auto add = [&](auto& v, auto value) { end == 0 ? void(v.insert(v.begin(), value)) : v.push_back(value); };
  add(points_, attached);
  add(restLengths_, gap);
  add(stretchImpulse_, 0.0);
  add(tension_, 0.0);
  add(bent_, char(0));
  add(bendImpulse_, 0.0);
  add(bendImpulse_, 0.0);
  (end == 0 ? route_.front() : route_.back()) = std::move(node);
  updateMasses();
}

template <Scalar S>
void WireT<S>::attach(ref_ptr<Node> node, bool begin) {
  if (!node) throw error("cannot attach to a null node", "nullptr");
  if (node->getType() != Node::Type::BODY_FIXED && node->getType() != Node::Type::CONNECTING)
    throw error("attaches only to a BodyFixedNode, a ConnectingNode, a link or a winch", "another node");
  attachEnd(begin ? 0 : 1, std::move(node));
}

template <Scalar S>
void WireT<S>::attach(ref_ptr<Link> link, const Vec3& position, bool begin) {
  if (!link) throw error("cannot attach to a null link", "nullptr");
  attach(link->makeConnection(position), begin);
}

template <Scalar S>
void WireT<S>::attach(ref_ptr<Winch> winch, S pulledInLength, bool begin) {
  if (!winch) throw error("cannot attach to a null winch", "nullptr");
  if (winch->wire_) throw error("cannot attach to a winch that is already routed in a wire", winch->getName());
  if (!(std::isfinite(pulledInLength) && pulledInLength >= S(0)))
    throw error("pulled-in length must be finite and >= 0 m", pulledInLength);
  const int end = begin ? 0 : 1;
  attachEnd(end, new BodyFixedNodeT<S>(winch->getRigidBody(), winch->getPosition()));
  winches_[end] = winch;
  winch->wire_ = this;
  winch->pulledIn_ = double(pulledInLength);
  if (!built()) return;
  winchRows_[end] = WinchRows{};
  detail::WireNodes::Drum drum;
  drum.freeLength = restLengths_[winchSegment(end)];
  drum.pulledIn = double(pulledInLength);
  drum.mass = linearDensity() / resolution_;
  winch->drum_ = nodes_->addDrum(drum);
  winch->store_ = nodes_;
}

}  // namespace spook
