// Swatch for docs/stdlib/noise.md: the analytic gradient dsnoise3 as a colour,
// 0.5 + 0.2 * dsnoise3 over (4s, 4t, 0.5).
#include <noise.sl>

surface noise_gradient_swatch(float scale = 4)
{
    vector g = dsnoise3(point(scale * s, scale * t, 0.5));
    Ci = clamp(color(0.5 + 0.2 * xcomp(g), 0.5 + 0.2 * ycomp(g), 0.5 + 0.2 * zcomp(g)), 0, 1);
    Oi = 1;
}
