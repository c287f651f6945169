// stdlib/lattice.sl: see docs/stdlib/lattice.md (being written for issue 7).

#ifndef PATINA_LATTICE_SL
#define PATINA_LATTICE_SL

#endif
