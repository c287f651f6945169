// stdlib/solid.sl: see docs/stdlib/solid.md (being written for issue 7).

#ifndef PATINA_SOLID_SL
#define PATINA_SOLID_SL

#endif
