// Swatch for docs/stdlib/solid.md: Hart's fire preset on the plane (3s, 0, t - 0.45) at phase 0:
// r grows downwards, so the flames are bright at the bottom and fade to black at the top.
#include <solid.sl>

surface solid_fire_swatch(float scale = 3)
{
    point p = point(scale * s, 0, t - 0.45);
    Ci = hart_fire(p, 0, filterwidth(scale * s) + filterwidth(t));
    Oi = 1;
}
