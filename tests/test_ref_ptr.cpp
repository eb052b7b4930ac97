#include <doctest/doctest.h>

#include <type_traits>
#include <unordered_set>
#include <utility>

#include <spook/spook.hpp>

namespace {

// A Referenced type that reports its own deletion. Like every spook object it
// has a protected destructor, so it can only live on the heap.
class Tracked : public spook::Referenced {
 public:
  explicit Tracked(int* deletions) : deletions_(deletions) {}

 protected:
  ~Tracked() override { ++*deletions_; }

 private:
  int* deletions_;
};

class TrackedChild : public Tracked {
 public:
  TrackedChild(int* deletions, bool* childDestructorRan) : Tracked(deletions), ran_(childDestructorRan) {}

 protected:
  ~TrackedChild() override { *ran_ = true; }

 private:
  bool* ran_;
};

using TrackedRef = spook::ref_ptr<Tracked>;

}  // namespace

TEST_CASE("a new object has no reference until a ref_ptr holds it") {
  int deletions = 0;
  Tracked* raw = new Tracked(&deletions);
  CHECK(raw->getReferenceCount() == 0);
  {
    TrackedRef a = raw;
    CHECK(raw->getReferenceCount() == 1);
  }
  CHECK(deletions == 1);
}

TEST_CASE("copies add a reference and destroying them drops it") {
  int deletions = 0;
  TrackedRef a = new Tracked(&deletions);
  {
    TrackedRef b = a;
    TrackedRef c(b);
    CHECK(a->getReferenceCount() == 3);
    CHECK(b == a);
    CHECK(c.get() == a.get());
  }
  CHECK(a->getReferenceCount() == 1);
  CHECK(deletions == 0);
}

TEST_CASE("a move transfers the reference and leaves the source null") {
  int deletions = 0;
  TrackedRef a = new Tracked(&deletions);
  Tracked* raw = a.get();
  TrackedRef b = std::move(a);
  CHECK(b.get() == raw);
  CHECK(!a.valid());  // a moved-from ref_ptr is null
  CHECK(raw->getReferenceCount() == 1);
  TrackedRef c;
  c = std::move(b);
  CHECK(c.get() == raw);
  CHECK(!b.valid());
  CHECK(raw->getReferenceCount() == 1);
  CHECK(deletions == 0);
}

TEST_CASE("assignment releases the old object and references the new one") {
  int deletionsA = 0, deletionsB = 0;
  TrackedRef a = new Tracked(&deletionsA);
  TrackedRef b = new Tracked(&deletionsB);
  a = b;
  CHECK(deletionsA == 1);
  CHECK(deletionsB == 0);
  CHECK(b->getReferenceCount() == 2);
  a = nullptr;
  CHECK(!a.valid());
  CHECK(b->getReferenceCount() == 1);
  CHECK(deletionsB == 0);
}

TEST_CASE("self-assignment keeps the object and its count") {
  int deletions = 0;
  TrackedRef a = new Tracked(&deletions);
  TrackedRef& alias = a;  // through an alias, so the compiler does not see the self-assignment
  a = alias;
  CHECK(a.valid());
  CHECK(a->getReferenceCount() == 1);
  a = std::move(alias);
  CHECK(a.valid());
  CHECK(a->getReferenceCount() == 1);
  CHECK(deletions == 0);
}

TEST_CASE("the object is deleted exactly when the last ref_ptr lets go") {
  int deletions = 0;
  TrackedRef a = new Tracked(&deletions);
  TrackedRef b = a;
  TrackedRef c = b;
  a = nullptr;
  CHECK(deletions == 0);
  c = TrackedRef();
  CHECK(deletions == 0);
  b = nullptr;
  CHECK(deletions == 1);
}

