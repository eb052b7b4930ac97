#pragma once

#include <algorithm>
#include <atomic>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <spook/collide/bounding_box.hpp>
#include <spook/collide/shapes/shape.hpp>
#include <spook/core/error.hpp>
#include <spook/core/frame.hpp>
#include <spook/core/implementation.hpp>
#include <spook/core/observer_ptr.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/referenced.hpp>
#include <spook/dynamics/material.hpp>

namespace spook {

template <Scalar S>
class RigidBodyT;

namespace detail {
template <Scalar S>
struct GeometryEdit;
/// Asked before, and told after, a geometry's shapes, material or placement
/// change, so that a body can refuse a change whose mass properties would
/// not be valid and recompute them once it is made.
template <Scalar S>
struct GeometryOwner {
  /// Throws spook::Error when the body could not take `edit`; changes nothing.
  virtual void checkGeometryChange(const GeometryEdit<S>& edit) const = 0;
  virtual void geometryChanged() = 0;

 protected:
  ~GeometryOwner() = default;
};
template <Scalar S>
struct GeometryAccess;
}  // namespace detail

/// One or more shapes, each at a transform relative to the geometry frame,
/// with a material and collision settings. A geometry belongs to a
/// RigidBody (its frame is then fixed in the body's model frame) or stands
/// static in the world (its frame is then a world transform).
template <Scalar S>
class GeometryT : public Referenced, private detail::ShapeOwner<S> {
 public:
  using Vec3 = spook::Vec3T<S>;
  using Transform = spook::TransformT<S>;
  using Shape = ShapeT<S>;
  using Frame = FrameT<S>;

  struct ShapeEntry {
    ref_ptr<Shape> shape;
    Transform transform;  ///< shape frame → geometry frame
  };

  explicit GeometryT(std::string name = "") : name_(std::move(name)), id_(nextId()) {}
  /// A geometry holding one shape at `transform` (shape → geometry frame).
  explicit GeometryT(ref_ptr<Shape> shape, const Transform& transform = Transform::Identity(), std::string name = "")
      : GeometryT(std::move(name)) {
    add(std::move(shape), transform);
  }

  [[nodiscard]] const std::string& getName() const { return name_; }
  void setName(std::string name) { name_ = std::move(name); }
  /// A number unique to this geometry for the life of the program.
  [[nodiscard]] std::uint64_t getId() const { return id_; }

  // --- Shapes ----------------------------------------------------------------

  /// Adds a shape at `transform` (shape → geometry frame, rigid). Updates the
  /// owning body's mass properties; throws, and adds nothing, when they would
  /// not be finite and valid (e.g. a box whose mass or inertia overflows).
  /// A shape changed later (resized, a child added to a composite) is
  /// checked the same way: refused, it keeps its old value; taken, the
  /// body's mass properties follow.
  void add(ref_ptr<Shape> shape, const Transform& transform = Transform::Identity());
  /// Removes a shape; false when it is not here.
  bool remove(const Shape* shape);
  [[nodiscard]] const std::vector<ShapeEntry>& getShapes() const { return shapes_; }
  /// The first shape, or nullptr.
  [[nodiscard]] Shape* getShape() const;

  // --- Placement -------------------------------------------------------------

  /// The geometry frame; its parent is the body's model frame when the
  /// geometry belongs to a body.
  [[nodiscard]] Frame* getFrame() const { return frame_.get(); }
  /// Geometry → world transform.
  [[nodiscard]] Transform getTransform() const { return frame_->getMatrix(); }
  /// Sets the world transform (a body-owned geometry moves relative to its
  /// body so that it lands there). Updates the owning body's mass; throws,
  /// and stays put, when it would not be finite and valid.
  void setTransform(const Transform& X_W);
  [[nodiscard]] Vec3 getPosition() const { return frame_->getTranslate(); }
  void setPosition(const Vec3& p_W);
  void setPosition(S x, S y, S z) { setPosition(Vec3(x, y, z)); }
  /// Geometry → body model frame (or world, without a body).
  [[nodiscard]] Transform getLocalTransform() const { return frame_->getLocalMatrix(); }
  void setLocalTransform(const Transform& X);
  /// The body this geometry belongs to, or nullptr for a static geometry.
  [[nodiscard]] RigidBodyT<S>* getRigidBody() const { return body_; }

