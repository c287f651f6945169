// Ebert's steam rising from a teacup (Texturing & Modeling, ch. 7 "Procedural Modeling of Gases",
// the steam slab, and ch. 8's moving steam; seed-digest §4.1, scene S12): a gas density ray-marched
// in the fragment shader of the cube that bounds it, with low-albedo single scattering (a
// Henyey-Greenstein phase toward a distant sun) and the exponential opacity law
// opacity = 1 - exp(-tau sum(rho dt)) (TM L5247), composited over the cup by the renderer's
// premultiplied "over" blend and the depth test (the cup is drawn first).
//
// Coordinates: the density is defined in the bounding cube's object space, q in [-1, 1]^3, the
// height fraction h = (q_y + 1) / 2 running from the tea (h = 0) to the top of the slab (h = 1).
//
// The density (steam_density), after Ebert's steam_slab1 and steam_moving, with these choices:
//   * turbulence is stdlib fractal.sl's (|snoise3| octaves, in [0, 2)), not Ebert's value-noise
//     turbulence, so Ebert's shaping constants are rescaled by `gain` (Ebert: "if other noise
//     implementations are used, then the gas shaping ... will be slightly different");
//   * basic_gas shaping pow(turb * gain, exponent) is computed directly (no pow table), its base
//     clamped to [0, 1], so the shaped value is in [0, 1];
//   * the sample point moves along Ebert's helical path (steam_moving: down = 3 frame DOWN + 4,
//     swirl RAD1 cos(theta), RAD2 sin(theta), theta = (frame mod 126) 2 pi / 126, a noise offset), so
//     the steam rises as `frame` advances;
//   * the falloff from the axis is Ebert's cosine ramp on the squared distance (1 up to a quarter of
//     the squared radius, 0 from the radius out), about the vertical axis with a radius that grows
//     with height (the plume spreads) instead of about a centre, and without his random offsets;
//   * the vertical falloff is Ebert's 1 - (exp((h - 0.05) 1.111111) - 1) / 1.718282 above h = 0.05,
//     with his misprint (offset for offset2) corrected and the factor clamped to >= 0, so it is 0
//     from h = 0.95 up (digest E19 and H14: as printed it turns negative there).
// So 0 <= density <= maxdensity everywhere, and density = 0 outside the plume (h <= 0, h >= 0.95, or
// at or beyond the axis radius).
#include <volume.sl>

// Ebert's DOWN_AMOUNT, SWIRL_FRAMES, RAD1 and RAD2 (Table 8.1).
#define STEAM_DOWN 0.0095
#define STEAM_SWIRL_FRAMES 126
#define STEAM_RAD1 0.12
#define STEAM_RAD2 0.08

// The plume's radius (in cube units) at height fraction h: radius0 at the tea, radius1 at the top.
float steam_radius(float h, radius0, radius1)
{
    return mix(radius0, radius1, clamp(h, 0, 1));
}

// The steam density at q (cube object space): maxdensity * shaped turbulence * axis falloff *
// vertical falloff, in [0, maxdensity]. frequency scales q into the turbulence space.
float steam_density(point q; float frame, maxdensity, exponent, gain, frequency, octaves,
                    radius0, radius1)
{
    float h = (q[1] + 1) * 0.5;
    if (h <= 0 || h >= 0.95)
        return 0;
    float radius = steam_radius(h, radius0, radius1);
    float dd = (q[0] * q[0] + q[2] * q[2]) / (radius * radius);
    if (dd >= 1)
        return 0;
    // Ebert's moving steam: the sample point follows a helical path down through the turbulence
    // space, so the gas rises.
    float theta = mod(frame, STEAM_SWIRL_FRAMES) * (2 * PI / STEAM_SWIRL_FRAMES);
    float down = frame * STEAM_DOWN * 3 + 4;
    point pt = q * frequency;
    float n = noise(pt);
    point moved = pt + vector(STEAM_RAD1 * cos(theta) + 2 + n, -down + n, STEAM_RAD2 * sin(theta) - 2 + n);
    float turb = turbulence(moved, octaves);
    float density = pow(clamp(turb * gain, 0, 1), exponent);
    // Falloff from the axis: Ebert's cosine ramp from a quarter of the squared radius out.
    if (dd >= 0.25)
        density *= (cos(PI * clamp((dd - 0.25) * (4.0 / 3.0), 0, 1)) + 1) * 0.5;
    // Vertical falloff (E19 fixed, clamped at 0: H14).
    if (h > 0.05)
        density *= max(1 - (exp((h - 0.05) * 1.111111) - 1) / 1.718282, 0);
    return clamp(maxdensity * density, 0, max(maxdensity, 0));
}

