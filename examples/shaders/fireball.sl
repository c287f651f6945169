// Perlin & Hoffert's fire ball (PH L246-250; stdlib volume.sl `fireball`): the soft sphere of
// radius 0.4 and softness 0.2 evaluated at x (1 + amplitude turbulence(frequency x)), emitting
// and absorbing, no lighting and no normals. Orthographic rays along +z from the plane z = -1
// (x = extent (s - 1/2), y = extent (1/2 - t)), clipped to the outer sphere (radius 0.5: the
// turbulence is >= 0, so the modulated density is 0 beyond it), cut into `steps` equal steps and
// sampled at their midpoints; each step composites (volume_composite) extinction kappa D and the
// colour fireball_color(D), red at low density to yellow at high (PH L250). `octaves` is the
// turbulence's octave count (fractional octaves blend in continuously).
#include <volume.sl>

// The colour map: deep red at density 0, through orange, to pale yellow at density 1; every
// channel is non-decreasing in the density.
color fireball_color(float density)
{
    float d = clamp(density, 0, 1);
    return color(0.8 + 0.2 * d, 0.04 + 0.86 * d * d, 0.01 + 0.35 * d * d * d * d);
}

// The fire ball's density at p (centre 0).
float fireball_density(point p; float frequency, amplitude, octaves)
{
    return fireball(p, point(0, 0, 0), 0.4, 0.2, frequency, amplitude, octaves);
}

// The cost knobs: past 65535 steps the interpreter's loop budget stops the march (docs/limits.md).
// sweep: steps in [1, 1024]; octaves in [0, 12]
surface
fireball_march(float steps = 64, octaves = 5, kappa = 8, frequency = 3, amplitude = 1.5,
               extent = 1)
{
    point o = point(extent * (s - 0.5), extent * (0.5 - t), -1);
    vector d = vector(0, 0, 1);
    vector hit = volume_ray_sphere(o, d, point(0, 0, 0), 0.5);
    uniform float n = max(floor(steps), 1);
    float h = hit[2] * (hit[1] - hit[0]) / n;
    float4 acc = {0, 0, 0, 0};
    uniform float i;
    for (i = 0; i < n; i += 1) {
        point p = o + (hit[0] + (i + 0.5) * h) * d;
        float density = fireball_density(p, frequency, amplitude, octaves);
        acc = volume_composite(acc, kappa * density, fireball_color(density), h);
    }
    Ci = rgb(acc);
    Oi = acc[3];
}
