// The one translation unit of the test suite that compiles the colliders of
// the full shape list (see SPOOK_EXTERN_TEMPLATES in spook/collide/space.hpp);
// every other test file of spook_tests declares them extern.
#define SPOOK_IMPLEMENTATION
#include <spook/collide/space.hpp>
