// Volumes and hypertexture: Perlin & Hoffert's soft objects, generalized booleans and density
// modulation, a front-to-back compositor with exponential per-step opacity, the shading normal
// from the density gradient, the Henyey-Greenstein phase function, Wyvill's cubic blend, and a
// ray-sphere interval for bounding a march. The reference page is docs/stdlib/volume.md.
//
// Sources: Perlin & Hoffert, "Hypertexture", SIGGRAPH 1989 (shared/seeds/000_b84f13d83bc72326.txt,
// "PH": soft sphere L69, booleans L77-80, noisy/fractal/fire spheres L178, L218, L248, fur L262-264,
// gradient normal L310-316, compositing L326-336); Perlin's chapter of Texturing & Modeling
// (shared/seeds/002_a44091d2843c02ac.txt, "TM": the raymarcher L8470-8556, sphere L8612-8632,
// explosion L8656-8680); Ebert's gas chapter (TM L5245-5263: exponential opacity, HG phase) and cloud
// chapter (TM L6780: Wyvill's cubic). The Henyey-Greenstein formula itself is not printed in the
// seeds (TM L5253 cites Blinn 1982); the standard normalized form is used.
//
// Numerical policy: every function here returns finite values for finite arguments (coordinates
// and radii up to 1e37 in magnitude; beyond that radii and distances are taken as 1e37), densities
// and opacities are in [0, 1] exactly, and no normal is NaN. Lengths are computed scaled by the
// largest component (volume_length), so squares never overflow or underflow; the soft profile is
// written without squares. Everything apart from density_bias_gain and hypertexture_fur (pow and
// log through pattern.sl's bias and gain), fractal_sphere (pow in fbm's weights) and
// hypertexture_alpha (log) is plain arithmetic, sqrt, floor and the noise's integer hashing (no
// exp, log, pow), so the GPU agrees with the interpreter bit for bit there; the measured
// tolerances of the others are in docs/stdlib/volume.md (runtime/tests/stdlib/volume.rs).

#ifndef PATINA_VOLUME_SL
#define PATINA_VOLUME_SL

#include <pattern.sl>
#include <fractal.sl>

// 1 / (4 pi), the normalization of a phase function over the sphere.
#define PATINA_VOLUME_INV_4PI 0.07957747154594767

// The largest magnitude of a radius or distance the soft shapes distinguish (larger ones are
// taken as this); keeps sums of two of them finite in f32.
#define PATINA_VOLUME_BIG 1e37

// The bound put on noise-domain coordinates before the noise-based density functions call the
// noise: above 2^53 every f64 (and above 2^23 every f32) is an integer, where the noise is 0, so
// the bound changes no value, and fbm's and turbulence's octave scaling (up to 2^29) stays finite.
#define PATINA_VOLUME_NOISE_BOUND 1e25

// The Euclidean length of v, computed as m |v / m| with m the largest |component|, so that no
// square overflows or underflows: accurate for every finite vector (m >= 1e38 returns m, a lower
// bound within a factor sqrt(3)). 0 for the zero vector.
float volume_length(vector v)
{
    float m = max(abs(v[0]), abs(v[1]), abs(v[2]));
    if (m <= 0)
        return 0;
    if (m >= 1e38)
        return m;
    vector u = v / m;
    return m * sqrt(u . u);
}

// v / |v|, scaled as volume_length so that tiny (denormal) and huge vectors normalize too; the
// zero vector for a zero v (components are clamped to +-1e37 first, so infinities do not make NaN).
vector volume_normalize(vector v)
{
    vector w = clamp(v, -PATINA_VOLUME_BIG, PATINA_VOLUME_BIG);
    float m = max(abs(w[0]), abs(w[1]), abs(w[2]));
    if (m <= 0)
        return vector(0, 0, 0);
    vector u = w / m;
    return u / sqrt(u . u);
}

// ---------------------------------------------------------------------------------------------
// Soft shapes (object density functions, PH L54-71)

