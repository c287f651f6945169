// Kajiya & Kay's texel fur ("Rendering Fur with Three Dimensional Textures", SIGGRAPH 1989;
// shared/seeds/003_40eb5f8fea62bec3.txt, seed-digest §2 and §12 S7) on the built-in torus (major
// radius 1, tube radius 0.25 around the object's z axis). The mesh is the outer boundary of a
// shell of hair over an opaque core of tube radius 0.25 - shell; the shader marches the view ray
// through the shell in object space.
//
// * The texel: hair roots on a jittered grid of nu x nv cells over the torus's two angles, hashed
//   with the cell index modulo (nu, nv), so the pattern wraps seamlessly around both circles
//   (Kajiya & Kay's torus topology; a jittered grid stands in for their Poisson disk). Two layers:
//   a dense short undercoat and a sparse long overcoat. Each hair is an anti-aliased cylinder
//   (density taper - r^2 / radius^2, taper = 1 - h / length, so it thins to nothing at the tip),
//   combed around the torus by comb * h^2 cells at height h in [0, 1]; its tangent is the height
//   axis bent by the comb.
// * The march: the interval [0, t_far] of the ray inside the shell (to the core, or to where the
//   ray leaves the outer surface), split into `steps` equal segments sampled at their centres;
//   each segment composites Kajiya-Kay lighting with opacity 1 - exp(-tau density length)
//   (volume_composite), so a uniform density gives the transmittance exp(-tau density t_far) for
//   any step count. Where the ray reaches the core, the skin (Lambert) is composited behind.
// * Self-shadowing: each sample's light from each non-ambient light is attenuated by the hair
//   between it and the light (fur_shadow, `shadow_steps` samples; 0 turns shadows off). Lights are
//   taken as distant: L is the light's direction at P, used for every sample along the ray.
// * Cost: steps * (1 + shadow_steps) density evaluations per pixel, each 8 cell hashes x 3.

#include <lighting.sl>
#include <cellular.sl>
#include <volume.sl>

#define FUR_MAJOR 1.0
#define FUR_OUTER 0.25

// (angle around the z axis, angle around the tube, distance to the core circle) of p.
// sweep: p in [-1e6, 1e6] (object-space points of the torus: past 1e19 their squares overflow f32)
vector fur_coords(point p)
{
    float q = sqrt(p[0] * p[0] + p[1] * p[1]);
    float dx = q - FUR_MAJOR, dz = p[2];
    return vector(atan(p[1], p[0]), atan(dz, dx), sqrt(dx * dx + dz * dz));
}

// The unit vector from the core circle towards p (the height axis of the hair at p).
// sweep: p in [-1e6, 1e6] (object-space points of the torus: past 1e19 their squares overflow f32)
vector fur_radial(point p)
{
    float q = max(sqrt(p[0] * p[0] + p[1] * p[1]), 1e-6);
    float dx = q - FUR_MAJOR, dz = p[2];
    float rho = max(sqrt(dx * dx + dz * dz), 1e-6);
    return vector(dx / rho * p[0] / q, dx / rho * p[1] / q, dz / rho);
}

// The density of one layer of hairs at texel coordinates (x, y) (in cells, already shifted back by
// the comb) and height h in [0, 1]: the sum over the 2 x 2 cells whose centres surround (x, y) of
// the hairs rooted in them (a root lies within jitter of its cell centre, jitter + radius <= 1, so
// no other cell's hair reaches (x, y) and the density is continuous across cell boundaries).
float fur_layer(float x, y, h, nu, nv, jitter, radius, minlen, maxlen; int seed)
{
    float i0 = floor(x - 0.5), j0 = floor(y - 0.5);
    float density = 0;
    for (float a = 0; a < 2; a += 1) {
        for (float b = 0; b < 2; b += 1) {
            float ci = i0 + a, cj = j0 + b;
            // The cell index modulo the grid: the texel tiles the torus.
            float wi = ci - nu * floor(ci / nu) + 0.5, wj = cj - nv * floor(cj / nv) + 0.5;
            float rx = ci + 0.5 + jitter * (2 * cellnoise2(wi, wj, seed) - 1);
            float ry = cj + 0.5 + jitter * (2 * cellnoise2(wi, wj, seed + 1) - 1);
            float len = mix(minlen, maxlen, cellnoise2(wi, wj, seed + 2));
            float taper = max(0, 1 - h / len);
            float dx = x - rx, dy = y - ry;
            float r2 = (dx * dx + dy * dy) / (radius * radius);
            // taper - r^2 / radius^2: the cross-section shrinks to nothing at the tip.
            density += max(0, taper - r2);
        }
    }
    return min(density, 1);
}

