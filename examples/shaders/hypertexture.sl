// Perlin & Hoffert's hypertexture gallery (SIGGRAPH 1989, shared/seeds/000_b84f13d83bc72326.txt,
// "PH" L174-234): the noisy sphere, the same with twice the frequency and half the amplitude, with
// a large amplitude, the fractal sphere, the dripping sphere and the eroded cube. Each tile (a
// plane) marches one of them with orthographic rays built from (s, t), front to back at a fixed
// increment (PH L296-306), and shades every sample of the soft region by the outward normal of
// the density gradient (PH L310-316) under the scene's lights. `variant` picks the density; `steps`
// (samples across the bounding sphere's diameter) is the cost knob, and it sets the octave clamp
// of the fractal ones (PH L308). The density functions come first (the tests evaluate them on
// their own, runtime/tests/gallery/hypertexture.rs); the surface shader is last.
#include <volume.sl>
#include <lighting.sl>

// The radius of the sphere that bounds every density here (the march's clipping volume, PH L292),
// centred at the origin of the tile's frame.
#define HT_BOUND 1.2

// The octave count of a fractal sum of base frequency `frequency` marched at increment `step`,
// under Perlin & Hoffert's frequency clamp (PH L308: octaves stop "when the period of the noise
// function is as small as the size of" the step): octave i, of frequency 2^i f, is kept while
// 2^i f step < 1. At least 1 (the base octave), at most 16. The doubling is exact, so both
// backends count alike.
float ht_octaves(float frequency, step)
{
    float n = 0;
    float w = frequency * step;
    while (w < 1 && n < 16) {
        n += 1;
        w *= 2;
    }
    return max(n, 1);
}

// The dripping sphere (PH L224: "noise ... to modulate only the y component of x"). The paper
// prints no formula; the choice here: below the centre, y is scaled by 1 - amplitude drip, with
// drip = max(-n - 0.25, 0) / 0.75 in [0, 1] for n = snoise3(frequency (x, 0, z)), a noise constant
// along y. Where the noise is well below 0 the column is stretched downward (a drip); elsewhere,
// and in the upper half, the sphere is plain. Continuous at y = 0 (the scaled y is 0 there).
float dripping_sphere(point p; float radius, softness, frequency, amplitude)
{
    float n = snoise3(point(frequency * p[0], 0, frequency * p[2]));
    float drip = max(-n - 0.25, 0) / 0.75;
    float k = p[1] < 0 ? 1 - amplitude * drip : 1;
    return soft_sphere(point(p[0], k * p[1], p[2]), point(0, 0, 0), radius, softness);
}

// The eroded cube (PH L234): the generalized intersection of a fractal sphere with a cube, here a
// soft box of half-size 0.5 turned to show three faces (rotations by atan(3/4) about y and
// atan(5/12) about x, exact rational cosines), so that the sphere's fractal surface eats its
// corners.
float eroded_cube(point p; float octaves)
{
    float x1 = 0.8 * p[0] - 0.6 * p[2];
    float z1 = 0.6 * p[0] + 0.8 * p[2];
    float y2 = (12.0 / 13.0) * p[1] - (5.0 / 13.0) * z1;
    float z2 = (5.0 / 13.0) * p[1] + (12.0 / 13.0) * z1;
    float cube = soft_box(point(x1, y2, z2), point(0, 0, 0), vector(0.5, 0.5, 0.5), 0.12);
    float sphere = fractal_sphere(p, point(0, 0, 0), 0.74, 0.08, 3, 1.0 / 3, octaves);
    return soft_intersection(sphere, cube);
}

// The density of gallery object `variant` at p (tile frame, bounded by HT_BOUND), with `octaves`
// for the fractal ones and `high_amplitude` for variant 2:
//   0 noisy sphere, frequency f = 4 and amplitude 1/f (PH L178);
//   1 high-frequency noisy sphere, 2f and half the amplitude (PH L188);
//   2 high-amplitude noisy sphere, f = 4 and amplitude `high_amplitude` (the gallery's 0.75 is
//     3/f): above 1, 1 + a noise < 0 where the noise is below -1/a and the point is mirrored
//     through the centre (PH L192; digest H10), and since the scale factor then crosses 0 the
//     density reaches out to any distance (the march's bound clips it);
//   3 fractal sphere, sum_i noise(2^i f x) / (2^i f) (PH L218);
//   4 dripping sphere (above);
//   5 eroded cube (above).
float ht_density(point p; float variant, octaves, high_amplitude)
{
    if (variant < 0.5)
        return noisy_sphere(p, point(0, 0, 0), 0.62, 0.16, 4, 0.25);
    if (variant < 1.5)
        return noisy_sphere(p, point(0, 0, 0), 0.62, 0.16, 8, 0.125);
    if (variant < 2.5)
        return noisy_sphere(p, point(0, 0, 0), 0.55, 0.16, 4, high_amplitude);
    if (variant < 3.5)
        return fractal_sphere(p, point(0, 0, 0), 0.62, 0.16, 4, 0.25, octaves);
    if (variant < 4.5)
        return dripping_sphere(p, 0.5, 0.16, 6, 0.6);
    return eroded_cube(p, octaves);
}