  // --- Material --------------------------------------------------------------

  /// The material; a geometry made without one uses a shared default
  /// (density 1000 kg/m³). Assigning updates the owning body's mass; throws,
  /// and keeps the old material, when that would not be finite and valid
  /// (e.g. a density whose mass overflows).
  [[nodiscard]] MaterialT<S>* getMaterial() const;
  void setMaterial(ref_ptr<MaterialT<S>> material);
  /// The material every geometry without its own uses.
  [[nodiscard]] static MaterialT<S>* defaultMaterial();

  // --- Collision settings ----------------------------------------------------

  /// A disabled geometry is ignored by collision detection.
  [[nodiscard]] bool getEnable() const { return enable_; }
  void setEnable(bool enable) { enable_ = enable; }
  /// False: collides with nothing.
  [[nodiscard]] bool getEnableCollisions() const { return enableCollisions_; }
  void setEnableCollisions(bool enable) { enableCollisions_ = enable; }
  /// Enables or disables collisions between this and `other` (both ways).
  void setEnableCollisions(GeometryT* other, bool enable);
  /// False when collisions with `other` were disabled pairwise.
  [[nodiscard]] bool getEnableCollisions(const GeometryT* other) const;

  /// Collision group ids and names, matched by Space::setEnablePair.
  void addGroup(std::uint32_t id);
  void addGroup(const std::string& name);
  void removeGroup(std::uint32_t id) { std::erase(groupIds_, id); }
  void removeGroup(const std::string& name) { std::erase(groupNames_, name); }
  [[nodiscard]] bool hasGroup(std::uint32_t id) const;
  [[nodiscard]] bool hasGroup(const std::string& name) const;
  [[nodiscard]] const std::vector<std::uint32_t>& getGroupIds() const { return groupIds_; }
  [[nodiscard]] const std::vector<std::string>& getGroupNames() const { return groupNames_; }

  /// A sensor's contacts are found and reported to listeners, never solved.
  [[nodiscard]] bool isSensor() const { return sensor_; }
  void setSensor(bool sensor) { sensor_ = sensor; }

  /// Velocity of the surface relative to the geometry, in the geometry
  /// frame (m/s): a conveyor belt. Used by the contact solver.
  [[nodiscard]] const Vec3& getSurfaceVelocity() const { return surfaceVelocity_; }
  void setSurfaceVelocity(const Vec3& v);

  /// World bounding box of every shape (m); infinite along the axes where a
  /// plane extends.
  [[nodiscard]] BoundingBoxT<S> getBoundingBox() const { return getBoundingBox(getTransform()); }
  /// The same with the geometry placed at X_WG instead of its frame's pose.
  [[nodiscard]] BoundingBoxT<S> getBoundingBox(const Transform& X_WG) const;

 protected:
  ~GeometryT() override;

 private:
  friend struct detail::GeometryAccess<S>;

  static std::uint64_t nextId();
  void check(const detail::GeometryEdit<S>& edit) const;
  // A would-be world transform of a body's geometry, checked as the local
  // transform it makes (to round-off, the one the frame then sets); a
  // transform that is not finite and rigid is left for the frame to refuse.
  void checkWorldPlacement(const Transform& X_W) const;
  void changed();
  // One of the shapes changed (its size, children, heights).
  void checkShapeChange() const override { check({this, nullptr, nullptr, nullptr}); }
  void shapeChanged() override { changed(); }
  void setPartner(GeometryT* other, bool enable);
  template <class T>
  [[nodiscard]] Error error(const std::string& what, const T& value) const {
    return detail::makeError("Geometry", name_, what, value);
  }

  std::string name_;
  std::uint64_t id_;
  std::vector<ShapeEntry> shapes_;
  ref_ptr<Frame> frame_ = new Frame();
  ref_ptr<MaterialT<S>> material_;
  bool enable_ = true;
  bool enableCollisions_ = true;
  bool sensor_ = false;
  Vec3 surfaceVelocity_ = Vec3::Zero();
  std::vector<observer_ptr<GeometryT>> disabledWith_;
  std::vector<std::uint32_t> groupIds_;
  std::vector<std::string> groupNames_;

