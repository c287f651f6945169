// Lighting functions: RenderMan's illuminance-based light sums written in the language
// (rm_diffuse, rm_specular, rm_phong, rm_specularbrdf: the built-ins diffuse, specular, phong and
// specularbrdf are these, through compiler/stdlib/builtins.sl; docs/builtins.md), Kajiya & Kay's
// hair lighting model and the Banks / Heidrich-Seidel anisotropic model. See docs/stdlib/lighting.md.
//
// Sources: RenderMan Interface Specification 3.2 §15.6 (the light sums);
// Kajiya & Kay, "Rendering Fur with Three Dimensional Textures", SIGGRAPH 1989
// (shared/seeds/003_40eb5f8fea62bec3.txt L257-325, equations 10-16); W. R. Mark's chapter of
// Texturing & Modeling, 3rd ed. (shared/seeds/002_a44091d2843c02ac.txt L3259-3401: the two
// Heidrich/Banks anisotropic listings, whose BRDF table is "precomputed as described in Heidrich
// and Seidel (1999)", L3281; the table's formula is from that paper, not in the seeds).
//
// Conventions: L (inside illuminance) points from the surface to the light, V and E point from the
// surface towards the eye (V = -normalize(I)), T is the fibre direction (hair tangent; the
// Stanford listings pass the binormal B). Sums visit the non-ambient lights in binding order, as
// the built-ins do.
//
// Guards (shared by every function, so that finite inputs give finite results on both backends):
//   * vectors are normalized by lighting_normalize: the built-in normalize where the largest
//     component's magnitude is in [1e-18, 1e18] (bit for bit the same), rescaled by that
//     component outside it (normalize would overflow or underflow in f32), and 0 for a zero
//     vector; a zero L, N, T or V contributes no light (0), as a NaN direction does in the
//     built-ins (max(0, NaN) = 0).
//   * powers go through lighting_pow01: the base clamped to [0, 1] (a cosine; above 1 only by
//     rounding or for an unnormalized N), the exponent clamped to [0, 1e30]; x^0 = 1 (also at
//     x = 0, where lavapipe's pow gives 0), and a base below the smallest normal f32 is 0 (pow of
//     a denormal is garbage on lavapipe).
//   * roughness enters as the exponent 1 / roughness with roughness clamped to >= 1e-30: 0 and
//     negative roughness are the limit roughness -> 0+ (a mirror-sharp highlight), huge roughness
//     gives exponents near 0 (flat, 1 wherever lit).
//   * square roots of 1 - c^2 take c clamped to [-1, 1] and the difference clamped to >= 0.

#ifndef PATINA_LIGHTING_SL
#define PATINA_LIGHTING_SL

// v / |v|, total: the built-in normalize(v) (v / sqrt(v . v)) when the largest component
// magnitude m is in [1e-18, 1e18], where v . v neither overflows nor underflows in f32;
// (v / m) / |v / m| outside that range; 0 for the zero vector.
// (One exit and selects, no early returns: inlined into a light loop on a SIMD device, a return
// under a varying condition costs a mask kept through the rest of the function.)
vector lighting_normalize(vector v)
{
    float m = max(abs(v[0]), abs(v[1]), abs(v[2]));
    vector n = normalize(v);
    if (m < 1e-18 || m > 1e18) {
        vector w = v / m;
        n = w / sqrt(w . w);
    }
    return m == 0 ? vector(0, 0, 0) : n;
}

// x^e for a cosine x, total: x clamped to [0, 1], e clamped to [0, 1e30]; 1 for e = 0 (0^0 = 1
// as on the interpreter), 0 for x below 2^-126 and e > 0.
float lighting_pow01(float x, e)
{
    float b = min(max(x, 0), 1);
    float k = min(max(e, 0), 1e30);
    float p = pow(b, k);
    return k == 0 ? 1 : (b < 1.17549435e-38 ? 0 : p);
}

