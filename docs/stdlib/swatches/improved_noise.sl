// Swatch for docs/stdlib/noise.md: Perlin's improved noise over (8s, 8t), mapped to [0, 1].
#include <noise.sl>

surface improved_noise_swatch(float scale = 8)
{
    Ci = noise3(point(scale * s, scale * t, 0.5));
    Oi = 1;
}
