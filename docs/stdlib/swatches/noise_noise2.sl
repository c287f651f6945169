// Swatch for docs/stdlib/noise.md: noise2 (2D improved noise, the plane z = 0) over (8s, 8t).
#include <noise.sl>

surface noise_noise2_swatch(float scale = 8)
{
    Ci = noise2(scale * s, scale * t);
    Oi = 1;
}
