// The standard RenderMan light and surface shaders (RenderMan Interface Specification 3.2,
// Appendix A): lights ambientlight, distantlight, pointlight, spotlight; surfaces constant, matte,
// metal, shinymetal, plastic, paintedplastic (`constant` is spelled `constant_`: `constant` is a
// keyword). See docs/stdlib/lighting.md.
//
// A scene names a shader by file, so use these through a one-line wrapper file next to the scene,
// `#include <shaders.sl>`, and pick the shader with `name = "plastic"` (docs/stdlib/swatches/
// lighting_shaders.sl is one).
//
// Departures from Appendix A, all documented in docs/stdlib/lighting.md:
//   * shinymetal has no environment term: environment maps work in rendered scenes
//     (examples/shaders/shinymetal.sl is Appendix A's shader with its term), but this library's
//     shaders are also checked on the GPU compute harness, which binds no textures; so it is metal
//     with the Kr parameter kept for compatibility (unused) and texturename ignored.
//   * pointlight and spotlight divide by max(L . L, 1e-30) rather than L . L, so a surface point
//     at the light position gets a large finite value rather than an infinity; spotlight's
//     cosangle is clamped to [0, 1] before pow and computed with lighting_normalize.
//   * The surfaces use the built-in light sums (ambient, diffuse, specular), which are the
//     definitions rm_diffuse and rm_specular (lighting.sl) reproduce.

#ifndef PATINA_SHADERS_SL
#define PATINA_SHADERS_SL

#include <lighting.sl>

// Ambient light: Cl = intensity * lightcolor, no direction (RI 3.2 Appendix A).
light ambientlight(float intensity = 1; color lightcolor = 1)
{
    Cl = intensity * lightcolor;
    L = 0;
}

// A light at infinity shining from `from` towards `to`: solar(to - from, 0), Cl = intensity *
// lightcolor.
light distantlight(float intensity = 1; color lightcolor = 1;
                   point from = point "shader" (0, 0, 0);
                   point to = point "shader" (0, 0, 1))
{
    solar(to - from, 0.0)
        Cl = intensity * lightcolor;
}

// A point light at `from`, falling off with the square of the distance:
// Cl = intensity * lightcolor / (L . L) (guarded: / max(L . L, 1e-30)).
light pointlight(float intensity = 1; color lightcolor = 1;
                 point from = point "shader" (0, 0, 0))
{
    illuminate(from)
        Cl = intensity * lightcolor / max(L . L, 1e-30);
}

// A spot light at `from` pointing at `to`: inside the cone of half angle coneangle around
// A = normalize(to - from), Cl = intensity * lightcolor * cosangle^beamdistribution / (L . L) *
// smoothstep(cos(coneangle), cos(coneangle - conedeltaangle), cosangle), cosangle = L . A / |L|.
light spotlight(float intensity = 1; color lightcolor = 1;
                point from = point "shader" (0, 0, 0);
                point to = point "shader" (0, 0, 1);
                float coneangle = radians(30);
                float conedeltaangle = radians(5);
                float beamdistribution = 2)
{
    vector A = lighting_normalize(to - from);
    uniform float cosoutside = cos(coneangle), cosinside = cos(coneangle - conedeltaangle);
    illuminate(from, A, coneangle) {
        float cosangle = lighting_normalize(L) . A;
        float atten = lighting_pow01(cosangle, beamdistribution) / max(L . L, 1e-30);
        atten *= smoothstep(cosoutside, cosinside, cosangle);
        Cl = atten * intensity * lightcolor;
    }
}

// Constant colour: Oi = Os, Ci = Os * Cs. Appendix A calls it `constant`, which is a keyword here
// (the Stanford rate), so it is `constant_` (the name the compiler suggests).
surface constant_()
{
    Oi = Os;
    Ci = Os * Cs;
}

// Lambertian: Ci = Os * Cs * (Ka * ambient() + Kd * diffuse(Nf)), Nf the unit normal facing the
// eye.
// sweep: Ka in [0, 1e4]; Kd in [0, 1e4] (non-negative coefficients: products of two values of 1e30 overflow f32)
surface matte(float Ka = 1; float Kd = 1)
{
    normal Nf = faceforward(normalize(N), I);
    Oi = Os;
    Ci = Os * Cs * (Ka * ambient() + Kd * diffuse(Nf));
}

// Metal: Ci = Os * Cs * (Ka * ambient() + Ks * specular(Nf, V, roughness)), V = -normalize(I).
// sweep: Ka in [0, 1e4]; Ks in [0, 1e4]
surface metal(float Ka = 1; float Ks = 1; float roughness = .1)
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    Oi = Os;
    Ci = Os * Cs * (Ka * ambient() + Ks * specular(Nf, V, roughness));
}

// Shiny metal: metal plus, in Appendix A, Kr * environment(texturename, reflect(I, Nf)). Here it
// is metal (see the departures above); Kr and texturename are kept so that scenes written for the
// standard shader load.
// sweep: Ka in [0, 1e4]; Ks in [0, 1e4]; Kr in [0, 1e4]
surface shinymetal(float Ka = 1; float Ks = 1; float Kr = 1; float roughness = .1;
                   string texturename = "")
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    Oi = Os;
    Ci = Os * Cs * (Ka * ambient() + Ks * specular(Nf, V, roughness));
}

// Plastic: Ci = Os * (Cs * (Ka * ambient() + Kd * diffuse(Nf)) + specularcolor * Ks *
// specular(Nf, V, roughness)) (the specular term is not multiplied by Cs; Peachey's printed
// parentheses, stdlib-catalogue §3.6, are not followed).
// sweep: Ka in [0, 1e4]; Kd in [0, 1e4]; Ks in [0, 1e4]; specularcolor in [0, 1e4]
surface plastic(float Ks = .5; float Kd = .5; float Ka = 1; float roughness = .1;
                color specularcolor = 1)
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    Oi = Os;
    Ci = Os * (Cs * (Ka * ambient() + Kd * diffuse(Nf))
               + specularcolor * Ks * specular(Nf, V, roughness));
}

// Painted plastic: plastic with Cs multiplied by color texture(texturename) at (s, t). The
// texture must be bound by the scene (a file, or a generated table such as "checker:8");
// Appendix A skips the lookup when texturename is "" (its default); this version always looks a
// texture up, by default the generated checker table "checker:8".
// sweep: Ka in [0, 1e4]; Kd in [0, 1e4]; Ks in [0, 1e4]; specularcolor in [0, 1e4]
surface paintedplastic(float Ks = .5; float Kd = .5; float Ka = 1; float roughness = .1;
                       color specularcolor = 1; string texturename = "checker:8")
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    color Ct = Cs * color texture(texturename);
    Oi = Os;
    Ci = Os * (Ct * (Ka * ambient() + Kd * diffuse(Nf))
               + specularcolor * Ks * specular(Nf, V, roughness));
}

#endif
