#pragma once

// Compiled once instead of header-only (the stb convention). A program that
// defines SPOOK_EXTERN_TEMPLATES everywhere declares spook's heavy templates
// extern (the simulation step with its solvers and contact code, the
// colliders of the full shape list) for float and double; one translation
// unit that defines SPOOK_IMPLEMENTATION before including <spook/spook.hpp>
// compiles them. A build may instead split that work over several
// translation units, each defining one or more of the parts below (CMake's
// spook::spook_compiled does, so that its parts compile in parallel).
#if defined(SPOOK_IMPLEMENTATION) && !defined(SPOOK_IMPLEMENT_SIMULATION_DOUBLE) &&   \
    !defined(SPOOK_IMPLEMENT_SIMULATION_FLOAT) && !defined(SPOOK_IMPLEMENT_COLLIDERS_DOUBLE) && \
    !defined(SPOOK_IMPLEMENT_COLLIDERS_FLOAT)
#define SPOOK_IMPLEMENT_SIMULATION_DOUBLE
#define SPOOK_IMPLEMENT_SIMULATION_FLOAT
#define SPOOK_IMPLEMENT_COLLIDERS_DOUBLE
#define SPOOK_IMPLEMENT_COLLIDERS_FLOAT
#endif

// What this translation unit sees. Header-only (no SPOOK_EXTERN_TEMPLATES):
// every definition. Otherwise only the declarations of the step and the
// solver, unless it implements a simulation part:
//   SPOOK_DEFINES_STEP           the simulation step's template definitions
//                                (sim/simulation_step.hpp), for either scalar;
//   SPOOK_DEFINES_NON_TEMPLATES  spook's non-template functions that do work
//                                (the double-only solver in
//                                solver/solver_impl.hpp, the island problem,
//                                the joints' row helpers, the convex hull),
//                                compiled with the double simulation and
//                                inline (SPOOK_INLINE) when header-only.
// A header declares such a function (SPOOK_INLINE where it is a free
// function) and defines it, with SPOOK_INLINE, in an
// `#if defined(SPOOK_DEFINES_NON_TEMPLATES)` block: every other file that
// includes spook then parses the declaration only and does not instantiate
// the Eigen expressions of its body (they cost ~3 s per file).
#if !defined(SPOOK_EXTERN_TEMPLATES) || defined(SPOOK_IMPLEMENT_SIMULATION_DOUBLE) || \
    defined(SPOOK_IMPLEMENT_SIMULATION_FLOAT)
#define SPOOK_DEFINES_STEP
#endif
#if defined(SPOOK_IMPLEMENT_SIMULATION_DOUBLE)
#define SPOOK_DEFINES_NON_TEMPLATES
#define SPOOK_INLINE
#elif !defined(SPOOK_EXTERN_TEMPLATES)
#define SPOOK_DEFINES_NON_TEMPLATES
#define SPOOK_INLINE inline
#else
#define SPOOK_INLINE
#endif

// The API's class templates (bodies, frames, geometries, shapes, joints)
// follow the simulation parts: SPOOK_COMPILED_ONCE(class, RigidBodyT) after a
// class's member definitions declares RigidBodyT<double> and <float> extern
// where spook is compiled once, instantiates them where the double or float
// simulation part is implemented, and is nothing header-only. Their heavy
// members are defined outside the class body: an extern template stops the
// instantiation of those only, not of inline ones, which every translation
// unit would otherwise compile again (with the Eigen expressions they use).
#if defined(SPOOK_IMPLEMENT_SIMULATION_DOUBLE)
#define SPOOK_COMPILED_DOUBLE(...) template __VA_ARGS__;
#elif defined(SPOOK_EXTERN_TEMPLATES)
#define SPOOK_COMPILED_DOUBLE(...) extern template __VA_ARGS__;
#else
#define SPOOK_COMPILED_DOUBLE(...)
#endif
#if defined(SPOOK_IMPLEMENT_SIMULATION_FLOAT)
#define SPOOK_COMPILED_FLOAT(...) template __VA_ARGS__;
#elif defined(SPOOK_EXTERN_TEMPLATES)
#define SPOOK_COMPILED_FLOAT(...) extern template __VA_ARGS__;
#else
#define SPOOK_COMPILED_FLOAT(...)
#endif
#define SPOOK_COMPILED_ONCE(kind, name) SPOOK_COMPILED_DOUBLE(kind name<double>) SPOOK_COMPILED_FLOAT(kind name<float>)

// The same for the shape classes, with the collider parts: a shape's
// virtual table holds its colliders (ShapeT::collideWithLowerRank), which
// compile with it.
#if defined(SPOOK_IMPLEMENT_COLLIDERS_DOUBLE)
#define SPOOK_COLLIDERS_DOUBLE(...) template __VA_ARGS__;
#elif defined(SPOOK_EXTERN_TEMPLATES)
#define SPOOK_COLLIDERS_DOUBLE(...) extern template __VA_ARGS__;
#else
#define SPOOK_COLLIDERS_DOUBLE(...)
#endif
#if defined(SPOOK_IMPLEMENT_COLLIDERS_FLOAT)
#define SPOOK_COLLIDERS_FLOAT(...) template __VA_ARGS__;
#elif defined(SPOOK_EXTERN_TEMPLATES)
#define SPOOK_COLLIDERS_FLOAT(...) extern template __VA_ARGS__;
#else
#define SPOOK_COLLIDERS_FLOAT(...)
#endif
#define SPOOK_COMPILED_WITH_COLLIDERS(kind, name) \
  SPOOK_COLLIDERS_DOUBLE(kind name<double>) SPOOK_COLLIDERS_FLOAT(kind name<float>)