// Hair density at object-space point p (0 outside the shell); slab > 0 replaces the hairs by
// that uniform density (for tests).
float fur_density(point p; float shell, nu, nv, comb, slab)
{
    vector c = fur_coords(p);
    float h = (c[2] - (FUR_OUTER - shell)) / shell;
    if (h < 0 || h > 1)
        return 0;
    if (slab > 0)
        return slab;
    float x = c[0] / (2 * PI) * nu - comb * h * h, y = c[1] / (2 * PI) * nv;
    float over = fur_layer(x, y, h, nu, nv, 0.3, 0.32, 0.75, 1.0, 0);
    float under = fur_layer(2 * x, 2 * y, h, 2 * nu, 2 * nv, 0.3, 0.4, 0.3, 0.55, 3);
    return min(over + under, 1);
}

// The exit of the ray o + t d (d a unit vector, o in the shell or just outside it) from the
// shell, as (t, 1 if the ray reached the core there else 0, 0). rho - ri is the exact distance to
// the core (a sphere-tracing bound: no step passes through it). Towards the outer surface,
// 0.25 - rho bounds the distance from inside; once the ray heads out (d rho / dt = radial . d > 0)
// Newton steps on rho(t) = 0.25 (at most 0.1 long) find the exit, overshooting and coming back
// from outside. Heading in with 0.25 - rho near 0 (at the entry), the step is at least 0.002.
vector fur_exit(point o; vector d; float ri)
{
    float t = 0, core = 0;
    for (float k = 0; k < 48; k += 1) {
        point q = o + t * d;
        float rho = fur_coords(q)[2];
        float to_core = rho - ri, to_out = FUR_OUTER - rho;
        float outward = fur_radial(q) . d;
        if (to_core < 1e-6) {
            core = 1;
            break;
        }
        if (outward > 0 && abs(to_out) < 1e-6)
            break;
        float step;
        if (to_out >= 0) {
            if (outward > 0)
                step = max(to_out, min(to_out / outward, 0.1));
            else
                step = max(to_out, 0.002);
        } else {
            step = outward > 0.05 ? to_out / outward : to_out; // back to the exit
        }
        t = clamp(t + min(step, to_core), 0, 2);
    }
    return vector(t, core, 0);
}

// The transmittance towards the light (unit direction l) from x, at distance rho from the core
// circle where the height axis is `radial`: exp(-tau * sum density * ds) over shadow_steps samples
// at the centres of equal segments up to where the ray leaves the shell, the shell taken as
// locally flat: (0.25 - rho) / max(radial . l, 0.25), at most 0.3. 0 when the ray heads into the
// core (radial . l <= 0); 1 when shadow_steps is 0 (shadows off).
// The cost knob: past 65535 steps the interpreter's loop budget stops the march (docs/limits.md).
// sweep: shadow_steps in [1, 256]
float fur_shadow(point x; vector l, radial; float rho, shell, nu, nv, comb, slab, tau, shadow_steps)
{
    if (shadow_steps <= 0)
        return 1;
    float up = radial . l;
    if (up <= 0)
        return 0;
    float reach = min((FUR_OUTER - rho) / max(up, 0.25), 0.3);
    float ds = reach / shadow_steps, depth = 0;
    for (float j = 0; j < shadow_steps; j += 1)
        depth += fur_density(x + (j + 0.5) * ds * l, shell, nu, nv, comb, slab);
    return 1 - volume_opacity(tau * depth * ds);
}

