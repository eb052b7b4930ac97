// One part of spook compiled once (spook::spook_compiled; see
// include/spook/core/implementation.hpp): the other parts stay extern here
// and compile in parallel in their own translation units.
#define SPOOK_IMPLEMENT_COLLIDERS_FLOAT
#include <spook/spook.hpp>
