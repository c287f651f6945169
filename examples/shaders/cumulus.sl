// Ebert's cumulus cloud (Texturing & Modeling ch. 9, "Volumetric Cloud Modeling with Implicit
// Functions"; seed-digest §4.3, scene S14): an implicit macrostructure of nine Wyvill spheres
// (stdlib volume.sl: wyvill_blend) and a turbulent microstructure (stdlib fractal.sl: turbulence),
// ray-marched in the fragment shader of its bounding sphere with single scattering of a distant sun
// (a sum of two Henyey-Greenstein lobes) attenuated by a short shadow march toward the sun, plus an
// ambient sky term (the high-albedo approximation), and the exponential opacity law.
//
// The density (cumulus_density) is Ebert's cumulus procedure without its animation (frame 0, no
// Peachey-noise path): turb = turbulence(frequency q), the point warped by
// (a turb, -a turb, a turb) with a = turbamount, mdens = sum of the spheres' Wyvill fields at the
// warped point, density = pow(maxdensity (blend mdens + (1 - blend) turb mdens), exponent), Ebert's
// parms[1..4] being maxdensity, exponent, blend and turbamount (0.3, 0.5, 0.4, 0.7 as he suggests).
// Every term carries mdens, so the density is exactly 0 wherever the warped point is outside every
// sphere's ball (Wyvill's cubic is forced to 0 at and beyond R), and pow's base is >= 0 (max(., 0))
// so pow(., 0.5) is never NaN. A point farther than R_i + sqrt(3) 2 a from every centre cannot warp
// into a ball (turbulence < 2), so the density returns 0 there without computing the turbulence.
//
// Coordinates: the cloud is defined in "cloud units", q = cloudscale times the bounding sphere's
// object space (the unit sphere), its spheres of radius 0.8 to 1.5.
#include <volume.sl>

// The nine spheres of the macrostructure: centre (cloud units) and radius.
#define CUMULUS_SPHERES 9

point cumulus_centre(float i)
{
    point c[CUMULUS_SPHERES] = {
        point(0, -0.2, 0), point(-1.4, -0.5, 0.1), point(1.4, -0.45, -0.1),
        point(-0.6, 0.8, 0), point(0.7, 0.7, -0.2), point(0, 1.6, 0.1),
        point(-2.4, -0.7, 0), point(2.4, -0.75, 0.2), point(1.3, 1.3, 0.3)
    };
    return c[int(i)];
}

float cumulus_radius(float i)
{
    float r[CUMULUS_SPHERES] = {1.3, 1.0, 1.05, 1.0, 1.05, 0.9, 0.7, 0.65, 0.7};
    return r[int(i)];
}

// The implicit macrostructure at q: the sum of the nine Wyvill fields (it may exceed 1 where the
// spheres overlap, as Ebert's does).
float cumulus_implicit(point q)
{
    float m = 0;
    float i;
    for (i = 0; i < CUMULUS_SPHERES; i += 1)
        m += wyvill_blend(q, cumulus_centre(i), cumulus_radius(i));
    return m;
}

// Ebert's cumulus density at q (cloud units), and the warped point it evaluated the
// macrostructure at (q itself where the early exit applies).
// exponent is a gamma on the density (0.5 in the scene): a negative one makes empty space
// infinitely dense, and a large one overflows what maxdensity scales.
// sweep: maxdensity in [0, 1e4]; exponent in [0, 4]; blend in [0, 1] (a mix weight)
float cumulus_density(point q; float maxdensity, exponent, blend, turbamount, frequency, octaves;
                      output point warped)
{
    warped = q;
    float reach = 1.7320508 * 2 * max(turbamount, 0);
    float near = 0;
    float i;
    for (i = 0; i < CUMULUS_SPHERES; i += 1) {
        if (volume_length(q - cumulus_centre(i)) < cumulus_radius(i) + reach)
            near = 1;
    }
    if (near == 0)
        return 0;
    float turb = turbulence(q * frequency, octaves);
    float a = turbamount * turb;
    warped = q + vector(a, -a, a);
    float mdens = cumulus_implicit(warped);
    float d = maxdensity * (blend * mdens + (1 - blend) * turb * mdens);
    return pow(max(d, 0), exponent);
}

// The surface of the bounding sphere (mesh "sphere", object space the unit sphere). The ray from
// the eye enters at P (t = 1 on E + t (P - E) in object space) and leaves the unit sphere at t1; on
// a back face t1 is P itself, so back faces add nothing. `steps` is the cost knob (the view march);
// shadowsteps samples the density over shadowlength (object units) toward the sun at each sample
// with density > 0. tosun: the direction to the sun (world space in the scene file).
// The cost knobs over the scene's values (its references' 256 and 40 steps cost more, alike):
// sweep: steps in [1, 64]; shadowsteps in [1, 10]; octaves in [0, 8]
surface cumulus(float steps = 32;
                float shadowsteps = 5;
                float shadowlength = 0.8;
                float maxdensity = 0.3;
                float exponent = 0.5;
                float blend = 0.4;
                float turbamount = 0.7;
                float frequency = 2;
                float octaves = 4;
                float cloudscale = 4;
                float tau = 4;
                float albedo = 1;
                float jitter = 1;
                vector tosun = vector(1, 1, -1);
                color suncolor = color(18, 17.2, 15.8);
                color skycolor = color(0.3, 0.36, 0.5))
{
    point O = transform("object", E);
    point Q = transform("object", P);
    vector D = Q - O;
    vector hit = volume_ray_sphere(O, D, point(0, 0, 0), 1);
    float t0 = 1;
    float t1 = max(hit[1], t0);
    float n = max(floor(steps), 1);
    float h = (t1 - t0) / n;
    float world = length(I) / max(length(D), 1e-30);  // world units per object unit
    float dl = h * length(I);
    vector S = normalize(vtransform("object", tosun));
    float ns = max(floor(shadowsteps), 1);
    float hs = shadowlength / ns;
    float cos_theta = normalize(I) . normalize(tosun);
    float phase = henyey_greenstein2(cos_theta, 0.6, -0.25, 0.7);
    float j = jitter > 0 ? random() : 0.5;
    float4 acc = {0, 0, 0, 0};
    point w;
    float k;
    for (k = 0; k < n; k += 1) {
        if (acc[3] >= 0.99)
            break;
        point q = O + (t0 + (k + j) * h) * D;
        float rho = cumulus_density(q * cloudscale, maxdensity, exponent, blend, turbamount, frequency,
                                    octaves, w);
        if (rho > 0) {
            float sum = 0;
            float m;
            for (m = 0; m < ns; m += 1) {
                point qs = q + ((m + 0.5) * hs) * S;
                sum += cumulus_density(qs * cloudscale, maxdensity, exponent, blend, turbamount,
                                       frequency, octaves, w);
            }
            float lit = 1 - volume_opacity(tau * sum * hs * world);
            color c = albedo * (suncolor * lit * phase + skycolor);
            acc = volume_composite(acc, tau * rho, c, dl);
        }
    }
    Ci = rgb(acc);
    Oi = acc[3];
}