// The cost knobs: past 65535 steps the interpreter's loop budget stops the march (docs/limits.md).
// sweep: steps in [1, 256]; shadow_steps in [1, 64]; tau in [0, 1e4] (an extinction coefficient)
// sweep: shell in [0, 0.25] (the fur's depth, at most the tube's radius)
surface kajiya_kay_fur(float steps = 24; float shadow_steps = 4;
                       float kd = 0.7; float ks = 0.5; float p = 24; float mirror = 0;
                       float tau = 120; float shell = 0.09; float nu = 180; float nv = 28;
                       float comb = 0.6; float slab = 0;
                       color skin = color(0.25, 0.16, 0.12))
{
    point o = transform("object", P);
    // The view direction, total: a denormal I is normalized without underflow; an eye at the
    // shading point itself (I = 0) has no direction and looks straight in, and on the core circle,
    // where "in" has no direction either (never a shading point), along -z.
    vector d = lighting_normalize(vtransform("object", I));
    if (d . d == 0)
        d = lighting_normalize(-fur_radial(o));
    if (d . d == 0)
        d = vector(0, 0, -1);
    float ri = FUR_OUTER - shell;
    // The ray's interval in the shell, [-t_back, t_far]: P lies on the mesh, on or just inside
    // the analytic outer surface, so the ray's entry is searched backwards from P and its exit
    // (or the core) forwards. Both are continuous as a ray turns to grazing, where a forward
    // search from P alone would jump between a sliver and nothing with the sign of radial . d.
    float t_back = fur_exit(o, -d, ri)[0];
    vector fwd = fur_exit(o, d, ri);
    float t_far = fwd[0], core = fwd[1];
    o -= t_back * d;
    t_far += t_back;
    float seg = t_far / max(steps, 1);
    vector e = -d;
    float4 acc = {0, 0, 0, 0};
    for (float i = 0; i < steps; i += 1) {
        point x = o + (i + 0.5) * seg * d;
        float density = fur_density(x, shell, nu, nv, comb, slab);
        if (density > 0) {
            vector c = fur_coords(x);
            float h = (c[2] - ri) / shell;
            // The hair's tangent: the height axis bent along u by the comb, d/dh (comb h^2) cells.
            vector radial = fur_radial(x);
            vector around = normalize(vector(-x[1], x[0], 0));
            float cell_u = 2 * PI * (FUR_MAJOR + c[2] * cos(c[1])) / nu;
            vector T = radial * shell + around * (2 * comb * h * cell_u);
            color lit = 0;
            illuminance(P) {
                vector l = normalize(vtransform("object", L));
                float shadow =
                    fur_shadow(x, l, radial, c[2], shell, nu, nv, comb, slab, tau, shadow_steps);
                float spec = mirror > 0 ? kajiya_kay_specular_mirror(T, l, e, p)
                                        : kajiya_kay_specular(T, l, e, p);
                lit += Cl * shadow * (kd * kajiya_kay_diffuse(T, l) + ks * spec);
            }
            // Darker towards the roots.
            color hair = Cs * (0.45 + 0.55 * h);
            acc = volume_composite(acc, tau * density, hair * (lit + 0.6 * ambient()), seg);
        }
    }
    color C = color(acc[0], acc[1], acc[2]);
    float alpha = acc[3];
    if (core > 0) {
        // The skin behind the fur: Lambert on the core's normal, shadowed by the hair above it.
        point xs = o + t_far * d;
        vector ns = fur_radial(xs);
        color lambert = 0;
        illuminance(P) {
            vector l = normalize(vtransform("object", L));
            lambert += Cl * max(0, ns . l)
                     * fur_shadow(xs, l, ns, ri, shell, nu, nv, comb, slab, tau, shadow_steps);
        }
        C += (1 - alpha) * skin * (lambert * 0.5 + ambient());
        alpha = 1;
    }
    Oi = alpha;
    Ci = C;
}
