// Swatch for docs/stdlib/fractal.md: distorted noise (distortion 1, Musgrave's Fig. 15.2) over
// (6s, 6t), mapped to [0, 1]; left half snoise3, right half distnoise, for comparison.
#include <fractal.sl>

surface fractal_distnoise_swatch(float scale = 6)
{
    point p = point(scale * s, scale * t, 0.5);
    float n = s < 0.5 ? snoise3(p) : distnoise(p, 1);
    Ci = 0.5 + 0.5 * n;
    Oi = 1;
}
