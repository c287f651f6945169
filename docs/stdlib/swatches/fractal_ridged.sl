// Swatch for docs/stdlib/fractal.md: the ridged multifractal (H 1, lacunarity 2, 6 octaves,
// offset 1, gain 2; Musgrave's suggested values) over (4s, 4t), divided by 2.
#include <fractal.sl>

surface fractal_ridged_swatch(float scale = 4)
{
    Ci = 0.5 * ridged_multifractal(point(scale * s, scale * t, 0.5), 1, 2, 6, 1, 2);
    Oi = 1;
}
