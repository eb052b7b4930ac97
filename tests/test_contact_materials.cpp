#include <doctest/doctest.h>

#include <cmath>
#include <initializer_list>
#include <limits>
#include <string>
#include <string_view>
#include <tuple>

#include <spook/dynamics/contact_material.hpp>
#include <spook/dynamics/friction_model.hpp>
#include <spook/dynamics/material.hpp>
#include <spook/sim/material_manager.hpp>

#include "tolerance.hpp"

// Two materials combine into contact parameters by the seed's implicit rules
// unless the material manager holds an explicit ContactMaterial for the pair
// (seed 000, "Materials" and "Friction Model").

namespace {

template <class S>
constexpr S kNaN = std::numeric_limits<S>::quiet_NaN();

template <class S>
using MaterialRef = spook::ref_ptr<spook::MaterialT<S>>;

/// Steel and rubber with every combined parameter away from its default.
template <class S>
struct Pair {
  MaterialRef<S> steel = new spook::MaterialT<S>("steel");
  MaterialRef<S> rubber = new spook::MaterialT<S>("rubber");

  Pair() {
    steel->getSurfaceMaterial()->setRoughness(S(0.3));
    steel->getSurfaceMaterial()->setViscosity(S(2e-9));
    steel->getBulkMaterial()->setViscosity(S(0.2));
    steel->getBulkMaterial()->setYoungsModulus(S(1e9));
    steel->getBulkMaterial()->setDamping(S(0.1));
    rubber->getSurfaceMaterial()->setRoughness(S(0.8));
    rubber->getSurfaceMaterial()->setViscosity(S(4e-9));
    rubber->getBulkMaterial()->setViscosity(S(0.5));
    rubber->getBulkMaterial()->setYoungsModulus(S(3e9));
    rubber->getBulkMaterial()->setDamping(S(0.05));
  }
};

template <class S>
auto fields(const spook::ContactParametersT<S>& p) {
  return std::make_tuple(p.friction[0], p.friction[1], p.surfaceViscosity[0], p.surfaceViscosity[1], p.restitution,
                         p.youngsModulus, p.damping, p.adhesiveForce, p.adhesiveOverlap, p.frictionModel,
                         p.reductionMode, p.binResolution, p.explicitMaterial);
}

template <class S>
auto fields(const spook::FrictionModelT<S>& m) {
  const auto* box = dynamic_cast<const spook::BoxFrictionT<S>*>(&m);
  return std::make_tuple(m.getType(), m.getSolveType(), m.hasPrimaryDirection(), m.getPrimaryDirection().x(),
                         m.getPrimaryDirection().y(), m.getPrimaryDirection().z(),
                         box && box->hasNormalForceMagnitude(), box ? box->getNormalForceMagnitude() : S(-1));
}

template <class S>
auto fields(const spook::MaterialT<S>& m) {
  return std::make_tuple(m.getBulkMaterial()->getDensity(), m.getBulkMaterial()->getYoungsModulus(),
                         m.getBulkMaterial()->getViscosity(), m.getBulkMaterial()->getDamping(),
                         m.getSurfaceMaterial()->getRoughness(), m.getSurfaceMaterial()->getViscosity());
}

template <class Call>
std::string messageOf(Call& call) {
  try {
    call();
  } catch (const spook::Error& e) {
    return e.what();
  }
  return "(no spook::Error)";
}

/// `call` must throw spook::Error whose message holds every fragment (the
/// object's name, the value as printed) and leave `capture()` as it was.
template <class Capture, class Call>
void checkRejected(Capture capture, Call call, std::initializer_list<std::string_view> fragments) {
  const auto before = capture();
  CHECK_THROWS_AS(call(), spook::Error);
  const std::string what = messageOf(call);
  for (std::string_view fragment : fragments)
    CHECK_MESSAGE(what.find(fragment) != std::string::npos, "'" << std::string(fragment) << "' not in: " << what);
  CHECK(capture() == before);
}

}  // namespace

