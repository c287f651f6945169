// stdlib/lighting.sl: see docs/stdlib/lighting.md (being written for issue 7).

#ifndef PATINA_LIGHTING_SL
#define PATINA_LIGHTING_SL

#endif
