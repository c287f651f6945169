// Swatch for docs/stdlib/noise.md: the graph of noise1(8 s) (1D improved noise in [0, 1]) over
// the unit square, t = 0 at the top: white below the curve.
#include <noise.sl>

surface noise_snoise1_swatch(float scale = 8)
{
    float n = noise1(scale * s);
    Ci = mix(color(0.15, 0.2, 0.3), color(1, 0.95, 0.85), step(1 - t, n));
    Oi = 1;
}
