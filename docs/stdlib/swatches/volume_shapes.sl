// Swatch for docs/stdlib/volume.md: the slice z = 0 of three soft shapes (compiler/stdlib/volume.sl), red a
// soft sphere, green a soft box, blue a soft torus around z, over (x, y) in [-2, 2]^2. Where they
// overlap the channels add; the soft edges are the linear-in-r^2 ramps of Perlin & Hoffert.
#include <volume.sl>

surface volume_shapes_swatch()
{
    point p = point(4 * s - 2, 2 - 4 * t, 0);
    float sphere = soft_sphere(p, point(-0.7, 0.6, 0), 0.9, 0.6);
    float box = soft_box(p, point(0.8, 0.7, 0), vector(0.7, 0.5, 0.5), 0.4);
    float torus = soft_torus(p, point(0.1, -0.8, 0), 0.8, 0.25, 0.3);
    Ci = color(sphere, box, torus);
    Oi = 1;
}
