#include <doctest/doctest.h>

#include <random>
#include <vector>

#include <spook/core/frame.hpp>

#include "tolerance.hpp"

using spook::test::pick;

namespace {

template <class S>
spook::TransformT<S> randomTransform(std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-2.0, 2.0);
  return spook::makeTransform<S>(spook::Vec3T<S>(S(u(rng)), S(u(rng)), S(u(rng))),
                                 spook::toQuat(spook::EulerAnglesT<S>{S(u(rng)), S(u(rng) / 2), S(u(rng))}));
}

// A chain root → … → leaf of `depth` frames with random local transforms.
template <class S>
std::vector<spook::ref_ptr<spook::FrameT<S>>> makeChain(int depth, std::mt19937& rng) {
  std::vector<spook::ref_ptr<spook::FrameT<S>>> chain;
  for (int i = 0; i < depth; ++i) {
    chain.push_back(new spook::FrameT<S>(randomTransform<S>(rng)));
    if (i > 0) chain[i]->setParent(chain[i - 1].get());
  }
  return chain;
}

}  // namespace

TEST_CASE_TEMPLATE("a chain of five frames maps points to world and back", S, float, double) {
  const S tol = pick<S>(1e-12, 2e-5);
  std::mt19937 rng(11);
  for (int trial = 0; trial < 50; ++trial) {
    const auto chain = makeChain<S>(5, rng);
    const spook::FrameT<S>& leaf = *chain.back();
    spook::TransformT<S> product = spook::TransformT<S>::Identity();
    for (const auto& f : chain) product = product * f->getLocalMatrix();
    CHECK((leaf.getMatrix().matrix() - product.matrix()).norm() < tol);

    const spook::Vec3T<S> p(S(0.3), S(-1.2), S(2.5));
    const spook::Vec3T<S> p_W = leaf.transformPointToWorld(p);
    CHECK((p_W - product * p).norm() < tol);
    CHECK((leaf.transformPointToLocal(p_W) - p).norm() < tol);
    const spook::Vec3T<S> v_W = leaf.transformVectorToWorld(p);
    CHECK((v_W - product.linear() * p).norm() < tol);
    CHECK((leaf.transformVectorToLocal(v_W) - p).norm() < tol);
  }
}

TEST_CASE_TEMPLATE("world setters keep the world value under a moved parent", S, float, double) {
  const S tol = pick<S>(1e-12, 1e-5);
  std::mt19937 rng(5);
  const auto chain = makeChain<S>(3, rng);
  spook::FrameT<S>& child = *chain.back();
  const spook::Vec3T<S> p_W(S(1), S(2), S(3));
  const spook::QuatT<S> q_W = spook::toQuat(spook::EulerAnglesT<S>{S(0.4), S(-0.2), S(1.1)});
  child.setTranslate(p_W);
  child.setRotate(q_W);
  CHECK((child.getTranslate() - p_W).norm() < tol);
  CHECK(std::abs(std::abs(child.getRotate().dot(q_W)) - S(1)) < tol);

  const spook::TransformT<S> X_W = randomTransform<S>(rng);
  child.setMatrix(X_W);
  CHECK((child.getMatrix().matrix() - X_W.matrix()).norm() < tol);
  CHECK(((chain[1]->getMatrix() * child.getLocalMatrix()).matrix() - X_W.matrix()).norm() < tol);

  // Moving the parent moves the child with it: local values are kept.
  const spook::TransformT<S> before = child.getLocalMatrix();
  chain[0]->setTranslate(S(10), S(0), S(0));
  CHECK((child.getLocalMatrix().matrix() - before.matrix()).norm() < tol);
  CHECK((child.getMatrix().matrix() - (chain[1]->getMatrix() * before).matrix()).norm() < tol);
}

TEST_CASE_TEMPLATE("local setters are relative to the parent", S, float, double) {
  const S tol = pick<S>(1e-14, 1e-6);
  spook::ref_ptr<spook::FrameT<S>> parent = new spook::FrameT<S>();
  spook::ref_ptr<spook::FrameT<S>> child = new spook::FrameT<S>();
  child->setParent(parent.get());
  parent->setTranslate(S(0), S(0), S(1));
  parent->setRotate(spook::rotate<S>(spook::Vec3T<S>::UnitX(), spook::Vec3T<S>::UnitY()));
  child->setLocalTranslate(S(2), S(0), S(0));
  CHECK((child->getTranslate() - spook::Vec3T<S>(S(0), S(2), S(1))).norm() < tol);
  child->setLocalRotate(spook::rotate<S>(spook::Vec3T<S>::UnitX(), spook::Vec3T<S>::UnitY()));
  CHECK((child->transformVectorToWorld(spook::Vec3T<S>::UnitX()) + spook::Vec3T<S>::UnitX()).norm() < tol);
}

TEST_CASE("a frame cannot become its own ancestor") {
  spook::FrameRef a = new spook::Frame(), b = new spook::Frame(), c = new spook::Frame();
  b->setParent(a);
  c->setParent(b);
  CHECK_THROWS_AS(a->setParent(c), spook::Error);
  CHECK_THROWS_AS(a->setParent(a), spook::Error);
  CHECK(a->getParent() == nullptr);
}
