// spook compiled once (the stb convention): this translation unit compiles
// the step, solvers and colliders, every other one (main.cpp) declares them
// extern (SPOOK_EXTERN_TEMPLATES, set for the whole target) and only parses
// their declarations. `#define SPOOK_IMPLEMENTATION` would compile them for
// float and double; a program that steps only double simulations names the
// two double parts instead (core/implementation.hpp) and compiles half.
#define SPOOK_IMPLEMENT_SIMULATION_DOUBLE
#define SPOOK_IMPLEMENT_COLLIDERS_DOUBLE
#include <spook/spook.hpp>
