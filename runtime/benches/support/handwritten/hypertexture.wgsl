// Perlin & Hoffert's noisy sphere as examples/shaders/hypertexture.sl marches it (variant 0,
// 64 steps): orthographic rays along +z through the plane's (s, t), clipped to the bounding
// sphere, sampled at the centres of fixed steps front to back until nearly opaque; each sample
// with density is shaded by the density gradient's outward normal (one-sided differences) under a
// distant light and composited with opacity 1 - exp(-kappa density step). The Rust side defines
// HT_LIGHT (the direction to the light, in camera space).

const HT_BOUND = 1.2;
const HT_STEPS = 64;
const HT_KAPPA = 40.0;
const HT_KS = 0.35;
const HT_SIZE = 30.0;
const HT_BACKGROUND = vec3f(0.06, 0.07, 0.1);
// The soft sphere's radius 0.62 less and plus half its softness 0.16.
const HT_INNER = 0.54;
const HT_OUTER = 0.70;

// The noisy sphere: the soft sphere, linear in the squared distance across its soft shell, at
// p scaled by 1 + snoise(4 p) / 4.
fn noisy_sphere(p: vec3f) -> f32 {
    let x = p * (1.0 + 0.25 * snoise(4.0 * p));
    return clamp((HT_OUTER * HT_OUTER - dot(x, x)) / (HT_OUTER * HT_OUTER - HT_INNER * HT_INNER), 0.0, 1.0);
}

@fragment
fn hypertexture(in: Varyings) -> @location(0) vec4f {
    let st = plane_st(in.uv);
    let o = vec3f(HT_BOUND * (2.0 * st.x - 1.0), HT_BOUND * (1.0 - 2.0 * st.y), -2.0 * HT_BOUND);
    let dir = vec3f(0.0, 0.0, 1.0);
    let v = -dir;
    let dt = 2.0 * HT_BOUND / f32(HT_STEPS);
    let e = 0.01;
    // The ray's interval inside the bounding sphere.
    let b = dot(o, dir);
    let perp2 = dot(o, o) - b * b;
    var t0 = 0.0;
    var t1 = 0.0;
    if (perp2 <= HT_BOUND * HT_BOUND) {
        let h = sqrt(HT_BOUND * HT_BOUND - perp2);
        t0 = max(-b - h, 0.0);
        t1 = -b + h;
    }
    var acc = vec4f(0.0);
    for (var i = 0; i < HT_STEPS; i++) {
        let t = t0 + (f32(i) + 0.5) * dt;
        if (t > t1 || acc.a >= 0.999) {
            break;
        }
        let p = o + t * dir;
        let d = noisy_sphere(p);
        if (d > 0.0) {
            let g = vec3f(noisy_sphere(p - vec3f(e, 0.0, 0.0)), noisy_sphere(p - vec3f(0.0, e, 0.0)),
                          noisy_sphere(p - vec3f(0.0, 0.0, e))) - d;
            let n = select(v, normalize(g), dot(g, g) > 0.0);
            let ln = dot(HT_LIGHT, n);
            let specular = select(0.0, pow(max(dot(reflect(-v, n), HT_LIGHT), 0.0), HT_SIZE), ln >= 0.0);
            let c = vec3f(0.08 + 0.9 * max(ln, 0.0) + HT_KS * specular);
            let alpha = (1.0 - exp(-HT_KAPPA * d * dt)) * (1.0 - acc.a);
            acc += vec4f(alpha * c, alpha);
        }
    }
    return vec4f(acc.rgb + (1.0 - acc.a) * HT_BACKGROUND, 1.0);
}
