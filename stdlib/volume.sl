// stdlib/volume.sl: see docs/stdlib/volume.md (being written for issue 7).

#ifndef PATINA_VOLUME_SL
#define PATINA_VOLUME_SL

#endif
