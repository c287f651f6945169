// Swatch for docs/stdlib/solid.md: Hart's wood preset over (4s - 2, 4t - 2, 0.3): rings about
// the r axis through the centre, box-filtered at the pixel's filter width.
#include <solid.sl>

surface solid_wood_swatch(float scale = 4)
{
    point p = point(scale * s - 2, scale * t - 2, 0.3);
    Ci = hart_wood(p, filterwidth(scale * s) + filterwidth(scale * t));
    Oi = 1;
}
