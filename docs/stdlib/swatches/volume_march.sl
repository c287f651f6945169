// Swatch for docs/stdlib/volume.md: Perlin & Hoffert's noisy sphere (compiler/stdlib/volume.sl) ray-marched
// front to back, orthographically along +z through its bounding sphere: 48 steps, opacity per step
// volume_opacity(20 density h) through volume_composite, each step shaded by the outward normal
// from central differences of the density (volume_density_normal) with one distant light, and a
// Henyey-Greenstein glow (g = 0.6) of the light seen through the volume.
#include <volume.sl>

surface volume_march_swatch()
{
    point o = point(2.4 * s - 1.2, 1.2 - 2.4 * t, -2);
    vector d = vector(0, 0, 1);
    point centre = point(0, 0, 0);
    vector L = normalize(vector(-1, 1, -0.7));
    vector hit = volume_ray_sphere(o, d, centre, 1);
    float t0 = max(hit[0], 0);
    float h = hit[2] * max(hit[1] - t0, 0) / 48;
    float e = 0.02;
    float4 acc = {0, 0, 0, 0};
    constant float i;
    for (i = 0; i < 48; i += 1) {
        point p = o + (t0 + (i + 0.5) * h) * d;
        float density = noisy_sphere(p, centre, 0.65, 0.3, 4, 0.25);
        normal n = volume_density_normal(
            noisy_sphere(p + vector(e, 0, 0), centre, 0.65, 0.3, 4, 0.25),
            noisy_sphere(p - vector(e, 0, 0), centre, 0.65, 0.3, 4, 0.25),
            noisy_sphere(p + vector(0, e, 0), centre, 0.65, 0.3, 4, 0.25),
            noisy_sphere(p - vector(0, e, 0), centre, 0.65, 0.3, 4, 0.25),
            noisy_sphere(p + vector(0, 0, e), centre, 0.65, 0.3, 4, 0.25),
            noisy_sphere(p - vector(0, 0, e), centre, 0.65, 0.3, 4, 0.25), -d);
        float diffuse = max(n . L, 0);
        color c = color(0.9, 0.75, 0.55) * (0.15 + 0.85 * diffuse)
                + color(1, 0.9, 0.7) * 0.4 * henyey_greenstein(d . L, 0.6);
        acc = volume_composite(acc, 20 * density, c, h);
    }
    Ci = rgb(acc) + (1 - acc[3]) * color(0.1, 0.12, 0.2);
    Oi = 1;
}
