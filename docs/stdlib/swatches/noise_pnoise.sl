// Swatch for docs/stdlib/noise.md: periodic noise pnoise2(8s, 8t, 3, 3): the pattern repeats
// every 3 units (8/3 times across the square).
#include <noise.sl>

surface noise_pnoise_swatch(float scale = 8)
{
    Ci = pnoise2(scale * s, scale * t, 3, 3);
    Oi = 1;
}
