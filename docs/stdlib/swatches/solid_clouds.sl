// Swatch for docs/stdlib/solid.md: Hart's clouds preset over (4s, 4t, 0.3), clamped blue to
// white.
#include <solid.sl>

surface solid_clouds_swatch(float scale = 4)
{
    point p = point(scale * s, scale * t, 0.3);
    Ci = hart_clouds(p, filterwidth(scale * s) + filterwidth(scale * t));
    Oi = 1;
}
