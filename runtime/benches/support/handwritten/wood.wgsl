// Hart's wood with APST's analytic filter (compiler/stdlib/solid.sl's hart_wood_footprint, as
// examples/shaders/hart_solid.sl's solid_wood calls it with aa = 1): f = s^2 + t^2 + noise3(4s, 4t, r),
// the noise averaged over probes along the pixel footprint's major axis and faded as the
// footprint outgrows it, and the modulo-one ramp from earlywood to latewood box-filtered over
// the spread of f across the pixel. The Rust side defines WOOD_SCALE and WOOD_LIGHT.

const WOOD_EARLY = vec3f(0.86, 0.66, 0.42);
const WOOD_LATE = vec3f(0.50, 0.30, 0.14);
// The noise term's map T = diag(4, 4, 1).
const WOOD_T = vec3f(4.0, 4.0, 1.0);
const WOOD_MAX_PROBES = 8.0;

fn grad_vector(hash: i32) -> vec3f {
    let h = hash & 15;
    let u = select(vec3f(0.0, 1.0, 0.0), vec3f(1.0, 0.0, 0.0), h < 8);
    let v = select(select(vec3f(0.0, 0.0, 1.0), vec3f(1.0, 0.0, 0.0), h == 12 || h == 14), vec3f(0.0, 1.0, 0.0), h < 4);
    return select(-u, u, (h & 1) == 0) + select(-v, v, (h & 2) == 0);
}

// The analytic gradient of improved_noise: the corners' gradients interpolated, plus the fade's
// derivative times the interpolated differences of the corners' dot products.
fn improved_noise_gradient(p: vec3f) -> vec3f {
    let cell = floor(p);
    let f = p - cell;
    let i = vec3i(cell) & vec3i(255);
    let u = fade(f);
    let du = 30.0 * f * f * (f * (f - 2.0) + 1.0);
    let a = perm(i.x) + i.y;
    let aa = perm(a) + i.z;
    let ab = perm(a + 1) + i.z;
    let b = perm(i.x + 1) + i.y;
    let ba = perm(b) + i.z;
    let bb = perm(b + 1) + i.z;
    let g000 = grad_vector(perm(aa));
    let g100 = grad_vector(perm(ba));
    let g010 = grad_vector(perm(ab));
    let g110 = grad_vector(perm(bb));
    let g001 = grad_vector(perm(aa + 1));
    let g101 = grad_vector(perm(ba + 1));
    let g011 = grad_vector(perm(ab + 1));
    let g111 = grad_vector(perm(bb + 1));
    let n000 = dot(g000, f);
    let n100 = dot(g100, f - vec3f(1.0, 0.0, 0.0));
    let n010 = dot(g010, f - vec3f(0.0, 1.0, 0.0));
    let n110 = dot(g110, f - vec3f(1.0, 1.0, 0.0));
    let n001 = dot(g001, f - vec3f(0.0, 0.0, 1.0));
    let n101 = dot(g101, f - vec3f(1.0, 0.0, 1.0));
    let n011 = dot(g011, f - vec3f(0.0, 1.0, 1.0));
    let n111 = dot(g111, f - vec3f(1.0, 1.0, 1.0));
    let g = mix(mix(mix(g000, g100, u.x), mix(g010, g110, u.x), u.y),
                mix(mix(g001, g101, u.x), mix(g011, g111, u.x), u.y), u.z);
    return g + du * vec3f(
        mix(mix(n100 - n000, n110 - n010, u.y), mix(n101 - n001, n111 - n011, u.y), u.z),
        mix(mix(n010 - n000, n110 - n100, u.x), mix(n011 - n001, n111 - n101, u.x), u.z),
        mix(mix(n001 - n000, n101 - n100, u.x), mix(n011 - n010, n111 - n110, u.x), u.y));
}

fn wood_ramp(x: f32) -> vec3f {
    return mix(WOOD_EARLY, WOOD_LATE, fract(x));
}

// The ramp's integral over [0, y], y in [0, 1].
fn wood_ramp_integral(y: f32) -> vec3f {
    return y * WOOD_EARLY + (0.5 * y * y) * (WOOD_LATE - WOOD_EARLY);
}

// The mean of the repeating ramp over [f - width / 2, f + width / 2]: the point value for a
// negligible width, the two linear pieces' midpoints when one ring boundary falls inside, and
// whole periods plus the ends' integrals beyond.
fn wood_colormap(f: f32, width: f32) -> vec3f {
    let h = 0.5 * width;
    let u = fract(f);
    let a = u - h;
    let b = u + h;
    if (h < 5e-7) {
        return wood_ramp(u);
    }
    if (h < 0.5) {
        let kb = floor(b);
        if (floor(a) == kb) {
            return wood_ramp(u);
        }
        return ((kb - a) * wood_ramp(0.5 * (a + kb)) + (b - kb) * wood_ramp(0.5 * (kb + b))) / (b - a);
    }
    let periods = floor(b) - floor(a);
    let rest = wood_ramp_integral(fract(b)) - wood_ramp_integral(fract(a));
    return (periods * 0.5 * (WOOD_EARLY + WOOD_LATE) + rest) / (b - a);
}

// Wood at p, filtered over the pixel footprint spanned by dpx and dpy.
fn hart_wood(p: vec3f, dpx: vec3f, dpy: vec3f) -> vec3f {
    let ts = p * WOOD_T;
    let x = dpx * WOOD_T;
    let y = dpy * WOOD_T;
    let xx = dot(x, x);
    let yy = dot(y, y);
    let major = select(y, x, xx >= yy);
    let lmajor = sqrt(max(xx, yy));
    // A probe per half a noise feature along the major axis, each faded by the footprint it
    // covers: the axis cut into pieces of length 1 / n from its start (n fractional, the last
    // piece shorter), a probe at each piece's middle weighing its length.
    let n = clamp(2.0 * lmajor + 0.5, 1.0, WOOD_MAX_PROBES);
    let piece = lmajor / n;
    let weight = 1.0 - smoothstep(0.4, 1.6, sqrt(0.5 * (min(xx, yy) + piece * piece)));
    var sum = 0.0;
    if (weight > 0.0) {
        for (var j = 0.0; j < ceil(n); j += 1.0) {
            let a = j / n - 0.5;
            let b = min((j + 1.0) / n - 0.5, 0.5);
            sum += (b - a) * snoise(ts + (0.5 * (a + b)) * major);
        }
    }
    let f = dot(p.xy, p.xy) + 0.5 + 0.5 * weight * sum;
    // f's gradient, its noise term faded by the whole footprint, gives f's spread over the pixel.
    let gradient_weight = 1.0 - smoothstep(0.4, 1.6, sqrt(0.5 * (xx + yy)));
    let gradient = vec3f(2.0 * p.xy, 0.0) + (gradient_weight * 0.5 * SNOISE_SCALE) * WOOD_T * improved_noise_gradient(ts);
    return wood_colormap(f, length(vec2f(dot(gradient, dpx), dot(gradient, dpy))));
}

@fragment
fn wood(in: Surface) -> @location(0) vec4f {
    let st = plane_st(in.uv);
    // The plane's object space is 2 wide, y up.
    let p = WOOD_SCALE * vec3f(2.0 * st.x - 1.0, 1.0 - 2.0 * st.y, 0.0);
    let colour = hart_wood(p, dpdx(p), dpdy(p));
    // Matte, under an ambient light and a distant one (diffuse's sum, with its guard).
    let lit = max(0.0, dot(safe_normalize(WOOD_LIGHT), facing_normal(in)));
    return vec4f(colour * (0.35 + 0.75 * lit), 1.0);
}