TEST_CASE("releaseNoDelete hands the object out alive and unreferenced") {
  int deletions = 0;
  TrackedRef a = new Tracked(&deletions);
  Tracked* raw = a.releaseNoDelete();
  CHECK(!a.valid());
  CHECK(deletions == 0);
  CHECK(raw->getReferenceCount() == 0);
  TrackedRef adopted = raw;
  CHECK(raw->getReferenceCount() == 1);
  adopted = nullptr;
  CHECK(deletions == 1);
}

TEST_CASE("a ref_ptr to a derived type converts to a ref_ptr to its base and shares the count") {
  int deletions = 0;
  bool childDestructorRan = false;
  spook::ref_ptr<TrackedChild> child = new TrackedChild(&deletions, &childDestructorRan);
  TrackedRef base = child;
  CHECK(base.get() == child.get());
  CHECK(child->getReferenceCount() == 2);
  TrackedRef assigned;
  assigned = child;
  CHECK(child->getReferenceCount() == 3);
  child = nullptr;
  assigned = nullptr;
  CHECK(deletions == 0);
  base = nullptr;  // deletes through the base: the derived destructor must run
  CHECK(childDestructorRan);
  CHECK(deletions == 1);
}

TEST_CASE("ref_ptrs hash by object, so they can key an unordered set") {
  int deletions = 0;
  TrackedRef a = new Tracked(&deletions);
  TrackedRef b = a;
  TrackedRef other = new Tracked(&deletions);
  std::unordered_set<TrackedRef> set{a, b, other};
  CHECK(set.size() == 2);
  CHECK(set.count(b) == 1);
}

TEST_CASE("an observer is non-null while the object lives and null once it is deleted") {
  int deletions = 0;
  TrackedRef object = new Tracked(&deletions);
  spook::observer_ptr<Tracked> observer(object.get());
  CHECK(observer == object.get());
  CHECK(observer.valid());
  CHECK(object->getReferenceCount() == 1);  // observing does not own
  object = nullptr;
  CHECK(deletions == 1);
  CHECK(observer == nullptr);
  CHECK(!observer.valid());
  CHECK(observer.get() == nullptr);
}

// The AGX course, "agx::observer_ptr", word for word.
TEST_CASE("a RigidBodyObserver taken from a RigidBodyRef goes null when the ref lets go") {
  spook::RigidBodyRef rb = new spook::RigidBody("crate");
  spook::RigidBodyObserver o = rb;
  CHECK(o != nullptr);
  CHECK(o->getName() == "crate");
  rb = nullptr;
  CHECK(o == nullptr);

  spook::f32::RigidBodyRef small = new spook::f32::RigidBody("pebble");
  spook::f32::RigidBodyObserver watch = small;
  CHECK(watch == small.get());
  small = nullptr;
  CHECK(watch == nullptr);
}

TEST_CASE("observer copies and assignments all go null with the object") {
  int deletions = 0;
  TrackedRef object = new Tracked(&deletions);
  spook::observer_ptr<Tracked> first(object.get());
  spook::observer_ptr<Tracked> copy = first;
  spook::observer_ptr<Tracked> assigned;
  CHECK(assigned == nullptr);
  assigned = copy;
  spook::observer_ptr<Tracked> moved = std::move(copy);
  CHECK(first == object.get());
  CHECK(assigned == object.get());
  CHECK(moved == object.get());
  object = nullptr;
  CHECK(first == nullptr);
  CHECK(assigned == nullptr);
  CHECK(moved == nullptr);
}

// Run under AddressSanitizer this also shows that the shared hub neither
// leaks nor is read after it is freed, in whichever order things die.
TEST_CASE("observers may outlive the object, be copied after its death, and die in any order") {
  int deletions = 0;
  auto* late = new spook::observer_ptr<Tracked>();
  {
    TrackedRef object = new Tracked(&deletions);
    spook::observer_ptr<Tracked> early(object.get());
    *late = early;
  }
  CHECK(deletions == 1);
  spook::observer_ptr<Tracked> bornAfterDeath = *late;
  CHECK(bornAfterDeath == nullptr);
  delete late;
  CHECK(bornAfterDeath == nullptr);
  bornAfterDeath = nullptr;

  // An observer of an object that dies without ever being observed again.
  TrackedRef second = new Tracked(&deletions);
  { spook::observer_ptr<Tracked> brief(second.get()); }
  second = nullptr;
  CHECK(deletions == 2);
}

