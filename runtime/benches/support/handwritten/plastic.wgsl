// Plastic (RenderMan's: ambient, diffuse and specular sums) under four point lights whose
// camera-space positions and colours (intensity / distance^2 follows) come from the uniforms, at
// the interpolated position and normal. The sums are the standard library's (compiler/stdlib/
// lighting.sl, which the built-ins diffuse and specular are), with its guards (noise.wgsl's
// safe_normalize and pow01).

struct Lights {
    position: array<vec4f, 4>,
    colour: array<vec4f, 4>,
};
@group(0) @binding(0) var<uniform> lights: Lights;

@fragment
fn plastic4(in: Surface) -> @location(0) vec4f {
    let p = in.p;
    let n = facing_normal(in);
    let v = -normalize(p);
    let cs = vec3f(1.0);
    var diffuse = vec3f(0.0);
    var specular = vec3f(0.0);
    for (var k = 0; k < 4; k++) {
        let l = lights.position[k].xyz - p;
        let cl = lights.colour[k].xyz / dot(l, l);
        let ln = safe_normalize(l);
        diffuse += cl * max(0.0, dot(ln, n));
        let lit = dot(ln, n) >= 0.0 && dot(ln, ln) > 0.0;
        specular += cl * select(0.0, pow01(dot(n, safe_normalize(ln + v)), 1.0 / 0.1), lit);
    }
    return vec4f(cs * (0.5 * diffuse) + 0.5 * specular, 1.0);
}