// RenderMan's specularbrdf(L, N, V, roughness) for one light (RI 3.2 §15.6):
// pow(max(0, N . normalize(normalize(L) + V)), 1 / roughness). L need not be normalized (it is
// here, as the built-in does); N and V should be (they are not normalized). Guards above.
color rm_specularbrdf(vector L; normal N; vector V; float roughness)
{
    vector H = lighting_normalize(lighting_normalize(L) + V);
    return lighting_pow01(N . H, 1 / max(roughness, 1e-30));
}

// RenderMan's diffuse(N): the sum over the non-ambient lights of Cl * max(0, normalize(L) . N)
// (the built-in's definition; RI 3.2 writes it with illuminance(P, N, PI/2), whose cone keeps
// exactly the lights this max(0, ...) does not zero). N is used as given (pass a unit normal).
color rm_diffuse(normal N)
{
    color C = 0;
    illuminance(P) {
        C += Cl * max(0, lighting_normalize(L) . N);
    }
    return C;
}

// RenderMan's specular(N, V, roughness): the sum over the non-ambient lights with
// normalize(L) . N >= 0 of Cl * pow(max(0, N . normalize(normalize(L) + V)), 1 / roughness).
// A light that is not lit contributes Cl * 0, as in the built-in.
color rm_specular(normal N; vector V; float roughness)
{
    color C = 0;
    float e = 1 / max(roughness, 1e-30);
    illuminance(P) {
        vector Ln = lighting_normalize(L);
        float lit = (Ln . N >= 0 && Ln . Ln > 0) ? 1 : 0;
        vector H = lighting_normalize(Ln + V);
        C += Cl * (lit > 0 ? lighting_pow01(N . H, e) : 0);
    }
    return C;
}

// RenderMan's phong(N, V, size): the sum over the non-ambient lights with normalize(L) . N >= 0
// of Cl * pow(max(0, R . normalize(L)), size), R = reflect(-normalize(V), normalize(N)).
color rm_phong(normal N; vector V; float size)
{
    color C = 0;
    vector Nn = lighting_normalize(N);
    vector Vn = lighting_normalize(V);
    vector R = reflect(-Vn, Nn);
    float defined = (Nn . Nn > 0 && Vn . Vn > 0) ? 1 : 0;
    illuminance(P) {
        vector Ln = lighting_normalize(L);
        float lit = (Ln . N >= 0 && Ln . Ln > 0 && defined > 0) ? 1 : 0;
        C += Cl * (lit > 0 ? lighting_pow01(R . Ln, size) : 0);
    }
    return C;
}

// Kajiya & Kay's diffuse term for one light (eq. 14, L290-302): sin(t, l) = sqrt(1 - (t . l)^2)
// for unit t and l (the Lambert integral over the lit half cylinder, with K_d = 1). T and L are
// normalized here; 0 for a zero T or L. 0 when the tangent points at the light, 1 across it.
float kajiya_kay_diffuse(vector T, L)
{
    vector t = lighting_normalize(T), l = lighting_normalize(L);
    if (t . t == 0 || l . l == 0)
        return 0;
    float c = clamp(t . l, -1, 1);
    return sqrt(max(0, 1 - c * c));
}

// Kajiya & Kay's specular term for one light, as printed (eq. 16, L318-322):
// ((t . l)(t . e) + sin(t, l) sin(t, e))^p = cos^p(theta - theta'), which peaks where t . e = t . l
// (the back-scatter cone when l points to the light, seed-digest erratum E5; see
// kajiya_kay_specular_mirror). T, L, E normalized; the base clamped to [0, 1]; 0 for a zero
// vector.
float kajiya_kay_specular(vector T, L, E; float p)
{
    vector t = lighting_normalize(T), l = lighting_normalize(L), e = lighting_normalize(E);
    if (t . t == 0 || l . l == 0 || e . e == 0)
        return 0;
    float tl = clamp(t . l, -1, 1), te = clamp(t . e, -1, 1);
    float sl = sqrt(max(0, 1 - tl * tl)), se = sqrt(max(0, 1 - te * te));
    return lighting_pow01(tl * te + sl * se, p);
}

