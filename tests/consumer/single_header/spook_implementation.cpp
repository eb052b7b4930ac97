// spook compiled once (the stb convention): this translation unit defines
// SPOOK_IMPLEMENTATION before including the single header and so compiles
// the step, solvers and colliders for float and double; every other one
// (main.cpp) declares them extern (SPOOK_EXTERN_TEMPLATES, set for the
// whole target) and only parses their declarations.
#define SPOOK_IMPLEMENTATION
#include <spook/spook.hpp>