TEST_CASE_TEMPLATE("the implicit contact parameters combine the two materials as the seed says", S, float, double) {
  Pair<S> p;
  const auto c = spook::ContactMaterialT<S>::implicitParameters(*p.steel, *p.rubber);
  const S tol = spook::test::pick<S>(1e-14, 1e-6);
  CHECK(c.friction[0] == doctest::Approx(std::sqrt(0.3 * 0.8)).epsilon(tol));  // √(r₁r₂) = √0.24
  CHECK(c.friction[1] == doctest::Approx(std::sqrt(0.24)).epsilon(tol));
  CHECK(c.restitution == doctest::Approx(std::sqrt(0.8 * 0.5)).epsilon(tol));  // √((1−v₁)(1−v₂))
  CHECK(c.youngsModulus == doctest::Approx(7.5e8).epsilon(tol));               // 1e9·3e9 / 4e9
  CHECK(c.damping == doctest::Approx(0.1).epsilon(tol));                       // the larger
  CHECK(c.surfaceViscosity[0] == doctest::Approx(6e-9).epsilon(tol));          // 2e-9 + 4e-9
  CHECK(c.surfaceViscosity[1] == doctest::Approx(6e-9).epsilon(tol));
  CHECK(c.adhesiveForce == S(0));
  CHECK(c.adhesiveOverlap == S(0));
  CHECK(c.frictionModel == nullptr);
  CHECK(c.reductionMode == spook::ContactReductionMode::REDUCE_GEOMETRY);
  CHECK(c.binResolution == 2);
  CHECK_FALSE(c.explicitMaterial);
  CHECK(fields(spook::ContactMaterialT<S>::implicitParameters(*p.rubber, *p.steel)) == fields(c));
}

TEST_CASE_TEMPLATE("two default materials give a plain, non-bouncing contact", S, float, double) {
  MaterialRef<S> a = new spook::MaterialT<S>("a");
  MaterialRef<S> b = new spook::MaterialT<S>("b");
  const auto c = spook::ContactMaterialT<S>::implicitParameters(*a, *b);
  const S tol = spook::test::pick<S>(1e-14, 1e-6);
  CHECK(c.friction[0] == doctest::Approx(0.41667).epsilon(tol));
  CHECK(c.restitution == S(0));
  CHECK(c.youngsModulus == doctest::Approx(2e8).epsilon(tol));  // 4e8 in series with 4e8
  CHECK(c.damping == doctest::Approx(0.075).epsilon(tol));
  CHECK(c.surfaceViscosity[0] == doctest::Approx(1e-8).epsilon(tol));
}

TEST_CASE_TEMPLATE("creating a contact material changes nothing until a value is set", S, float, double) {
  Pair<S> p;
  spook::MaterialManagerT<S> manager;
  const auto before = manager.resolve(*p.steel, *p.rubber);
  CHECK_FALSE(before.explicitMaterial);
  auto* cm = manager.getOrCreateContactMaterial(p.steel, p.rubber);
  REQUIRE(cm != nullptr);
  CHECK(cm->getMaterial1() == p.steel.get());
  CHECK(cm->getMaterial2() == p.rubber.get());
  auto after = manager.resolve(*p.steel, *p.rubber);
  CHECK(after.explicitMaterial);
  after.explicitMaterial = false;
  CHECK(fields(after) == fields(before));
}

TEST_CASE_TEMPLATE("an explicit contact material overrides the implicit values of its pair only", S, float, double) {
  Pair<S> p;
  MaterialRef<S> wood = new spook::MaterialT<S>("wood");
  spook::MaterialManagerT<S> manager;
  auto* cm = manager.getOrCreateContactMaterial(p.steel, p.rubber);
  cm->setFrictionCoefficient(S(0.5));
  cm->setRestitution(S(0.25));
  cm->setYoungsModulus(S(5e7));
  cm->setDamping(S(0.2));
  cm->setAdhesion(S(10), S(0.001));
  cm->setContactReductionMode(spook::ContactReductionMode::REDUCE_ALL);
  cm->setContactReductionBinResolution(3);
  const auto c = manager.resolve(*p.rubber, *p.steel);
  CHECK(c.explicitMaterial);
  CHECK(c.friction[0] == S(0.5));
  CHECK(c.friction[1] == S(0.5));
  CHECK(c.restitution == S(0.25));
  CHECK(c.youngsModulus == S(5e7));
  CHECK(c.damping == S(0.2));
  CHECK(c.adhesiveForce == S(10));
  CHECK(c.adhesiveOverlap == S(0.001));
  CHECK(c.reductionMode == spook::ContactReductionMode::REDUCE_ALL);
  CHECK(c.binResolution == 3);
  CHECK(fields(manager.resolve(*p.steel, *wood)) ==
        fields(spook::ContactMaterialT<S>::implicitParameters(*p.steel, *wood)));
  CHECK(manager.getContactMaterial(p.steel, wood) == nullptr);
}

