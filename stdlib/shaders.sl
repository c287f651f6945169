// stdlib/shaders.sl: the standard RenderMan light and surface shaders; see docs/stdlib/lighting.md (being written for issue 7).

#ifndef PATINA_SHADERS_SL
#define PATINA_SHADERS_SL

#endif
