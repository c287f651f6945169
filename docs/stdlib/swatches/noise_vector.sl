// Swatch for docs/stdlib/noise.md: vector noise as a colour, 0.5 + 0.5 * vsnoise3 over
// (4s, 4t, 0.5).
#include <noise.sl>

surface noise_vector_swatch(float scale = 4)
{
    vector v = vsnoise3(point(scale * s, scale * t, 0.5));
    Ci = color(0.5 + 0.5 * xcomp(v), 0.5 + 0.5 * ycomp(v), 0.5 + 0.5 * zcomp(v));
    Oi = 1;
}
