// Swatch for docs/stdlib/noise.md: Perlin's original noise (1985), 0.5 + 0.5 * perlin_noise3
// over (8s, 8t, 0.5).
#include <noise.sl>

surface noise_perlin_swatch(float scale = 8)
{
    Ci = clamp(0.5 + 0.5 * perlin_noise3(point(scale * s, scale * t, 0.5)), 0, 1);
    Oi = 1;
}
