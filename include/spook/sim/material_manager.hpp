#pragma once

#include <cstddef>
#include <functional>
#include <unordered_map>
#include <utility>

#include <spook/core/error.hpp>
#include <spook/core/implementation.hpp>
#include <spook/core/pointer_pair_hash.hpp>
#include <spook/core/ref_ptr.hpp>
#include <spook/core/scalar.hpp>
#include <spook/dynamics/contact_material.hpp>
#include <spook/dynamics/material.hpp>

namespace spook {

/// The material table of a simulation (seed 000, "Explicit
/// agx::ContactMaterial"): at most one explicit ContactMaterial per
/// unordered pair of materials; pairs without one use the implicit
/// combination. Keeps its contact materials, and through them their
/// materials, alive.
template <Scalar S>
class MaterialManagerT {
 public:
  /// The explicit contact material of the pair (order does not matter),
  /// created from the implicit values when missing.
  ContactMaterialT<S>* getOrCreateContactMaterial(MaterialT<S>* m1, MaterialT<S>* m2);

  /// The explicit contact material of the pair (order does not matter);
  /// nullptr when there is none.
  [[nodiscard]] ContactMaterialT<S>* getContactMaterial(const MaterialT<S>* m1, const MaterialT<S>* m2) const;

  /// Adds an explicit contact material, replacing an earlier one of the
  /// same pair.
  void add(ref_ptr<ContactMaterialT<S>> contactMaterial);

  /// Removes a contact material; false when it is not in the table.
  bool remove(ContactMaterialT<S>* contactMaterial);

  [[nodiscard]] std::size_t getNumContactMaterials() const { return table_.size(); }

  /// What the solver uses for a contact between the two materials: the
  /// explicit contact material's parameters, else the implicit combination.
  [[nodiscard]] ContactParametersT<S> resolve(const MaterialT<S>& m1, const MaterialT<S>& m2) const;

 private:
  using Key = std::pair<const MaterialT<S>*, const MaterialT<S>*>;
  static Key keyOf(const MaterialT<S>* m1, const MaterialT<S>* m2);

  std::unordered_map<Key, ref_ptr<ContactMaterialT<S>>, detail::PointerPairHash> table_;
};

template <Scalar S>
auto MaterialManagerT<S>::getOrCreateContactMaterial(MaterialT<S>* m1, MaterialT<S>* m2) -> ContactMaterialT<S>* {
  if (!m1 || !m2)
    throw detail::makeError("MaterialManager", detail::materialPairName<S>(m1, m2), "both materials must be non-null",
                            "nullptr");
  const Key key = keyOf(m1, m2);
  if (auto it = table_.find(key); it != table_.end()) return it->second.get();
  ref_ptr<ContactMaterialT<S>> created = new ContactMaterialT<S>(m1, m2);
  return table_.emplace(key, std::move(created)).first->second.get();
}

template <Scalar S>
auto MaterialManagerT<S>::getContactMaterial(const MaterialT<S>* m1, const MaterialT<S>* m2) const
    -> ContactMaterialT<S>* {
  if (table_.empty()) return nullptr;
  auto it = table_.find(keyOf(m1, m2));
  return it == table_.end() ? nullptr : it->second.get();
}

template <Scalar S>
void MaterialManagerT<S>::add(ref_ptr<ContactMaterialT<S>> contactMaterial) {
  if (!contactMaterial) throw detail::makeError("MaterialManager", "", "contact material must be non-null", "nullptr");
  const Key key = keyOf(contactMaterial->getMaterial1(), contactMaterial->getMaterial2());
  table_.insert_or_assign(key, std::move(contactMaterial));
}

template <Scalar S>
bool MaterialManagerT<S>::remove(ContactMaterialT<S>* contactMaterial) {
  if (!contactMaterial) return false;
  auto it = table_.find(keyOf(contactMaterial->getMaterial1(), contactMaterial->getMaterial2()));
  if (it == table_.end() || it->second.get() != contactMaterial) return false;
  table_.erase(it);
  return true;
}

template <Scalar S>
auto MaterialManagerT<S>::resolve(const MaterialT<S>& m1, const MaterialT<S>& m2) const -> ContactParametersT<S> {
  if (const ContactMaterialT<S>* explicitMaterial = getContactMaterial(&m1, &m2)) return explicitMaterial->parameters();
  return ContactMaterialT<S>::implicitParameters(m1, m2);
}

template <Scalar S>
auto MaterialManagerT<S>::keyOf(const MaterialT<S>* m1, const MaterialT<S>* m2) -> Key {
  return std::less<const MaterialT<S>*>()(m2, m1) ? Key(m2, m1) : Key(m1, m2);
}

SPOOK_COMPILED_ONCE(class, MaterialManagerT)

using MaterialManager = MaterialManagerT<double>;
namespace f32 {
using MaterialManager = MaterialManagerT<float>;
}  // namespace f32

}  // namespace spook