// The march of the ray O + t D (cube object space) from t0 to t1, in `steps` equal steps with the
// sample of step k at t0 + (k + jitter) (t1 - t0) / steps: each step's opacity is
// volume_opacity(tau density dl), dl = (t1 - t0) len / steps the step's length in world units (len
// = |D| in world units), and its colour the low-albedo single scattering of the sun (suncolor times
// the Henyey-Greenstein phase at cos_theta, the cosine between the view ray and the direction to the
// sun) plus an ambient term, times albedo. Front to back (volume_composite), stopping once the
// opacity reaches `threshold` (Ebert stops at transparency < 0.01). Returns the premultiplied
// colour and opacity; `depth` is the optical depth tau sum(density dl) of the samples taken.
// The cost knob: past 65535 steps the interpreter's loop budget stops the march (docs/limits.md).
// sweep: steps in [1, 1024]; t1 in [0, 1e4]; len in [0, 1e4] (a ray inside the unit cube)
float4 steam_march(point O; vector D; float t0, t1, len, steps, jitter, threshold, tau;
                   color suncolor, ambient; float cos_theta, g, albedo;
                   float frame, maxdensity, exponent, gain, frequency, octaves, radius0, radius1;
                   output float depth)
{
    float n = max(floor(steps), 1);
    float h = max(t1 - t0, 0) / n;
    float dl = h * len;
    color c = albedo * (suncolor * henyey_greenstein(cos_theta, g) + ambient);
    float4 acc = {0, 0, 0, 0};
    depth = 0;
    float k;
    for (k = 0; k < n; k += 1) {
        if (acc[3] >= threshold)
            break;
        point q = O + (t0 + (k + jitter) * h) * D;
        float rho = steam_density(q, frame, maxdensity, exponent, gain, frequency, octaves, radius0, radius1);
        depth += tau * rho * dl;
        acc = volume_composite(acc, tau * rho, c, dl);
    }
    return acc;
}

// The surface of the bounding cube (mesh "cube", side 2: object space [-1, 1]^3). The ray from the
// eye enters at P (t = 1 on E + t (P - E) in object space) and leaves at the cube's far side; on a
// back face the exit is P itself, so back faces add nothing. `steps` is the cost knob. tosun is the
// direction to the sun (world space in the scene file), suncolor its radiance.
// The cost knob: past 65535 steps the interpreter's loop budget stops the march (docs/limits.md).
// sweep: steps in [1, 1024]; g in [-0.99, 0.99] (Henyey-Greenstein's asymmetry); albedo in [0, 1]
surface steam(float steps = 24;
              float frame = 0;
              float maxdensity = 0.57;
              float exponent = 6;
              float gain = 1.8;
              float frequency = 1.6;
              float octaves = 5;
              float radius0 = 0.55;
              float radius1 = 1.0;
              float tau = 6;
              float g = 0.35;
              float albedo = 1;
              float jitter = 1;
              vector tosun = vector(1, 1, 1);
              color suncolor = color(9, 8.6, 8);
              color ambient = color(0.25, 0.27, 0.32))
{
    point O = transform("object", E);
    point Q = transform("object", P);
    vector D = Q - O;
    // The exit parameter: the nearest far slab of the three axes (D has no zero component in
    // practice; a zero one is skipped).
    float t1 = 1e30;
    float i;
    for (i = 0; i < 3; i += 1) {
        float d = D[i];
        if (d > 0)
            t1 = min(t1, (1 - O[i]) / d);
        else if (d < 0)
            t1 = min(t1, (-1 - O[i]) / d);
    }
    t1 = max(t1, 1);
    float cos_theta = normalize(I) . normalize(tosun);
    float j = jitter > 0 ? random() : 0.5;
    float depth;
    float4 acc = steam_march(O, D, 1, t1, length(I), steps, j, 0.99, tau, suncolor, ambient, cos_theta,
                             g, albedo, frame, maxdensity, exponent, gain, frequency, octaves, radius0,
                             radius1, depth);
    Ci = rgb(acc);
    Oi = acc[3];
}
