// Swatch for docs/stdlib/fractal.md: fBm (H 0.5, lacunarity 2, 6 octaves) over (6s, 6t), mapped
// to [0, 1].
#include <fractal.sl>

surface fractal_fbm_swatch(float scale = 6)
{
    Ci = 0.5 + 0.5 * fbm(point(scale * s, scale * t, 0.5), 0.5, 2, 6);
    Oi = 1;
}