// The base frequency of the fractal sum of `variant` (for the octave clamp); 4 for the spheres.
float ht_frequency(float variant)
{
    return variant > 4.5 ? 3 : 4;
}

// The density of `variant` at p and at p - e x, p - e y, p - e z, the book's one-sided
// differences for the gradient normal (TM L8549): returned as (d, dxm, dym, dzm); evaluated in a
// loop so that the density's code appears once in the compiled shader (four inlined copies of
// six densities made lavapipe's pipeline compilation take seconds per object). When d = 0 the
// three others are not evaluated (returned 0): the sample is empty and needs no normal.
float4 ht_samples(point p; float variant, octaves, high_amplitude, e)
{
    float4 r = {0, 0, 0, 0};
    float k;
    for (k = 0; k < 4; k += 1) {
        vector off = vector(k == 1 ? e : 0, k == 2 ? e : 0, k == 3 ? e : 0);
        float dk = ht_density(p - off, variant, octaves, high_amplitude);
        r += {k == 0 ? dk : 0, k == 1 ? dk : 0, k == 2 ? dk : 0, k == 3 ? dk : 0};
        if (k == 0 && dk <= 0)
            break;
    }
    return r;
}

// The outward shading normal from ht_samples' densities (volume_density_normal, one-sided);
// `fallback` where the gradient vanishes (inside D = 1, outside D = 0).
normal ht_normal(float4 d; vector fallback)
{
    return volume_density_normal(d[0], d[1], d[2], d[3], fallback);
}

// ---- the gallery tile

// One tile: the ray through (s, t) along +z (x to the right, y up, as camera space when the tile
// faces the camera), clipped to the bounding sphere and sampled at the centres of steps of fixed
// length h = 2 HT_BOUND / steps (so the octave clamp is the same over the whole tile). Each
// sample's opacity is volume_opacity(kappa density h), composited front to back; samples with
// density are shaded with Lambert plus Phong on the gradient normal (facing the viewer where the
// gradient vanishes, in the D = 1 cores; reached only behind the soft region). The eroded cube is
// coloured by turbulence (PH L234), the others by `Cs`. Marching stops at opacity 0.999 (TM L8482).
surface hypertexture(float variant = 0; float steps = 64; float high_amplitude = 0.75;
                     float kappa = 40; float Ks = 0.35;
                     float size = 30; color background = color(0.06, 0.07, 0.1))
{
    point o = point(HT_BOUND * (2 * s - 1), HT_BOUND * (1 - 2 * t), -2 * HT_BOUND);
    vector dir = vector(0, 0, 1);
    vector V = -dir;
    float n = clamp(floor(steps), 1, 4096);
    float h = 2 * HT_BOUND / n;
    float octaves = ht_octaves(ht_frequency(variant), h);
    vector hit = volume_ray_sphere(o, dir, point(0, 0, 0), HT_BOUND);
    float t0 = max(hit[0], 0);
    float t1 = hit[2] > 0 ? hit[1] : t0;
    float e = 0.01;
    float4 acc = {0, 0, 0, 0};
    float i;
    for (i = 0; i < n; i += 1) {
        float tt = t0 + (i + 0.5) * h;
        if (tt > t1 || acc[3] >= 0.999)
            break;
        point p = o + tt * dir;
        float4 ds = ht_samples(p, variant, octaves, high_amplitude, e);
        float d = ds[0];
        if (d > 0) {
            normal Nv = ht_normal(ds, V);
            color base = Cs;
            if (variant > 4.5)
                base = mix(color(0.45, 0.3, 0.2), color(0.95, 0.85, 0.7),
                           clamp(1.6 * turbulence(point(4 * p), 4), 0, 1));
            color c = base * (0.08 + 0.9 * rm_diffuse(Nv)) + Ks * rm_phong(Nv, V, size);
            acc = volume_composite(acc, kappa * d, c, h);
        }
    }
    Ci = rgb(acc) + (1 - acc[3]) * background;
    Oi = 1;
}