// The soft profile of Perlin & Hoffert's sphere (PH L69; TM L8612-8632) at distance d from the
// core: 1 for |d| <= inner, 0 for |d| >= outer, and (outer^2 - d^2) / (outer^2 - inner^2) between
// (linear in d^2), evaluated as ((outer - d) / (outer - inner)) ((outer + d) / (outer + inner)),
// which has no squares (no overflow) and no cancellation near either edge. outer is clamped to
// [0, 1e37] and inner to [0, outer]; inner = outer is the hard step (1 up to and including the
// radius). The result is clamped to [0, 1] against rounding.
float soft_profile(float d, inner, outer)
{
    float r0 = clamp(outer, 0, PATINA_VOLUME_BIG);
    float r1 = clamp(inner, 0, r0);
    float x = min(abs(d), PATINA_VOLUME_BIG);
    if (x <= r1)
        return 1;
    if (x >= r0)
        return 0;
    return clamp(((r0 - x) / (r0 - r1)) * ((r0 + x) / (r0 + r1)), 0, 1);
}

// Perlin & Hoffert's soft sphere of centre c, radius and softness (PH L69): the soft profile with
// inner radius r - s/2 and outer radius r + s/2, that is 1 inside r - s/2, 0 outside r + s/2,
// 1/2 near |p - c| = r. Departure: the paper squares r - s/2 as printed, which makes the inner
// sphere grow again when s > 2r; here the inner radius is max(r - s/2, 0). Negative radius or
// softness counts as 0; softness 0 is the hard sphere (errata H10: no division by zero).
float soft_sphere(point p, c; float radius, softness)
{
    float r = clamp(radius, 0, PATINA_VOLUME_BIG);
    float s = clamp(softness, 0, PATINA_VOLUME_BIG);
    return soft_profile(volume_length(p - c), r - s / 2, r + s / 2);
}

// A soft box of centre c and half-sizes halfsize (per axis): the generalized intersection (the
// product, PH L77) of three soft slabs, each the soft profile of |p_i - c_i| with inner half-size
// h_i - s/2 and outer h_i + s/2. On a face it has the soft sphere's profile; near an edge or a
// corner the product rounds it (density 1/4 on an edge where both slabs are 1/2). The paper's
// eroded cube (PH L234) gives no formula for its cube; this is the choice. Negative half-sizes or
// softness count as 0.
float soft_box(point p, c; vector halfsize; float softness)
{
    float s = clamp(softness, 0, PATINA_VOLUME_BIG);
    vector h = clamp(halfsize, 0, PATINA_VOLUME_BIG);
    vector d = p - c;
    return soft_profile(d[0], h[0] - s / 2, h[0] + s / 2)
         * soft_profile(d[1], h[1] - s / 2, h[1] + s / 2)
         * soft_profile(d[2], h[2] - s / 2, h[2] + s / 2);
}

// A soft torus around the z axis through c (RenderMan's torus orientation; transform p for
// others): the soft profile of the distance from the core circle of radius `major` in the plane
// z = c_z, with tube radius `radius` and softness s (inner r - s/2, outer r + s/2, as the soft
// sphere). The inner (D = 1) surface is the torus of tube radius r - s/2 (the digest's furry-donut
// torus, PH L266). Negative sizes count as 0.
float soft_torus(point p, c; float major, radius, softness)
{
    vector d = p - c;
    float ring = volume_length(vector(d[0], d[1], 0)) - clamp(major, 0, PATINA_VOLUME_BIG);
    float r = clamp(radius, 0, PATINA_VOLUME_BIG);
    float s = clamp(softness, 0, PATINA_VOLUME_BIG);
    return soft_profile(volume_length(vector(ring, d[2], 0)), r - s / 2, r + s / 2);
}

// ---------------------------------------------------------------------------------------------
// Generalized booleans (PH L77-80): algebraic product and sum, not min and max, so that fillets
// stay continuous (PH L88). Arguments are clamped to [0, 1]; each result is written in a form that
// stays in [0, 1] under rounding.