// The mirror form of Kajiya & Kay's specular term (erratum E5): (sin(t, l) sin(t, e) - (t . l)(t . e))^p,
// the cosine between e and the mirror cone of -l about the fibre, which peaks where
// t . e = -t . l. This is also Heidrich and Seidel's V . R for Banks' model.
float kajiya_kay_specular_mirror(vector T, L, E; float p)
{
    vector t = lighting_normalize(T), l = lighting_normalize(L), e = lighting_normalize(E);
    if (t . t == 0 || l . l == 0 || e . e == 0)
        return 0;
    float tl = clamp(t . l, -1, 1), te = clamp(t . e, -1, 1);
    float sl = sqrt(max(0, 1 - tl * tl)), se = sqrt(max(0, 1 - te * te));
    return lighting_pow01(sl * se - tl * te, p);
}

// Kajiya & Kay hair lighting summed over the non-ambient lights:
// sum of Cl * (kd * sin(t, l) + ks * ((t . l)(t . e) + sin(t, l) sin(t, e))^p), with e = V (towards
// the eye). No facing test: the diffuse integral already covers only the lit half cylinder.
color kajiya_kay(vector T; vector V; float kd, ks, p)
{
    color C = 0;
    illuminance(P) {
        C += Cl * (kd * kajiya_kay_diffuse(T, L) + ks * kajiya_kay_specular(T, L, V, p));
    }
    return C;
}

// kajiya_kay with the mirror specular term (kajiya_kay_specular_mirror).
color kajiya_kay_mirror(vector T; vector V; float kd, ks, p)
{
    color C = 0;
    illuminance(P) {
        C += Cl * (kd * kajiya_kay_diffuse(T, L) + ks * kajiya_kay_specular_mirror(T, L, V, p));
    }
    return C;
}

// Banks' anisotropic diffuse term in Heidrich and Seidel's form: L . N' = sqrt(1 - (L . T)^2),
// N' the normal in the plane of L and T (the same value as kajiya_kay_diffuse).
float banks_diffuse(vector T, L)
{
    return kajiya_kay_diffuse(T, L);
}

// Banks' anisotropic specular term in Heidrich and Seidel's form:
// (V . R)^n = (sqrt(1 - (L . T)^2) sqrt(1 - (V . T)^2) - (L . T)(V . T))^n (the same value as
// kajiya_kay_specular_mirror).
float banks_specular(vector T, L, V; float n)
{
    return kajiya_kay_specular_mirror(T, L, V, n);
}

// The table entry of the Stanford listings' anisotex (L3320, L3394): the BRDF as a function of
// the texture coordinates (0.5 (T . V) + 0.5, 0.5 (T . L) + 0.5), that is, with a = 2 s - 1 = T . V
// and b = 2 t - 1 = T . L (each clamped to [-1, 1]):
// kd sqrt(1 - b^2) + ks (sqrt(1 - b^2) sqrt(1 - a^2) - a b)^n.
float banks_table(float s, t; float kd, ks, n)
{
    float a = clamp(2 * s - 1, -1, 1), b = clamp(2 * t - 1, -1, 1);
    float sb = sqrt(max(0, 1 - b * b)), sa = sqrt(max(0, 1 - a * a));
    return kd * sb + ks * lighting_pow01(sb * sa - a * b, n);
}

// The Heidrich/Banks anisotropic model summed over the non-ambient lights, as the Stanford
// listings compute it per light (L3326, L3395) with the table replaced by its formula:
// sum of Cl * max(0, normalize(N) . normalize(L)) * (kd * banks_diffuse(T, L) +
// ks * banks_specular(T, L, V, n)). The max(0, N . L) factor is the listings' self-shadowing
// term (their N is normalized, L3314, so it is here).
color banks(vector T; normal N; vector V; float kd, ks, n)
{
    color C = 0;
    illuminance(P) {
        float shadowing = max(0, lighting_normalize(N) . lighting_normalize(L));
        C += Cl * shadowing * (kd * banks_diffuse(T, L) + ks * banks_specular(T, L, V, n));
    }
    return C;
}

#endif
