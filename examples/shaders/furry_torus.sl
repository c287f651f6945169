// Perlin & Hoffert's furry donut and tribble (SIGGRAPH 1989, shared/seeds/000_b84f13d83bc72326.txt,
// "PH" L254-288): fur grown in the soft region of a soft torus, from the inner surface (D = 1)
// to the outer one (D = 0). Each point x of the soft region is displaced by a vector noise shaped
// by gain_0.8(1 - D) (curly fur that is straight at the root), dropped perpendicularly onto the
// inner surface (`project`, analytic for a torus), and the noise there, shaped by
// gain_0.9(bias_0.3(.)), times D is the density (stdlib volume.sl: hypertexture_fur). Ray-marched
// on a plane with orthographic rays and shaded with Phong on the gradient normal. The density
// functions come first (runtime/tests/gallery/hypertexture.rs evaluates them on their own); the
// surface shader is last.
#include <volume.sl>
#include <lighting.sl>

// The torus, in its own frame (core circle in the plane z = 0 around the z axis, as soft_torus):
// core radius, tube radius and softness. The inner (D = 1, root) tube radius is
// FUR_TUBE - FUR_SOFT / 2 = 0.17, the outer (D = 0, tip) one FUR_TUBE + FUR_SOFT / 2 = 0.35: the
// hairs are FUR_SOFT long.
#define FUR_MAJOR 0.58
#define FUR_TUBE 0.26
#define FUR_SOFT 0.18
// The radius of the sphere about the origin that bounds the fur (the march's clipping volume).
#define FUR_BOUND 1.0

// The point of the torus of core radius `major` (around the z axis, in the plane z = 0) and tube
// radius r1 nearest q: the perpendicular projection onto that surface (PH L258, "project" for the
// donut). On the axis (no nearest core point) the core point on +x is taken; on the core circle
// (no nearest surface point) the point outward from the axis.
point torus_project(point q; float major, r1)
{
    vector radial = volume_normalize(vector(q[0], q[1], 0));
    if (radial . radial <= 0)
        radial = vector(1, 0, 0);
    point ring = point(major * radial);
    vector out = volume_normalize(q - ring);
    if (out . out <= 0)
        out = radial;
    return ring + r1 * out;
}

// The vector noise of the tribble (PH L284): [noise(x - sigma), noise(x), noise(x + sigma)] with
// the signed snoise3 (a displacement in any direction) at frequency `frequency`, and
// sigma = (100, 100, 100): a whole number of lattice cells, far enough that the three components
// meet different pseudorandom knots.
vector fur_vnoise(point q; float frequency)
{
    point x = point(frequency * q);
    vector sigma = vector(100, 100, 100);
    return vector(snoise3(x - sigma), snoise3(x), snoise3(x + sigma));
}

// The curled point of the tribble (PH L272): x' = x + gain_0.8(1 - d) curliness noise(x), d being
// the torus density at x. At the roots (d = 1) gain_0.8(0) = 0 and x' = x exactly.
point fur_curl(point q; float d, curliness, curlfreq)
{
    return q + gain(0.8, 1 - d) * curliness * fur_vnoise(q, curlfreq);
}

// The tribble's density at q (torus frame): d = soft_torus(q); 0 where d = 0 (outside the outer
// tube, without evaluating the noise); else hypertexture_fur(d, project(x'), freq, 0.3, 0.9) =
// gain_0.9(bias_0.3(noise3(freq project(x')))) d (PH L264, L274-276; the noise is the unsigned
// noise3, digest H8). curliness 0 is the straight-haired furry donut.
float fur_density(point q; float freq, curliness, curlfreq)
{
    float d = soft_torus(q, point(0, 0, 0), FUR_MAJOR, FUR_TUBE, FUR_SOFT);
    if (d <= 0)
        return 0;
    point x = fur_curl(q, d, curliness, curlfreq);
    point base = torus_project(x, FUR_MAJOR, FUR_TUBE - FUR_SOFT / 2);
    return hypertexture_fur(d, base, freq, 0.3, 0.9);
}

