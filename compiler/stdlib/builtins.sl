// The built-in functions written in the language: RenderMan's `noise`, `snoise`, `pnoise` and
// `cellnoise` in every overload of docs/builtins.md, and the light sums `diffuse`, `specular`,
// `phong` and the one-light `specularbrdf`. The semantic stage inlines `__NAME_RESULT`
// (overloaded by parameter types) where a shader calls built-in NAME with result type RESULT, so
// both backends run this code and nothing else. This file is not for `#include`; its functions
// see only each other and what it includes, never the calling file's functions.
//
// Float results are the stdlib's noises directly (compiler/stdlib/noise.sl, cellular.sl). A colour,
// point or vector result has three components: the same noise at three domain offsets (noise,
// snoise, pnoise), or three independent hash streams (cellnoise: seeds 0, 1, 2). The offsets are
// far from the origin and not lattice-aligned, so the components are decorrelated; a periodic
// noise stays periodic, since an offset moves the domain, not the period.

#include <noise.sl>
#include <cellular.sl>
#include <lighting.sl>

#define PATINA_OFFSET_1 vector(123.4567, -371.2345, 291.7311)
#define PATINA_OFFSET_2 vector(-217.8913, 159.3417, -433.5129)
#define PATINA_OFFSET_W1 57.3291
#define PATINA_OFFSET_W2 -141.6183

// A builtin of one float-valued noise family F (F1, F2, F3, F4 over 1-4 dimensions): the float
// overloads and the three-component ones for type T.
#define PATINA_NOISE_FLOAT(NAME, F1, F2, F3, F4) \
    float __##NAME##_float(float x) { return F1(x); } \
    float __##NAME##_float(float x, y) { return F2(x, y); } \
    float __##NAME##_float(point p) { return F3(p); } \
    float __##NAME##_float(point p; float w) { return F4(p, w); }

#define PATINA_NOISE_TRIPLE(NAME, T, F1, F2, F3, F4) \
    T __##NAME##_##T(float x) \
    { \
        return T(F1(x), F1(x + xcomp(PATINA_OFFSET_1)), F1(x + xcomp(PATINA_OFFSET_2))); \
    } \
    T __##NAME##_##T(float x, y) \
    { \
        return T(F2(x, y), F2(x + xcomp(PATINA_OFFSET_1), y + ycomp(PATINA_OFFSET_1)), \
                 F2(x + xcomp(PATINA_OFFSET_2), y + ycomp(PATINA_OFFSET_2))); \
    } \
    T __##NAME##_##T(point p) \
    { \
        return T(F3(p), F3(p + PATINA_OFFSET_1), F3(p + PATINA_OFFSET_2)); \
    } \
    T __##NAME##_##T(point p; float w) \
    { \
        return T(F4(p, w), F4(p + PATINA_OFFSET_1, w + PATINA_OFFSET_W1), \
                 F4(p + PATINA_OFFSET_2, w + PATINA_OFFSET_W2)); \
    }

#define PATINA_NOISE(NAME, F1, F2, F3, F4) \
    PATINA_NOISE_FLOAT(NAME, F1, F2, F3, F4) \
    PATINA_NOISE_TRIPLE(NAME, color, F1, F2, F3, F4) \
    PATINA_NOISE_TRIPLE(NAME, point, F1, F2, F3, F4) \
    PATINA_NOISE_TRIPLE(NAME, vector, F1, F2, F3, F4)

// noise in [0, 1] and snoise in [-1, 1]: Perlin's improved noise (compiler/stdlib/noise.sl).
PATINA_NOISE(noise, noise1, noise2, noise3, noise4)
PATINA_NOISE(snoise, snoise1, snoise2, snoise3, snoise4)

// pnoise: each domain argument followed by its period, in [0, 1].
float __pnoise_float(float x, px) { return pnoise1(x, px); }
float __pnoise_float(float x, y, px, py) { return pnoise2(x, y, px, py); }
float __pnoise_float(point p, period) { return pnoise3(p, period); }
float __pnoise_float(point p; float w; point pp; float pw) { return pnoise4(p, w, pp, pw); }

