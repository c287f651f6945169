// The Banks / Heidrich-Seidel anisotropic lighting model in the two styles of W. R. Mark's chapter
// of Texturing & Modeling (shared/seeds/002_a44091d2843c02ac.txt L3259-3401). The fibres run along
// the binormal B, as in the listings; the table is indexed by (0.5 B.E + 0.5, 0.5 B.L + 0.5) and
// holds the diffuse term sqrt(1 - (B.L)^2) and the specular term (V.R)^n (compiler/stdlib/lighting.sl
// banks_table; the `banks:N:n` generated texture, runtime/src/render/textures.rs).
#include <lighting.sl>

// The first listing's style (anisotropic1, L3283-3327): every computation written out with its
// rate. The light is a parameter (a point light: position in camera space and intensity, falling
// off as 1 / distance^2 like the standard pointlight); the dot products are computed per vertex and
// interpolated, the table lookup and the lighting per fragment.
surface shader float4
banks_explicit(primitive group texref anisotex,
               primitive group float3 lightpos,
               primitive group float intensity,
               primitive group float4 base,
               primitive group float kd,
               primitive group float ks,
               primitive group float ambient)
{
    // The listing transforms __position and __objnormal by __modelview and __invmodelview3; the
    // runtime gives those matrices no value yet, so this reads the eye-space P and N it computes.
    vertex float3 Peye3 = {P[0], P[1], P[2]};
    vertex float3 Lvec = lightpos - Peye3;
    vertex float3 Ldir = normalize(Lvec);
    vertex float light_intensity = intensity / dot(Lvec, Lvec);
    vertex float3 Ndir = normalize(N);
    vertex float3 Bdir = normalize(B);
    vertex float3 Edir = normalize(-Peye3);
    vertex float4 aniso_uv = {0.5 * dot(Bdir, Edir) + 0.5, 0.5 * dot(Bdir, Ldir) + 0.5, 0, 1};
    fragment float4 brdf = texture(anisotex, aniso_uv);
    fragment float lit = light_intensity * max(dot(Ndir, Ldir), 0) * (kd * brdf[0] + ks * brdf[1]);
    float4 result = base * (ambient + lit);
    result[3] = 1;
    return result;
}

// The table entry of an N x N table at (s, t), filtered as a texture lookup is (bilinear between
// texel centres, wrapping at the border: compiler/src/opt/textures.rs), with each texel computed
// by banks_table; N = 0 evaluates banks_table at (s, t) itself.
// The table wraps, so s and t are taken modulo 1 first, and size is at most 8192 (the largest 2D
// texture every WebGPU device has): s * size then stays far inside f32's range.
float banks_lookup(float s, float t, float kd, float ks, float n, float size)
{
    float exact = banks_table(s, t, kd, ks, n);
    float entries = min(size, 8192);
    float x = (s - floor(s)) * entries - 0.5, y = (t - floor(t)) * entries - 0.5;
    float x0 = floor(x), y0 = floor(y);
    float fx = x - x0, fy = y - y0;
    float sx0 = (mod(x0, entries) + 0.5) / entries, sx1 = (mod(x0 + 1, entries) + 0.5) / entries;
    float sy0 = (mod(y0, entries) + 0.5) / entries, sy1 = (mod(y0 + 1, entries) + 0.5) / entries;
    float top = mix(banks_table(sx0, sy0, kd, ks, n), banks_table(sx1, sy0, kd, ks, n), fx);
    float bottom = mix(banks_table(sx0, sy1, kd, ks, n), banks_table(sx1, sy1, kd, ks, n), fx);
    return select(size > 0, mix(top, bottom, fy), exact);
}

// The second listing's style (anisotropic2, L3363-3397): the light is any bound light shader,
// the per-light values are `perlight` and summed by integrate(); rates are inferred, except the
// one declaration that moves the table lookup to fragments (as a texture lookup would be).
// The table is the standard library's banks_table, evaluated per fragment as a table of
// `table_size` entries per axis would give it (the cost knob; 0 evaluates it exactly).
surface shader float4
banks_perlight(primitive group float4 base,
               primitive group float kd,
               primitive group float ks,
               primitive group float exponent,
               primitive group float ambient,
               primitive group float table_size)
{
    // The dot products per vertex (B, E and L are per-vertex values), interpolated to fragments
    // (a fragment-rate copy), where the table is read.
    perlight float s = 0.5 * dot(B, E) + 0.5;
    perlight float t = 0.5 * dot(B, L) + 0.5;
    fragment perlight float s_at = s, t_at = t;
    perlight float brdf = banks_lookup(s_at, t_at, kd, ks, exponent, table_size);
    perlight float lit = Cl[0] * max(dot(N, L), 0) * brdf;
    float4 result = base * (ambient + integrate(lit));
    result[3] = 1;
    return result;
}

// The same model in RenderMan style, with the standard library's light sum banks() evaluated per
// fragment (fibres along N x dPdu, the Stanford binormal). Not in the scene: the tests compare it
// with banks_perlight at table_size 0. (It also keeps this file readable in both styles: a file
// whose shaders are all Stanford-style checks the uncalled RenderMan functions of an included
// module, lighting.sl's illuminance loops, as Stanford code, and rejects them.)
surface
banks_rsl(color base = 1; float kd = 0.6, ks = 0.4, exponent = 32, ambient = 0.05)
{
    normal Nn = normalize(N);
    vector fibre = Nn ^ normalize(dPdu);
    Oi = 1;
    Ci = base * (ambient + banks(fibre, Nn, -normalize(I), kd, ks, exponent));
}
