// stdlib/cellular.sl: see docs/stdlib/cellular.md (being written for issue 7).

#ifndef PATINA_CELLULAR_SL
#define PATINA_CELLULAR_SL

#endif