// Intersection A and B: a b.
float soft_intersection(float a, b)
{
    return clamp(a, 0, 1) * clamp(b, 0, 1);
}

// Complement of A: 1 - a.
float soft_complement(float a)
{
    return 1 - clamp(a, 0, 1);
}

// Difference A - B = A and (not B): a - a b, written a (1 - b).
float soft_difference(float a, b)
{
    return clamp(a, 0, 1) * (1 - clamp(b, 0, 1));
}

// Union A or B = not (not A and not B): a + b - a b, written 1 - (1 - a)(1 - b) as the paper
// derives it (the printed a + b - a b can round above 1).
float soft_union(float a, b)
{
    return 1 - (1 - clamp(a, 0, 1)) * (1 - clamp(b, 0, 1));
}

// ---------------------------------------------------------------------------------------------
// Density modulation (PH L61-63, L92-106 and the examples L176-266)

// The soft sphere (c, radius, softness) evaluated at c + (p - c) k: scaling the point by k about
// the centre, the form every modulated sphere of the paper takes (sphere(x (1 + ...)), PH L178).
// A negative k mirrors the point through the centre (the high-amplitude noisy sphere, PH L192).
float _patina_scaled_sphere(vector x; float k, radius, softness)
{
    float r = clamp(radius, 0, PATINA_VOLUME_BIG);
    float s = clamp(softness, 0, PATINA_VOLUME_BIG);
    return soft_profile(volume_length(x * k), r - s / 2, r + s / 2);
}

// The noise domain point frequency (p - c), clamped to +-PATINA_VOLUME_NOISE_BOUND.
point _patina_noise_domain(vector x; float frequency)
{
    return point(clamp(frequency * x, -PATINA_VOLUME_NOISE_BOUND, PATINA_VOLUME_NOISE_BOUND));
}

// Perlin & Hoffert's noisy sphere (PH L178): sphere(x (1 + amplitude snoise3(frequency x))) with
// x = p - c. The paper's amplitude is 1/frequency; frequency sets the number of bumps, amplitude
// their height.
float noisy_sphere(point p, c; float radius, softness, frequency, amplitude)
{
    vector x = p - c;
    float n = snoise3(_patina_noise_domain(x, frequency));
    return _patina_scaled_sphere(x, 1 + amplitude * n, radius, softness);
}

// Perlin & Hoffert's fractal sphere (PH L218): sphere(x (1 + sum_i noise(2^i f x) / (2^i f))),
// written sphere(x (1 + amplitude fbm(frequency x, 1, 2, octaves))): fbm with H = 1 and lacunarity 2
// is sum_i snoise3(2^i f x) / 2^i, so amplitude = 1/frequency is the paper's sphere. octaves as
// fbm takes them (fractional, clamped to [0, 30]).
float fractal_sphere(point p, c; float radius, softness, frequency, amplitude, octaves)
{
    vector x = p - c;
    float n = fbm(_patina_noise_domain(x, frequency), 1, 2, octaves);
    return _patina_scaled_sphere(x, 1 + amplitude * n, radius, softness);
}

// Perlin & Hoffert's fire ball (PH L248): sphere(x (1 + amplitude turbulence(frequency x))),
// the paper's being frequency = amplitude = 1. turbulence >= 0, so the flames lick inward from
// the outer radius (scaling the point up shrinks the sphere).
float fireball(point p, c; float radius, softness, frequency, amplitude, octaves)
{
    vector x = p - c;
    float n = turbulence(_patina_noise_domain(x, frequency), octaves);
    return _patina_scaled_sphere(x, 1 + amplitude * n, radius, softness);
}

