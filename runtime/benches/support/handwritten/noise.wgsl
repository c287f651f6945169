// The vertex stages (a full-screen quad's, and a surface's with its position and normal), the plane's (s, t), improved noise, the trivial shader and fBm. The Rust side
// puts before this: PERM (Perlin's permutation), PLANE_SPAN and the shaders' constants.

struct Varyings {
    @builtin(position) position: vec4f,
    @location(0) uv: vec2f,
};

@vertex
fn vs_main(@location(0) position: vec3f) -> Varyings {
    var out: Varyings;
    out.position = vec4f(position.xy, 0.5, 1.0);
    out.uv = vec2f(position.x * 0.5 + 0.5, 0.5 - position.y * 0.5);
    return out;
}

// What a mesh's vertex stage hands a surface shader: the position and normal in the camera's
// space (the plane at z = 2 facing the camera, 4 wide in view) and the texture coordinates.
struct Surface {
    @builtin(position) position: vec4f,
    @location(0) p: vec3f,
    @location(1) n: vec3f,
    @location(2) uv: vec2f,
};

@vertex
fn vs_surface(@location(0) position: vec3f) -> Surface {
    var out: Surface;
    out.position = vec4f(position.xy, 0.5, 1.0);
    out.p = vec3f(2.0 * position.x, 2.0 * position.y, 2.0);
    out.n = vec3f(0.0, 0.0, -1.0);
    out.uv = vec2f(position.x * 0.5 + 0.5, 0.5 - position.y * 0.5);
    return out;
}

// The shading normal as RenderMan's faceforward(normalize(N), I) gives it: turned towards the eye
// by the geometric normal, which comes from the position's screen derivatives on N's side.
fn facing_normal(in: Surface) -> vec3f {
    let c = normalize(cross(dpdy(in.p), dpdx(in.p)));
    let ng = select(-c, c, dot(c, in.n) >= 0.0);
    return faceForward(normalize(in.n), in.p, ng);
}

// The lighting library's guards (compiler/stdlib/lighting.sl), part of the light sums the
// built-ins diffuse and specular are: RenderMan's sums made total.
// v / |v| where |v|^2 neither overflows nor underflows, rescaled first where it would, 0 for 0.
fn safe_normalize(v: vec3f) -> vec3f {
    let m = max(max(abs(v.x), abs(v.y)), abs(v.z));
    var n = normalize(v);
    if (m < 1e-18 || m > 1e18) {
        let w = v / m;
        n = w / sqrt(dot(w, w));
    }
    return select(n, vec3f(0.0), m == 0.0);
}
// x^e for a cosine x: the base clamped to [0, 1], the exponent to [0, 1e30]; 1 for e = 0, 0 for a
// denormal base.
fn pow01(x: f32, e: f32) -> f32 {
    let b = clamp(x, 0.0, 1.0);
    let k = clamp(e, 0.0, 1e30);
    return select(select(pow(b, k), 0.0, b < 1.17549435e-38), 1.0, k == 0.0);
}

// The Patina plane's (s, t) at a point of the screen: the plane reaches past the view, which
// shows the middle PLANE_SPAN of it.
fn plane_st(uv: vec2f) -> vec2f {
    return 0.5 + (uv - 0.5) * PLANE_SPAN;
}

fn perm(i: i32) -> i32 {
    return PERM[i & 255];
}

fn fade(t: vec3f) -> vec3f {
    return t * t * t * (t * (t * 6.0 - 15.0) + 10.0);
}

fn grad(hash: i32, x: f32, y: f32, z: f32) -> f32 {
    let h = hash & 15;
    let u = select(y, x, h < 8);
    let v = select(select(z, x, h == 12 || h == 14), y, h < 4);
    return select(-u, u, (h & 1) == 0) + select(-v, v, (h & 2) == 0);
}

// Perlin's improved noise (ImprovedNoise.java), unscaled.
fn improved_noise(p: vec3f) -> f32 {
    let cell = floor(p);
    let f = p - cell;
    let i = vec3i(cell) & vec3i(255);
    let u = fade(f);
    let a = perm(i.x) + i.y;
    let aa = perm(a) + i.z;
    let ab = perm(a + 1) + i.z;
    let b = perm(i.x + 1) + i.y;
    let ba = perm(b) + i.z;
    let bb = perm(b + 1) + i.z;
    return mix(
        mix(mix(grad(perm(aa), f.x, f.y, f.z), grad(perm(ba), f.x - 1.0, f.y, f.z), u.x),
            mix(grad(perm(ab), f.x, f.y - 1.0, f.z), grad(perm(bb), f.x - 1.0, f.y - 1.0, f.z), u.x), u.y),
        mix(mix(grad(perm(aa + 1), f.x, f.y, f.z - 1.0), grad(perm(ba + 1), f.x - 1.0, f.y, f.z - 1.0), u.x),
            mix(grad(perm(ab + 1), f.x, f.y - 1.0, f.z - 1.0), grad(perm(bb + 1), f.x - 1.0, f.y - 1.0, f.z - 1.0), u.x), u.y),
        u.z);
}

// RenderMan's snoise: improved noise scaled into [-1, 1] as the standard library scales it.
fn snoise(p: vec3f) -> f32 {
    return SNOISE_SCALE * improved_noise(p);
}

@fragment
fn baseline(in: Varyings) -> @location(0) vec4f {
    return vec4f(in.uv, 0.0, 1.0);
}

@fragment
fn fbm_bench(in: Varyings) -> @location(0) vec4f {
    var p = vec3f(plane_st(in.uv) * 16.0, 0.5);
    var sum = 0.0;
    var amplitude = 1.0;
    for (var octave = 0; octave < 6; octave++) {
        sum += amplitude * snoise(p);
        p *= 2.0;
        amplitude *= 0.5;
    }
    return vec4f(vec3f(sum), 1.0);
}
