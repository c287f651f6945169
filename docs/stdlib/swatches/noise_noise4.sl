// Swatch for docs/stdlib/noise.md: noise4 (4D improved noise) over (8s, 8t, 0.5, w = 0.3).
#include <noise.sl>

surface noise_noise4_swatch(float scale = 8)
{
    Ci = noise4(point(scale * s, scale * t, 0.5), 0.3);
    Oi = 1;
}
