// Swatch for docs/stdlib/lattice.md: Peachey's gradient noise (left) and value-gradient noise (right) over (8s, 8t), scaled by 1.5 around 0.5.
#include <lattice.sl>

surface lattice_vgnoise_swatch(float scale = 8)
{
    point p = point(scale * s, scale * t, 0.5);
    float a = gnoise(p), b = vgnoise(p);
    Ci = 0.5 + 0.75 * (s < 0.5 ? a : b);
    Oi = 1;
}
