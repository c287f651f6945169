// Swatch for docs/stdlib/lattice.md: Peachey's lattice convolution noise vcnoise (left) and sparse convolution noise scnoise (right) over (8s, 8t), mapped to [0, 1].
#include <lattice.sl>

surface lattice_convolution_swatch(float scale = 8)
{
    point p = point(scale * s, scale * t, 0.5);
    float a = vcnoise(p), b = scnoise(p);
    Ci = 0.5 + (s < 0.5 ? 0.4 * a : 0.6 * b);
    Oi = 1;
}
