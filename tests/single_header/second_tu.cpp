// A second translation unit including the single header: any non-inline,
// non-template definition in it becomes a duplicate symbol at link time.
// It instantiates little (a box's inertia; main.cpp steps the simulation),
// so that it compiles in seconds: the symbols it checks are emitted by the
// inclusion alone.
#include <spook/spook.hpp>

// Inertia about x of a box of half extents (a, b, c) and mass m (kg m²); used by main.cpp.
double boxInertiaX(double a, double b, double c, double m) {
  spook::BoxRef box = new spook::Box(spook::Vec3(a, b, c));
  return box->calculateInertia(m).diagonal().x();
}
