// Swatch for docs/stdlib/volume.md: Wyvill's cubic blend (compiler/stdlib/volume.sl) of three point
// primitives of radius R = 1.1 in the slice z = 0, over (x, y) in [-2, 2]^2: the summed field in
// grey, the 0.5 contour (the blended surface) in orange; each field is exactly 0 beyond R.
#include <volume.sl>

surface volume_blend_swatch()
{
    point p = point(4 * s - 2, 2 - 4 * t, 0);
    float field = wyvill_blend(p, point(-0.7, 0.3, 0), 1.1) + wyvill_blend(p, point(0.6, 0.5, 0), 1.1)
                + wyvill_blend(p, point(0, -0.7, 0), 1.1);
    float contour = 1 - smoothstep(0.0, 0.04, abs(field - 0.5));
    Ci = mix(color(clamp(field, 0, 1)), color(1, 0.55, 0.1), contour);
    Oi = 1;
}