  // Maintained by the owning body and the space.
  RigidBodyT<S>* body_ = nullptr;
  detail::GeometryOwner<S>* owner_ = nullptr;
  const void* space_ = nullptr;
};

template <Scalar S>
void GeometryT<S>::add(ref_ptr<Shape> shape, const Transform& transform) {
  if (!shape) throw error("cannot add a null shape", "nullptr");
  if (!(transform.matrix().allFinite() && isRotation<S>(transform.linear())))
    throw error("shape transform must be finite and rigid", SPDMat3T<S>::flat(transform.linear()));
  if (std::any_of(shapes_.begin(), shapes_.end(), [&](const ShapeEntry& e) { return e.shape == shape; }))
    throw error("shape already added to this geometry", std::string(shapeTypeName(shape->getType())));
  std::vector<ShapeEntry> shapes = shapes_;
  shapes.push_back({shape, makeTransform<S>(transform.translation(), QuatT<S>(transform.linear()))});
  check({this, &shapes, nullptr, nullptr});
  shapes_ = std::move(shapes);
  detail::ShapeOwners<S>::add(*shape, this);
  changed();
}

template <Scalar S>
bool GeometryT<S>::remove(const Shape* shape) {
  const auto it = std::find_if(shapes_.begin(), shapes_.end(), [&](const ShapeEntry& e) { return e.shape == shape; });
  if (it == shapes_.end()) return false;
  detail::ShapeOwners<S>::remove(*it->shape, this);
  shapes_.erase(it);
  changed();
  return true;
}

template <Scalar S>
auto GeometryT<S>::getShape() const -> Shape* {
  return shapes_.empty() ? nullptr : shapes_.front().shape.get();
}

template <Scalar S>
void GeometryT<S>::setTransform(const Transform& X_W) {
  checkWorldPlacement(X_W);
  frame_->setMatrix(X_W);
  changed();
}

template <Scalar S>
void GeometryT<S>::setPosition(const Vec3& p_W) {
  Transform X_W = getTransform();
  X_W.translation() = p_W;
  checkWorldPlacement(X_W);
  frame_->setTranslate(p_W);
  changed();
}

template <Scalar S>
void GeometryT<S>::setLocalTransform(const Transform& X) {
  if (X.matrix().allFinite() && isRotation<S>(X.linear())) check({this, nullptr, nullptr, &X});
  frame_->setLocalMatrix(X);
  changed();
}

template <Scalar S>
auto GeometryT<S>::getMaterial() const -> MaterialT<S>* {
  return material_ ? material_.get() : defaultMaterial();
}

template <Scalar S>
void GeometryT<S>::setMaterial(ref_ptr<MaterialT<S>> material) {
  if (!material) throw error("material must not be null", "nullptr");
  check({this, nullptr, material.get(), nullptr});
  material_ = std::move(material);
  changed();
}

template <Scalar S>
auto GeometryT<S>::defaultMaterial() -> MaterialT<S>* {
  static const ref_ptr<MaterialT<S>> material = new MaterialT<S>("default");
  return material.get();
}

template <Scalar S>
void GeometryT<S>::setEnableCollisions(GeometryT* other, bool enable) {
  if (!other) throw error("cannot pair collisions with a null geometry", "nullptr");
  if (other == this) throw error("cannot pair collisions with itself", name_);
  setPartner(other, enable);
  other->setPartner(this, enable);
}

template <Scalar S>
bool GeometryT<S>::getEnableCollisions(const GeometryT* other) const {
  return std::none_of(disabledWith_.begin(), disabledWith_.end(),
                      [&](const observer_ptr<GeometryT>& g) { return g.get() == other; });
}

template <Scalar S>
void GeometryT<S>::addGroup(std::uint32_t id) {
  if (!hasGroup(id)) groupIds_.push_back(id);
}

template <Scalar S>
void GeometryT<S>::addGroup(const std::string& name) {
  if (!hasGroup(name)) groupNames_.push_back(name);
}

template <Scalar S>
bool GeometryT<S>::hasGroup(std::uint32_t id) const {
  return std::find(groupIds_.begin(), groupIds_.end(), id) != groupIds_.end();
}

template <Scalar S>
bool GeometryT<S>::hasGroup(const std::string& name) const {
  return std::find(groupNames_.begin(), groupNames_.end(), name) != groupNames_.end();
}

template <Scalar S>
void GeometryT<S>::setSurfaceVelocity(const Vec3& v) {
  if (!v.allFinite()) throw error("surface velocity must be finite (m/s)", v);
  surfaceVelocity_ = v;
}

template <Scalar S>
auto GeometryT<S>::getBoundingBox(const Transform& X_WG) const -> BoundingBoxT<S> {
  BoundingBoxT<S> box{Vec3::Constant(std::numeric_limits<S>::infinity()),
                      Vec3::Constant(-std::numeric_limits<S>::infinity())};
  for (const ShapeEntry& e : shapes_) {
    const Transform X_WS = X_WG * e.transform;
    const BoundingBoxT<S> local = e.shape->getBoundingBox();
    const Mat3T<S> R = X_WS.linear();
    if (!(local.min.allFinite() && local.max.allFinite())) {
      box.min = box.min.cwiseMin(Vec3::Constant(-std::numeric_limits<S>::infinity()));
      box.max = box.max.cwiseMax(Vec3::Constant(std::numeric_limits<S>::infinity()));
      continue;
    }
    const Vec3 center = X_WS * local.center();
    const Vec3 reach = R.cwiseAbs() * local.halfExtents();
    box.min = box.min.cwiseMin(center - reach);
    box.max = box.max.cwiseMax(center + reach);
  }
  return box;
}

template <Scalar S>
GeometryT<S>::~GeometryT() {
  for (ShapeEntry& e : shapes_) detail::ShapeOwners<S>::remove(*e.shape, this);
}

template <Scalar S>
std::uint64_t GeometryT<S>::nextId() {
  static std::atomic<std::uint64_t> counter{0};
  return ++counter;
}

template <Scalar S>
void GeometryT<S>::check(const detail::GeometryEdit<S>& edit) const {
  if (owner_) owner_->checkGeometryChange(edit);
}

template <Scalar S>
void GeometryT<S>::checkWorldPlacement(const Transform& X_W) const {
  if (!(owner_ && X_W.matrix().allFinite() && isRotation<S>(X_W.linear()))) return;
  const Transform X_local = frame_->getParent()->getMatrix().inverse() * X_W;
  check({this, nullptr, nullptr, &X_local});
}

template <Scalar S>
void GeometryT<S>::changed() {
  if (owner_) owner_->geometryChanged();
}

template <Scalar S>
void GeometryT<S>::setPartner(GeometryT* other, bool enable) {
  std::erase_if(disabledWith_, [&](const observer_ptr<GeometryT>& g) { return !g.valid() || g.get() == other; });
  if (!enable) disabledWith_.emplace_back(other);
}

namespace detail {
/// A change to one geometry, described before it is made: its shapes,
/// material or local transform as they would be (nullptr: unchanged).
template <Scalar S>
struct GeometryEdit {
  const GeometryT<S>* geometry = nullptr;
  const std::vector<typename GeometryT<S>::ShapeEntry>* shapes = nullptr;
  const MaterialT<S>* material = nullptr;
  const TransformT<S>* localTransform = nullptr;
};

/// The owning body's and the space's handle on a geometry's membership.
template <Scalar S>
struct GeometryAccess {
  static RigidBodyT<S>*& body(GeometryT<S>& g) { return g.body_; }
  static GeometryOwner<S>*& owner(GeometryT<S>& g) { return g.owner_; }
  static const void*& space(GeometryT<S>& g) { return g.space_; }
  static const void* space(const GeometryT<S>& g) { return g.space_; }
};
}  // namespace detail

// After GeometryEdit, which its members use.
SPOOK_COMPILED_ONCE(class, GeometryT)

using Geometry = GeometryT<double>;
using GeometryRef = ref_ptr<Geometry>;
using GeometryObserver = observer_ptr<Geometry>;
namespace f32 {
using Geometry = GeometryT<float>;
using GeometryRef = ref_ptr<Geometry>;
using GeometryObserver = observer_ptr<Geometry>;
}  // namespace f32

}  // namespace spook