// Perlin's explosion (TM L8656-8680): shape times texture, with shape the soft sphere of inner
// radius 0 and outer radius `radius` (so the soft region is the whole ball) and texture
// clamp(0.5 + amplitude turbulence(frequency x), 0, 1) (TM L8662). Animate `radius`.
float explosion(point p, c; float radius, frequency, amplitude, octaves)
{
    vector x = p - c;
    float shape = soft_profile(volume_length(x), 0, radius);
    if (shape <= 0)
        return 0;
    float n = turbulence(_patina_noise_domain(x, frequency), octaves);
    return shape * clamp(0.5 + amplitude * n, 0, 1);
}

// The position-independent DMF of the fur (PH L264): gain(g, bias(b, density)), Perlin's
// gain_0.9(bias_0.3(s)) being density_bias_gain(s, 0.3, 0.9). bias and gain are pattern.sl's (x and
// the parameters clamped to [0, 1], total at the corners).
float density_bias_gain(float density, b, g)
{
    return gain(g, bias(b, density));
}

// Perlin & Hoffert's fur on a soft object (PH L262-264): gain(g, bias(b, s)) times the object's
// density, with s = noise3(frequency * base) the unsigned noise (in [0, 1]: the paper's noise is
// signed and bias/gain take [0, 1]; digest hazard H8) at the projection `base` of the point onto
// the object's inner surface (geometry-dependent, so the caller supplies it: for a soft sphere
// c + r1 normalize(p - c); see volume_project_sphere).
float hypertexture_fur(float density; point base; float frequency, b, g)
{
    float s = noise3(_patina_noise_domain(vector(base), frequency));
    return density_bias_gain(s, b, g) * clamp(density, 0, 1);
}

// The point of the sphere (c, radius) nearest p: c + radius (p - c) / |p - c|; c + (0, 0, radius)
// when p = c. The projection of the fur DMF for a soft sphere (pass its inner radius).
point volume_project_sphere(point p, c; float radius)
{
    vector u = volume_normalize(p - c);
    if (u . u <= 0)
        u = vector(0, 0, 1);
    return c + clamp(radius, 0, PATINA_VOLUME_BIG) * u;
}

// ---------------------------------------------------------------------------------------------
// Compositing (PH L326-336 front to back; opacity per step exponential in the optical depth,
// TM L5247 and TM L8497)

// The opacity of a step of optical depth `depth` (density times length): 1 - exp(-depth), the
// exact absorption of a homogeneous step (TM L5247). Accurate to a few ulp for every depth (no
// cancellation for small depths, where the printed 1 - exp(-x) loses all digits) and computed
// without exp, so the GPU agrees bit for bit: depth is halved k times until below 1/64 (k <= 12),
// expm1(-x) there is its Taylor series to x^8, and expm1(2x) = expm1(x) (2 + expm1(x)) undoes the
// halvings. depth <= 0 (and NaN) gives 0, depth >= 40 gives 1 exactly (exp(-40) < 2^-57); the result
// is in [0, 1] and never above 1.
float volume_opacity(float depth)
{
    float x = max(depth, 0);
    if (x >= 40)
        return 1;
    float k = 0;
    while (x > 0.015625) {
        x *= 0.5;
        k += 1;
    }
    float y = 1 - x / 8;
    y = 1 - (x / 7) * y;
    y = 1 - (x / 6) * y;
    y = 1 - (x / 5) * y;
    y = 1 - (x / 4) * y;
    y = 1 - (x / 3) * y;
    y = 1 - (x / 2) * y;
    y = -x * y;
    while (k > 0) {
        y = y * (2 + y);
        k -= 1;
    }
    return clamp(-y, 0, 1);
}

