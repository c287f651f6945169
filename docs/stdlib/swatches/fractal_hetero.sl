// Swatch for docs/stdlib/fractal.md: heterogeneous terrain (H 0.25, lacunarity 2, 5 octaves,
// offset 0.3) over (3s, 3t) as a height map: smooth near sea level (dark), rough at altitude.
#include <fractal.sl>

surface fractal_hetero_swatch(float scale = 3)
{
    float h = hetero_terrain(point(scale * s, scale * t, 0.5), 0.25, 2, 5, 0.3);
    Ci = clamp(0.3 + 0.3 * h, 0, 1);
    Oi = 1;
}
