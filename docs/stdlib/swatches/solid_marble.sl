// Swatch for docs/stdlib/solid.md: Hart's marble preset on the plane (4s, 0.5, 4t): the ramp
// along r (here 4t) distorted by four octaves of noise, modulo one.
#include <solid.sl>

surface solid_marble_swatch(float scale = 4)
{
    point p = point(scale * s, 0.5, scale * t);
    Ci = hart_marble(p, filterwidth(scale * s) + filterwidth(scale * t));
    Oi = 1;
}
