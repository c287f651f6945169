// Perlin & Hoffert's soft sphere (PH L67-71; stdlib volume.sl) ray-marched front to back with an
// exact reference: centre 0, radius 0.4, softness 0.2 (inner radius r1 = 0.3, outer r0 = 0.5), in
// the unit cube, seen orthographically along +z. The rays start on the plane z = -1, at
// x = extent (s - 1/2), y = extent (1/2 - t), so that the unit plane filling the image shows the
// square [-extent/2, extent/2]^2; a ray's impact parameter is b = sqrt(x^2 + y^2).
//
// Each ray is clipped to the outer sphere (volume_ray_sphere) and that chord is cut into `steps`
// equal steps of length h; the density is sampled at fraction `phase` of each step (1/2: the
// midpoint rule; 0: the left endpoint) and composited with volume_composite at extinction
// kappa * D (linear in the density), emission only, in the constant colour `emission`. The
// opacity is then exactly 1 - exp(-kappa h sum D_k) up to rounding, the quadrature of the
// closed-form optical depth I(b) of the digest (seed-digest §12 S2). Oi is that opacity (grey), Ci
// the premultiplied emission, so a render on a transparent background has the marched opacity as
// its alpha channel.
//
// Variant C (`variant` = 1): the generalized union (soft_union, PH L80) of two such spheres with
// centres (+-offset, 0, 0), marched over the union of their two chords.
#include <volume.sl>

// The density of the scene at p: one soft sphere, or the soft union of two.
float soft_sphere_density(point p; float variant, offset)
{
    if (variant < 0.5)
        return soft_sphere(p, point(0, 0, 0), 0.4, 0.2);
    return soft_union(soft_sphere(p, point(-offset, 0, 0), 0.4, 0.2),
                      soft_sphere(p, point(offset, 0, 0), 0.4, 0.2));
}

// The cost knob: past 65535 steps the interpreter's loop budget stops the march (docs/limits.md).
// sweep: steps in [1, 1024]
surface
soft_sphere(float steps = 64, kappa = 3, phase = 0.5, extent = 1.2;
            color emission = color(1, 0.55, 0.15);
            float variant = 0, offset = 0.25)
{
    point o = point(extent * (s - 0.5), extent * (0.5 - t), -1);
    vector d = vector(0, 0, 1);
    // The chord through the outer sphere (both outer spheres for the union).
    vector hit;
    if (variant < 0.5) {
        hit = volume_ray_sphere(o, d, point(0, 0, 0), 0.5);
    } else {
        vector a = volume_ray_sphere(o, d, point(-offset, 0, 0), 0.5);
        vector b = volume_ray_sphere(o, d, point(offset, 0, 0), 0.5);
        if (a[2] > 0 && b[2] > 0)
            hit = vector(min(a[0], b[0]), max(a[1], b[1]), 1);
        else
            hit = a[2] > 0 ? a : b;
    }
    uniform float n = max(floor(steps), 1);
    float h = hit[2] * (hit[1] - hit[0]) / n;
    float4 acc = {0, 0, 0, 0};
    uniform float i;
    for (i = 0; i < n; i += 1) {
        point p = o + (hit[0] + (i + phase) * h) * d;
        acc = volume_composite(acc, kappa * soft_sphere_density(p, variant, offset), emission, h);
    }
    Ci = rgb(acc);
    Oi = acc[3];
}

// The exact image of `soft_sphere` (variant 0), the reference `patina bench` measures the march
// against: the closed-form optical depth of the unit-extinction soft sphere along the ray at
// impact parameter b (seed-digest §12 S2; S0 and S1 are the half-chords of the outer and inner
// spheres), and the opacity 1 - exp(-kappa tau) of linear extinction, emission only.
// sweep: kappa in [0, 1e4] (an absorption coefficient: a negative one amplifies without bound)
surface
soft_sphere_exact(float kappa = 3, extent = 1.2; color emission = color(1, 0.55, 0.15))
{
    float r1 = 0.3, r0 = 0.5;
    float b = length(vector(extent * (s - 0.5), extent * (0.5 - t), 0));
    float d = r0 * r0 - r1 * r1;
    float tau = 0;
    if (b < r0) {
        float s0 = sqrt(r0 * r0 - b * b);
        if (b >= r1) {
            tau = 4.0 / 3.0 * s0 * s0 * s0 / d;
        } else {
            float s1 = sqrt(r1 * r1 - b * b);
            tau = 2 * s1 + 2 * (s0 * s0 * (s0 - s1) - (s0 * s0 * s0 - s1 * s1 * s1) / 3) / d;
        }
    }
    float alpha = 1 - exp(-kappa * tau);
    Ci = emission * alpha;
    Oi = alpha;
}