// The fur with its skin: the generalized union (PH L80) with a thin soft torus just inside the
// roots, so that the donut has an opaque body under the hair.
float tribble_density(point q; float freq, curliness, curlfreq)
{
    float skin = soft_torus(q, point(0, 0, 0), FUR_MAJOR, FUR_TUBE - FUR_SOFT / 2 - 0.01, 0.02);
    return soft_union(fur_density(q, freq, curliness, curlfreq), skin);
}

// The torus frame of a point of the tile frame: turned about x by atan(4/3) (exact rational
// cosines), so that the camera sees the donut from above at a slant.
point fur_frame(point p)
{
    return point(p[0], 0.6 * p[1] - 0.8 * p[2], 0.8 * p[1] + 0.6 * p[2]);
}

// The tribble's density at the tile-frame point p and at p - e x, p - e y, p - e z (the book's
// one-sided differences for the gradient normal, TM L8549), as (d, dxm, dym, dzm); in a loop so
// that the density's code appears once in the compiled shader (lavapipe compiles a long shader
// slowly). When d = 0 the others are not evaluated (0): an empty sample needs no normal.
float4 tribble_samples(point p; float freq, curliness, curlfreq, e)
{
    float4 r = {0, 0, 0, 0};
    float k;
    for (k = 0; k < 4; k += 1) {
        vector off = vector(k == 1 ? e : 0, k == 2 ? e : 0, k == 3 ? e : 0);
        float dk = tribble_density(fur_frame(p - off), freq, curliness, curlfreq);
        r += {k == 0 ? dk : 0, k == 1 ? dk : 0, k == 2 ? dk : 0, k == 3 ? dk : 0};
        if (k == 0 && dk <= 0)
            break;
    }
    return r;
}

// ---- the gallery tile

// The ray through (s, t) along +z (x to the right, y up), clipped to the bounding sphere and
// sampled at the centres of steps of fixed length h = 2 FUR_BOUND / steps; each sample's opacity
// is volume_opacity(kappa density h), composited front to back, and samples with density are
// shaded with Lambert plus Phong on the outward normal of the density gradient (one-sided
// differences, TM L8549), the hair lighter towards the tips. Marching stops at opacity 0.999.
surface furry_torus(float steps = 96; float freq = 22; float curliness = 0.09; float curlfreq = 3;
                    float kappa = 40; float Ks = 0.3; float size = 12;
                    color background = color(0.06, 0.07, 0.1))
{
    point o = point(FUR_BOUND * (2 * s - 1), FUR_BOUND * (1 - 2 * t), -2 * FUR_BOUND);
    vector dir = vector(0, 0, 1);
    vector V = -dir;
    float n = clamp(floor(steps), 1, 4096);
    float h = 2 * FUR_BOUND / n;
    vector hit = volume_ray_sphere(o, dir, point(0, 0, 0), FUR_BOUND);
    float t0 = max(hit[0], 0);
    float t1 = hit[2] > 0 ? hit[1] : t0;
    float e = 0.006;
    float4 acc = {0, 0, 0, 0};
    float i;
    for (i = 0; i < n; i += 1) {
        float tt = t0 + (i + 0.5) * h;
        if (tt > t1 || acc[3] >= 0.999)
            break;
        point p = o + tt * dir;
        float4 ds = tribble_samples(p, freq, curliness, curlfreq, e);
        float d = ds[0];
        if (d > 0) {
            // The gradient in the tile frame: differences along the tile's axes.
            normal Nv = volume_density_normal(d, ds[1], ds[2], ds[3], V);
            point q = fur_frame(p);
            float tip = 1 - soft_torus(q, point(0, 0, 0), FUR_MAJOR, FUR_TUBE, FUR_SOFT);
            color base = Cs * (0.45 + 0.55 * tip);
            color c = base * (0.15 + 0.9 * rm_diffuse(Nv)) + Ks * rm_phong(Nv, V, size);
            acc = volume_composite(acc, kappa * d, c, h);
        }
    }
    Ci = rgb(acc) + (1 - acc[3]) * background;
    Oi = 1;
}