TEST_CASE_TEMPLATE("the order of the two materials does not matter", S, float, double) {
  Pair<S> p;
  spook::MaterialManagerT<S> manager;
  auto* forward = manager.getOrCreateContactMaterial(p.steel, p.rubber);
  CHECK(manager.getOrCreateContactMaterial(p.rubber, p.steel) == forward);
  CHECK(manager.getContactMaterial(p.rubber, p.steel) == forward);
  CHECK(manager.getContactMaterial(p.steel, p.rubber) == forward);
  CHECK(manager.getNumContactMaterials() == 1);
  forward->setFrictionCoefficient(S(0.9));
  CHECK(manager.resolve(*p.rubber, *p.steel).friction[0] == S(0.9));
  auto* self = manager.getOrCreateContactMaterial(p.steel, p.steel);
  CHECK(self != forward);
  CHECK(manager.getNumContactMaterials() == 2);
}

TEST_CASE_TEMPLATE("friction and surface viscosity can differ between the two tangents", S, float, double) {
  Pair<S> p;
  spook::ref_ptr<spook::ContactMaterialT<S>> cm = new spook::ContactMaterialT<S>(p.steel, p.rubber);
  using CM = spook::ContactMaterialT<S>;
  cm->setFrictionCoefficient(S(0.4));
  cm->setFrictionCoefficient(S(0.2), CM::SECONDARY_DIRECTION);
  CHECK(cm->getFrictionCoefficient() == S(0.4));
  CHECK(cm->getFrictionCoefficient(CM::PRIMARY_DIRECTION) == S(0.4));
  CHECK(cm->getFrictionCoefficient(CM::SECONDARY_DIRECTION) == S(0.2));
  cm->setFrictionCoefficient(S(0.7), CM::PRIMARY_DIRECTION);
  CHECK(cm->parameters().friction[0] == S(0.7));
  CHECK(cm->parameters().friction[1] == S(0.2));
  cm->setSurfaceViscosity(S(1e-7));
  cm->setSurfaceViscosity(S(3e-7), CM::SECONDARY_DIRECTION);
  CHECK(cm->getSurfaceViscosity() == S(1e-7));
  CHECK(cm->getSurfaceViscosity(CM::SECONDARY_DIRECTION) == S(3e-7));
  CHECK(cm->parameters().surfaceViscosity[0] == S(1e-7));
  CHECK(cm->parameters().surfaceViscosity[1] == S(3e-7));
}

TEST_CASE_TEMPLATE("the default friction is the projected cone solved SPLIT", S, float, double) {
  Pair<S> p;
  spook::ref_ptr<spook::ContactMaterialT<S>> cm = new spook::ContactMaterialT<S>(p.steel, p.rubber);
  CHECK(cm->getFrictionModel() == nullptr);
  CHECK(cm->parameters().frictionModel == nullptr);

  spook::ref_ptr<spook::FrictionModelT<S>> cone = new spook::IterativeProjectedConeFrictionT<S>("cone");
  CHECK(cone->getType() == spook::FrictionModelT<S>::ITERATIVE_PROJECTED_CONE);
  CHECK(cone->getSolveType() == spook::SolveType::SPLIT);
  CHECK_FALSE(cone->hasPrimaryDirection());
  CHECK(cone->getName() == "cone");

  spook::ref_ptr<spook::BoxFrictionT<S>> box = new spook::BoxFrictionT<S>();
  CHECK(box->getType() == spook::FrictionModelT<S>::BOX);
  CHECK(box->getSolveType() == spook::SolveType::SPLIT);
  CHECK_FALSE(box->hasNormalForceMagnitude());
  CHECK(box->getNormalForceMagnitude() == S(0));
  spook::ref_ptr<spook::ScaleBoxFrictionT<S>> scaleBox = new spook::ScaleBoxFrictionT<S>("scaled");
  CHECK(scaleBox->getType() == spook::FrictionModelT<S>::SCALE_BOX);
  CHECK(scaleBox->getSolveType() == spook::SolveType::SPLIT);

  cm->setFrictionModel(box);
  CHECK(cm->getFrictionModel() == box.get());
  CHECK(cm->parameters().frictionModel == box.get());
  cm->setFrictionModel(nullptr);
  CHECK(cm->getFrictionModel() == nullptr);
  CHECK(cm->parameters().frictionModel == nullptr);
}