// One front-to-back compositing step (PH L326-336: t = alpha_k (1 - alpha), color += t color_k,
// alpha += t), with alpha_k = volume_opacity(density * step). `acc` is the state accumulated so
// far: premultiplied colour in its first three components, opacity in the fourth (start with
// {0, 0, 0, 0}); the updated state is returned: acc = volume_composite(acc, density, c, step),
// then Ci = rgb(acc), Oi = acc[3]. c is the step's colour (for an emitting and absorbing medium,
// the source term: exact for density and colour constant over the step). density and step are
// clamped to >= 0, the opacity to [0, 1]. The opacity never exceeds 1 and reaches 1 exactly for an
// opaque step (rounding: a + fl(1 - a) = 1 for every a in [0, 1]). N steps of depth x composite to
// the one step of depth N x, up to rounding. (A state in a float4 rather than two `output`
// parameters: written while uncalled library functions could not write `output` parameters,
// E0507, since fixed; one state in and one out also composes in expressions.)
float4 volume_composite(float4 acc; float density; color c; float step)
{
    float a = clamp(acc[3], 0, 1);
    float t = volume_opacity(max(density, 0) * max(step, 0)) * (1 - a);
    color C = rgb(acc);
    C += t * c;
    return {C, a + t};
}

// The hypertexture raymarcher's step-size correction (TM L8497, which settles the paper's
// misprinted alpha_k := 1 - (1 - density)^c * step-size, PH L332; digest errata E1):
// 1 - (1 - alpha)^(scale step), for a colour-map opacity alpha given per unit of scale (the book's
// scale is 100 for a unit cube). Computed as volume_opacity(-log(1 - alpha) scale step); alpha is
// clamped to [0, 1], scale and step to >= 0; alpha = 1 gives 1 when scale step > 0, 0 otherwise.
float hypertexture_alpha(float alpha, step, scale)
{
    float a = clamp(alpha, 0, 1);
    float n = max(scale, 0) * max(step, 0);
    if (n <= 0)
        return 0;
    if (a >= 1)
        return 1;
    return volume_opacity(-log(1 - a) * n);
}

// ---------------------------------------------------------------------------------------------
// Shading normal from the density gradient (PH L310-316; TM L8544-8554)

// The outward unit normal -g / |g| of a density with gradient g (density grows inward, so the
// normal points down the gradient, as the book's compute_normal, TM L8549; the paper's "normalized
// gradient" points inward). Where g is 0 (flat density: inside D = 1, outside D = 0, at
// extrema; digest hazard H6) it returns `fallback` normalized, and (0, 0, 1) if that is 0 too.
// Never NaN; scaled so that denormal gradients normalize too.
normal volume_gradient_normal(vector g; vector fallback)
{
    vector n = volume_normalize(-g);
    if (n . n > 0)
        return normal(n);
    vector f = volume_normalize(fallback);
    if (f . f > 0)
        return normal(f);
    return normal(0, 0, 1);
}

// The outward normal from central differences: the densities at p + h x, p - h x, p + h y,
// p - h y, p + h z, p - h z (any h > 0; the 1/2h factor cancels). volume_gradient_normal of their
// differences, with its fallback.
normal volume_density_normal(float dxp, dxm, dyp, dym, dzp, dzm; vector fallback)
{
    return volume_gradient_normal(vector(dxp - dxm, dyp - dym, dzp - dzm), fallback);
}

// The book's one-sided form (TM L8549): d the density at p and dxm, dym, dzm the densities at
// p - h x, p - h y, p - h z; the normal is (dxm - d, dym - d, dzm - d) normalized. Three extra
// evaluations instead of six, first-order accurate.
normal volume_density_normal(float d, dxm, dym, dzm; vector fallback)
{
    return volume_gradient_normal(vector(d - dxm, d - dym, d - dzm), fallback);
}

// ---------------------------------------------------------------------------------------------
// Phase functions and blends

