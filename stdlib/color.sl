// stdlib/color.sl: see docs/stdlib/color.md (being written for issue 7).

#ifndef PATINA_COLOR_SL
#define PATINA_COLOR_SL

#endif