TEST_CASE_TEMPLATE("a friction model keeps its solve type, unit primary direction and box normal force", S, float,
                   double) {
  using Vec3 = spook::Vec3T<S>;
  spook::ref_ptr<spook::BoxFrictionT<S>> box = new spook::BoxFrictionT<S>("box");
  for (auto type : {spook::SolveType::DIRECT, spook::SolveType::ITERATIVE, spook::SolveType::DIRECT_AND_ITERATIVE,
                    spook::SolveType::SPLIT}) {
    box->setSolveType(type);
    CHECK(box->getSolveType() == type);
  }
  box->setPrimaryDirection(Vec3(S(0), S(3), S(4)));
  CHECK(box->hasPrimaryDirection());
  CHECK(box->getPrimaryDirection().isApprox(Vec3(S(0), S(0.6), S(0.8))));
  box->clearPrimaryDirection();
  CHECK_FALSE(box->hasPrimaryDirection());
  box->setNormalForceMagnitude(S(98.1));
  CHECK(box->hasNormalForceMagnitude());
  CHECK(box->getNormalForceMagnitude() == S(98.1));
  box->setNormalForceMagnitude(S(0));
  CHECK(box->hasNormalForceMagnitude());
  box->clearNormalForceMagnitude();
  CHECK_FALSE(box->hasNormalForceMagnitude());
  CHECK(box->getNormalForceMagnitude() == S(0));
}

TEST_CASE_TEMPLATE("the manager adds, replaces and removes contact materials and keeps them alive", S, float, double) {
  spook::MaterialManagerT<S> manager;
  spook::ContactMaterialT<S>* held = nullptr;
  spook::MaterialT<S>* steel = nullptr;
  {
    Pair<S> p;
    steel = p.steel.get();
    spook::ref_ptr<spook::ContactMaterialT<S>> first = new spook::ContactMaterialT<S>(p.steel, p.rubber);
    spook::ref_ptr<spook::ContactMaterialT<S>> second = new spook::ContactMaterialT<S>(p.rubber, p.steel);
    second->setFrictionCoefficient(S(0.05));
    manager.add(first);
    CHECK(manager.getNumContactMaterials() == 1);
    manager.add(second);
    CHECK(manager.getNumContactMaterials() == 1);
    CHECK(manager.getContactMaterial(p.steel, p.rubber) == second.get());
    CHECK_FALSE(manager.remove(first));
    CHECK(manager.getNumContactMaterials() == 1);
    CHECK_FALSE(manager.remove(nullptr));
    held = second.get();
  }
  CHECK(held->getReferenceCount() == 1);
  CHECK(held->getMaterial2() == steel);
  CHECK(steel->getName() == "steel");
  CHECK(manager.resolve(*held->getMaterial1(), *steel).friction[0] == S(0.05));
  CHECK(manager.remove(held));
  CHECK(manager.getNumContactMaterials() == 0);
}