// The Henyey-Greenstein phase function (1 - g^2) / (4 pi (1 + g^2 - 2 g cos_theta)^(3/2)),
// normalized over the sphere (its integral over all directions is 1), forward scattering for
// g > 0. cos_theta is the cosine of the scattering angle, dot(normalize(I), normalize(L)) for a view
// ray I and a direction L to the light. The base is written (1 - g)^2 + 2 g (1 - cos) for g >= 0
// and (1 + g)^2 - 2 g (1 + cos) for g < 0 (sums of non-negative terms: no cancellation at the
// peak), and ^(3/2) as b sqrt(b) (no pow). g is clamped to +-(1 - 2^-24) (the limit |g| -> 1 is a
// delta, which no finite function is; at the bound the peak is 4.5e13 and the function still
// normalized), cos_theta to [-1, 1].
float henyey_greenstein(float cos_theta, g)
{
    float gmax = 1 - 1.0 / 16777216;
    float gg = clamp(g, -gmax, gmax);
    float c = clamp(cos_theta, -1, 1);
    float b;
    if (gg >= 0)
        b = (1 - gg) * (1 - gg) + 2 * gg * (1 - c);
    else
        b = (1 + gg) * (1 + gg) - 2 * gg * (1 + c);
    float ratio = ((1 - gg) * (1 + gg)) / (b * sqrt(b));
    return ratio * PATINA_VOLUME_INV_4PI;
}

// A sum of two Henyey-Greenstein lobes, w HG(g1) + (1 - w) HG(g2) (Ebert's "sums of
// Henyey-Greenstein functions", TM L5253, after Blinn), w clamped to [0, 1]: still normalized.
float henyey_greenstein2(float cos_theta, g1, g2, w)
{
    float ww = clamp(w, 0, 1);
    return ww * henyey_greenstein(cos_theta, g1) + (1 - ww) * henyey_greenstein(cos_theta, g2);
}

// Wyvill's cubic blend (soft object field; TM L6780): F(r) = -4/9 a^3 + 17/9 a^2 - 22/9 a + 1 with
// a = r^2 / R^2, for |r| < R, and 0 for |r| >= R (the polynomial is positive again between R and
// 1.5 R, digest H14; it is forced to 0). 1 at r = 0, 1/2 at r = R/2, 0 at R; zero slope at both
// ends, so the field is C1 everywhere (its second derivative jumps at R). Evaluated in the factored form
// (1 - a)^2 (9 - 4a) / 9 (non-negative, no cancellation near R). R <= 0 gives 0.
float wyvill_cubic(float r, R)
{
    float x = abs(r);
    if (R <= 0 || x >= R)
        return 0;
    float q = x / R;
    float a = q * q;
    return (1 - a) * (1 - a) * ((9 - 4 * a) / 9);
}

// The Wyvill field of a point primitive: wyvill_cubic(|p - c|, R) (TM L6784, with q = c).
float wyvill_blend(point p, c; float R)
{
    return wyvill_cubic(volume_length(p - c), R);
}

// ---------------------------------------------------------------------------------------------
// Marching helpers (PH L290-306: clip the ray against a bound, then march at a fixed increment)

// The parameter interval [t0, t1] of the ray o + t d (any non-zero d; t in units of |d|) inside the
// sphere (c, radius), returned as the vector (t0, t1, hit): hit = 1 and t0 <= t1 if the line meets
// the sphere (t0 < 0 when o is inside, both when the sphere is behind), else (0, 0, 0). Computed
// from the distance of the centre to the line (no difference of squares), so it stays finite for
// coordinates up to 1e37; t0 and t1 are clamped to +-1e38.
vector volume_ray_sphere(point o; vector d; point c; float radius)
{
    float r = clamp(radius, 0, PATINA_VOLUME_BIG);
    float len = volume_length(d);
    vector u = volume_normalize(d);
    if (len <= 0 || u . u <= 0)
        return vector(0, 0, 0);
    vector oc = clamp(o - c, -PATINA_VOLUME_BIG, PATINA_VOLUME_BIG);
    float b = u . oc;
    float perp = volume_length(oc - b * u);
    if (perp > r)
        return vector(0, 0, 0);
    float h = sqrt(r - perp) * sqrt(r + perp);
    return vector(clamp((-b - h) / len, -1e38, 1e38), clamp((-b + h) / len, -1e38, 1e38), 1);
}

#endif