#define PATINA_PNOISE_TRIPLE(T) \
    T __pnoise_##T(float x, px) \
    { \
        return T(pnoise1(x, px), pnoise1(x + xcomp(PATINA_OFFSET_1), px), \
                 pnoise1(x + xcomp(PATINA_OFFSET_2), px)); \
    } \
    T __pnoise_##T(float x, y, px, py) \
    { \
        return T(pnoise2(x, y, px, py), \
                 pnoise2(x + xcomp(PATINA_OFFSET_1), y + ycomp(PATINA_OFFSET_1), px, py), \
                 pnoise2(x + xcomp(PATINA_OFFSET_2), y + ycomp(PATINA_OFFSET_2), px, py)); \
    } \
    T __pnoise_##T(point p, period) \
    { \
        return T(pnoise3(p, period), pnoise3(p + PATINA_OFFSET_1, period), \
                 pnoise3(p + PATINA_OFFSET_2, period)); \
    } \
    T __pnoise_##T(point p; float w; point pp; float pw) \
    { \
        return T(pnoise4(p, w, pp, pw), pnoise4(p + PATINA_OFFSET_1, w + PATINA_OFFSET_W1, pp, pw), \
                 pnoise4(p + PATINA_OFFSET_2, w + PATINA_OFFSET_W2, pp, pw)); \
    }

PATINA_PNOISE_TRIPLE(color)
PATINA_PNOISE_TRIPLE(point)
PATINA_PNOISE_TRIPLE(vector)

// cellnoise: one value in [0, 1) per unit cell (compiler/stdlib/cellular.sl); components are streams.
float __cellnoise_float(float x) { return cellnoise1(x, 0); }
float __cellnoise_float(float x, y) { return cellnoise2(x, y, 0); }
float __cellnoise_float(point p) { return cellnoise3(p, 0); }
float __cellnoise_float(point p; float w) { return cellnoise4(p, w, 0); }

#define PATINA_CELLNOISE_TRIPLE(T) \
    T __cellnoise_##T(float x) { return T(cellnoise1(x, 0), cellnoise1(x, 1), cellnoise1(x, 2)); } \
    T __cellnoise_##T(float x, y) \
    { \
        return T(cellnoise2(x, y, 0), cellnoise2(x, y, 1), cellnoise2(x, y, 2)); \
    } \
    T __cellnoise_##T(point p) { return T(cellnoise3(p, 0), cellnoise3(p, 1), cellnoise3(p, 2)); } \
    T __cellnoise_##T(point p; float w) \
    { \
        return T(cellnoise4(p, w, 0), cellnoise4(p, w, 1), cellnoise4(p, w, 2)); \
    }

PATINA_CELLNOISE_TRIPLE(color)
PATINA_CELLNOISE_TRIPLE(point)
PATINA_CELLNOISE_TRIPLE(vector)

// The light sums: the lighting library's definitions (compiler/stdlib/lighting.sl, where their
// guards are described), so that a shader calling `diffuse(N)` and one calling `rm_diffuse(N)` run
// the same code on both backends. The sums are at fragment rate whatever their arguments, as the
// built-ins' rate rule has it (docs/builtins.md): RenderMan lights every shading point, never a
// vertex to be interpolated.
color __diffuse_color(normal N)
{
    fragment color C = rm_diffuse(N);
    return C;
}

color __specular_color(normal N; vector V; float roughness)
{
    fragment color C = rm_specular(N, V, roughness);
    return C;
}

color __phong_color(normal N; vector V; float size)
{
    fragment color C = rm_phong(N, V, size);
    return C;
}

color __specularbrdf_color(vector L; normal N; vector V; float roughness)
{
    return rm_specularbrdf(L, N, V, roughness);
}
