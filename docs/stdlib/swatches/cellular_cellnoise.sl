// Swatch for docs/stdlib/cellular.md: RenderMan's cellnoise over (8s, 8t): one colour per unit cell from seeds 0, 1, 2.
#include <cellular.sl>

surface cellular_cellnoise_swatch(float scale = 8)
{
    point p = point(scale * s, scale * t, 0.5);
    Ci = color(cellnoise3(p, 0), cellnoise3(p, 1), cellnoise3(p, 2));
    Oi = 1;
}