TEST_CASE_TEMPLATE("bad contact material values are rejected and leave it unchanged", S, float, double) {
  using CM = spook::ContactMaterialT<S>;
  Pair<S> p;
  spook::ref_ptr<CM> cm = new CM(p.steel, p.rubber);
  cm->setFrictionCoefficient(S(0.6));
  cm->setFrictionCoefficient(S(0.3), CM::SECONDARY_DIRECTION);
  cm->setRestitution(S(0.5));
  cm->setAdhesion(S(2), S(0.25));
  const auto capture = [&] { return fields(cm->parameters()); };
  const std::string_view name = "'steel/rubber'";
  checkRejected(capture, [&] { cm->setFrictionCoefficient(S(-0.25)); }, {name, "got -0.25"});
  checkRejected(capture, [&] { cm->setFrictionCoefficient(S(-1), CM::SECONDARY_DIRECTION); }, {name, "got -1"});
  checkRejected(capture, [&] { cm->setFrictionCoefficient(kNaN<S>); }, {name, "got nan"});
  checkRejected(capture, [&] { cm->setFrictionCoefficient(S(0.1), static_cast<typename CM::FrictionDirection>(3)); },
                {name, "got 3"});
  checkRejected(capture, [&] { cm->setSurfaceViscosity(S(-0.5)); }, {name, "got -0.5"});
  checkRejected(capture, [&] { cm->setRestitution(S(1.5)); }, {name, "got 1.5"});
  checkRejected(capture, [&] { cm->setRestitution(S(-0.125)); }, {name, "got -0.125"});
  checkRejected(capture, [&] { cm->setRestitution(kNaN<S>); }, {name, "got nan"});
  checkRejected(capture, [&] { cm->setYoungsModulus(S(0)); }, {name, "got 0"});
  checkRejected(capture, [&] { cm->setYoungsModulus(S(-4)); }, {name, "got -4"});
  checkRejected(capture, [&] { cm->setDamping(S(-0.5)); }, {name, "got -0.5"});
  checkRejected(capture, [&] { cm->setAdhesion(S(-3), S(0.5)); }, {name, "got -3"});
  checkRejected(capture, [&] { cm->setAdhesion(S(3), S(-0.5)); }, {name, "got -0.5"});
  checkRejected(capture, [&] { cm->setContactReductionBinResolution(0); }, {name, "got 0"});
  checkRejected(capture, [&] { cm->setContactReductionBinResolution(4); }, {name, "got 4"});
  checkRejected(capture, [&] { cm->setContactReductionMode(static_cast<spook::ContactReductionMode>(9)); },
                {name, "got 9"});
}

TEST_CASE_TEMPLATE("a null material is rejected", S, float, double) {
  using CM = spook::ContactMaterialT<S>;
  Pair<S> p;
  spook::MaterialManagerT<S> manager;
  manager.getOrCreateContactMaterial(p.steel, p.steel);
  const auto count = [&] { return manager.getNumContactMaterials(); };
  checkRejected(count, [&] { spook::ref_ptr<CM> cm = new CM(p.steel, nullptr); },
                {"ContactMaterial", "'steel/", "nullptr"});
  checkRejected(count, [&] { spook::ref_ptr<CM> cm = new CM(nullptr, p.rubber); },
                {"ContactMaterial", "rubber", "nullptr"});
  checkRejected(count, [&] { manager.getOrCreateContactMaterial(nullptr, p.rubber); },
                {"MaterialManager", "rubber", "nullptr"});
  checkRejected(count, [&] { manager.add(nullptr); }, {"MaterialManager", "nullptr"});
  CHECK(p.steel->getReferenceCount() == 3);  // p.steel and the steel/steel contact material's two
  CHECK(p.rubber->getReferenceCount() == 1);
}

TEST_CASE_TEMPLATE("bad friction model values are rejected and leave it unchanged", S, float, double) {
  using Vec3 = spook::Vec3T<S>;
  spook::ref_ptr<spook::BoxFrictionT<S>> box = new spook::BoxFrictionT<S>("dry");
  box->setSolveType(spook::SolveType::ITERATIVE);
  box->setPrimaryDirection(Vec3(S(1), S(0), S(0)));
  box->setNormalForceMagnitude(S(20));
  const auto capture = [&] { return fields<S>(*box); };
  checkRejected(capture, [&] { box->setSolveType(static_cast<spook::SolveType>(0)); },
                {"FrictionModel", "'dry'", "got 0"});
  checkRejected(capture, [&] { box->setSolveType(static_cast<spook::SolveType>(5)); }, {"'dry'", "got 5"});
  checkRejected(capture, [&] { box->setPrimaryDirection(Vec3::Zero()); }, {"'dry'", "got (0, 0, 0)"});
  checkRejected(capture, [&] { box->setPrimaryDirection(Vec3(kNaN<S>, S(1), S(0))); }, {"'dry'", "got (nan, 1, 0)"});
  checkRejected(capture, [&] { box->setNormalForceMagnitude(S(-3)); }, {"'dry'", "got -3"});
  checkRejected(capture, [&] { box->setNormalForceMagnitude(kNaN<S>); }, {"'dry'", "got nan"});
}

TEST_CASE_TEMPLATE("a material density that is not positive is rejected", S, float, double) {
  Pair<S> p;
  const auto capture = [&] { return fields<S>(*p.steel); };
  checkRejected(capture, [&] { p.steel->getBulkMaterial()->setDensity(S(0)); }, {"Material", "'steel'", "got 0"});
  checkRejected(capture, [&] { p.steel->getBulkMaterial()->setDensity(S(-5)); }, {"'steel'", "got -5"});
}
