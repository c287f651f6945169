// Swatch for docs/stdlib/lattice.md: Peachey's value noise (Catmull-Rom) over (8s, 8t), mapped from [-1, 1] to [0, 1]; left half linear interpolation, right half cubic.
#include <lattice.sl>

surface lattice_vnoise_swatch(float scale = 8)
{
    point p = point(scale * s, scale * t, 0.5);
    float a = vnoise_linear(p), b = vnoise(p);
    Ci = 0.5 + 0.5 * (s < 0.5 ? a : b);
    Oi = 1;
}
