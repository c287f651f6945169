// The standard light and surface shaders of stdlib/shaders.sl, for scenes: a scene names a shader
// file, not a library module, so this wrapper includes the module and the scene picks a shader of
// it by name (`name = "plastic"`).
#include <shaders.sl>