TEST_CASE("XxxRef aliases name ref_ptrs of the double types and of spook::f32") {
  CHECK(std::is_same_v<spook::RigidBody, spook::RigidBodyT<double>>);
  CHECK(std::is_same_v<spook::f32::RigidBody, spook::RigidBodyT<float>>);
  CHECK(std::is_same_v<spook::RigidBodyRef, spook::ref_ptr<spook::RigidBodyT<double>>>);
  CHECK(std::is_same_v<spook::RigidBodyObserver, spook::observer_ptr<spook::RigidBodyT<double>>>);
  CHECK(std::is_same_v<spook::SimulationRef, spook::ref_ptr<spook::SimulationT<double>>>);
  CHECK(std::is_same_v<spook::CollectionRef, spook::ref_ptr<spook::CollectionT<double>>>);
  CHECK(std::is_same_v<spook::AssemblyRef, spook::ref_ptr<spook::AssemblyT<double>>>);
  CHECK(std::is_same_v<spook::StepEventListenerRef, spook::ref_ptr<spook::StepEventListenerT<double>>>);
  CHECK(std::is_same_v<spook::FrameRef, spook::ref_ptr<spook::FrameT<double>>>);
  CHECK(std::is_same_v<spook::GravityFieldRef, spook::ref_ptr<spook::GravityFieldT<double>>>);
  CHECK(std::is_same_v<spook::UniformGravityFieldRef, spook::ref_ptr<spook::UniformGravityFieldT<double>>>);
  CHECK(std::is_same_v<spook::PointGravityFieldRef, spook::ref_ptr<spook::PointGravityFieldT<double>>>);
  CHECK(std::is_same_v<spook::f32::RigidBodyRef, spook::ref_ptr<spook::RigidBodyT<float>>>);
  CHECK(std::is_same_v<spook::f32::RigidBodyObserver, spook::observer_ptr<spook::RigidBodyT<float>>>);
  CHECK(std::is_same_v<spook::f32::SimulationRef, spook::ref_ptr<spook::SimulationT<float>>>);
  CHECK(std::is_same_v<spook::f32::CollectionRef, spook::ref_ptr<spook::CollectionT<float>>>);
  CHECK(std::is_same_v<spook::f32::AssemblyRef, spook::ref_ptr<spook::AssemblyT<float>>>);
  CHECK(std::is_same_v<spook::f32::StepEventListenerRef, spook::ref_ptr<spook::StepEventListenerT<float>>>);
  CHECK(std::is_same_v<spook::f32::FrameRef, spook::ref_ptr<spook::FrameT<float>>>);
  CHECK(std::is_same_v<spook::f32::GravityFieldRef, spook::ref_ptr<spook::GravityFieldT<float>>>);
  CHECK(std::is_same_v<spook::f32::UniformGravityFieldRef, spook::ref_ptr<spook::UniformGravityFieldT<float>>>);
  CHECK(std::is_same_v<spook::f32::PointGravityFieldRef, spook::ref_ptr<spook::PointGravityFieldT<float>>>);
}

TEST_CASE("a ref_ptr passes where the API takes a raw pointer, and a raw new where it takes a ref_ptr") {
  spook::SimulationRef sim = new spook::Simulation();
  spook::RigidBodyRef body = new spook::RigidBody("crate");
  sim->add(body);
  CHECK(sim->contains(body));
  CHECK(body->getReferenceCount() == 2);
  sim->remove(body);
  CHECK(body->getReferenceCount() == 1);
  sim->add(new spook::RigidBody("barrel"));
  REQUIRE(sim->getRigidBody("barrel") != nullptr);
  CHECK(sim->getRigidBody("barrel")->getReferenceCount() == 1);
}
