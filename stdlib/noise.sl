// The noise core: Perlin's improved noise (2002) and RenderMan's signed and unsigned conventions
// on top of it. Issue 7 extends this module (original gradient noise, value noise, 1D/2D/4D
// domains, periodic noise, vector results, fractal sums).
//
// Sources: Perlin, "Recent improvements to the noise function", T&M ch. 12
// (shared/seeds/002_a44091d2843c02ac.txt L8436-8447: the fade 6t^5 - 15t^4 + 10t^3 and the 12
// gradient directions), with the details the text leaves out (the permutation table, how a hash
// picks one of the 12 gradients) taken from his reference implementation, ImprovedNoise.java
// (Perlin 2002, mrl.nyu.edu/~perlin/noise/), which this file reproduces operation for operation.
// RenderMan's ranges: Peachey, T&M ch. 2, L2676-2681 (noise in [0, 1], 0.5 at the lattice points;
// `snoise(x) = 2 * noise(x) - 1`).
//
// Precision (measured by compiler/tests/stdlib_noise.rs): in the interpreter's f64 mode
// `perlin_improved_noise` is bit-identical to the Java reference for |coordinates| < 2^31. In f32
// it is within 2e-6 of the reference at the same coordinates, at any magnitude (largest error
// measured 1.76e-6, about 15 ulp of 1: the reference's order of operations, kept for the f64
// mode, is not the most accurate one in f32). The cell is split off with floor before anything
// else, so no offset (Perlin's original +10000, T&M L8321) eats into the fraction: what is lost
// at large coordinates is only the coordinate's own rounding to f32, and against f64 at the exact
// coordinate the f32 result stays within 1e-3 up to |coordinates| of 2^12 = 4096 (1.3e-3 at
// 2^13, 0.18 at 2^20; above 2^23 every f32 is an integer and the noise is 0). The GPU (WGSL)
// computes the same operations and agrees bit for bit (runtime/tests/stdlib_noise_gpu.rs).
// Derivatives (Du, filterwidth, ...) go through this code by automatic differentiation.

#ifndef PATINA_NOISE_SL
#define PATINA_NOISE_SL

// Perlin's fade curve 6t^5 - 15t^4 + 10t^3 (T&M L8438), in the reference's Horner form
// t * t * t * (t * (t * 6 - 15) + 10). fade(0) = 0, fade(1) = 1; first and second derivatives
// are 0 at both ends, so noise is C2 across cell faces.
float perlin_fade(float t)
{
    return t * t * t * (t * (t * 6 - 15) + 10);
}

// The reference's lerp: a + t * (b - a) (not `mix`, which rounds differently).
float perlin_lerp(float t, a, b)
{
    return a + t * (b - a);
}

// The gradient of a lattice point dotted with the offset (x, y, z) from it: the low 4 bits of
// `hash` pick one of the 12 edge directions (+-1, +-1, 0), (+-1, 0, +-1), (0, +-1, +-1) of
// T&M L8445, in the order listed there for codes 0-11; codes 12-15 repeat (1, 1, 0), (0, -1, 1),
// (-1, 1, 0), (0, -1, -1), as in the reference. No multiplies: a component +-1 is a sign.
float perlin_grad(int hash; float x, y, z)
{
    int h = hash & 15;
    float u = h < 8 ? x : y;
    float v = h < 4 ? y : ((h == 12 || h == 14) ? x : z);
    return ((h & 1) == 0 ? u : -u) + ((h & 2) == 0 ? v : -v);
}

// The reference's p[i] for an int i: Perlin's table entry i mod 256 (p[i & 255] reads the same
// entries as the reference's doubled table for its indices 0..511). For perlin_improved_noise only.
#define PERLIN_P(i) perlin_p[(i) & 255]

// Perlin's improved noise at (x, y, z): ImprovedNoise.noise(x, y, z), operation for operation.
// Signed; 0 at every lattice point; C2; period 256 in each coordinate.
// Range [-1.0266, 1.0364]: measured by local maximisation in every one of the 256^3 cells (a
// search outside the tests, which check the two extreme points); the maximum, 1.036354 at
// (12.3553, 187.5185, 5.5), is also the bound for any choice of the 12 gradients.
// Departure from the reference: the cell is reduced modulo 256 in float (exact: the cell and
// 256 floor(cell / 256) are integers, and multiplying by 2^-8 is exact) before the conversion to
// int, so the period holds for every finite input; the reference's (int) cast saturates beyond
// 2^31, which changes the hash there (only the f64 mode has fractions at such coordinates).
// Every finite input gives a finite result; an infinite or NaN one gives NaN.
float perlin_improved_noise(float x, y, z)
{
    // Perlin's permutation of 0..255, as published in ImprovedNoise.java. A local table (one
    // constant composite store per call on the GPU, uniform registers in the interpreter): a
    // file-level table cannot be used yet, because the semantic stage checks a function that no
    // shader calls without the file's global declarations in scope.
    constant int perlin_p[256] = {
        151, 160, 137,  91,  90,  15, 131,  13, 201,  95,  96,  53, 194, 233,   7, 225,
        140,  36, 103,  30,  69, 142,   8,  99,  37, 240,  21,  10,  23, 190,   6, 148,
        247, 120, 234,  75,   0,  26, 197,  62,  94, 252, 219, 203, 117,  35,  11,  32,
         57, 177,  33,  88, 237, 149,  56,  87, 174,  20, 125, 136, 171, 168,  68, 175,
         74, 165,  71, 134, 139,  48,  27, 166,  77, 146, 158, 231,  83, 111, 229, 122,
         60, 211, 133, 230, 220, 105,  92,  41,  55,  46, 245,  40, 244, 102, 143,  54,
         65,  25,  63, 161,   1, 216,  80,  73, 209,  76, 132, 187, 208,  89,  18, 169,
        200, 196, 135, 130, 116, 188, 159,  86, 164, 100, 109, 198, 173, 186,   3,  64,
         52, 217, 226, 250, 124, 123,   5, 202,  38, 147, 118, 126, 255,  82,  85, 212,
        207, 206,  59, 227,  47,  16,  58,  17, 182, 189,  28,  42, 223, 183, 170, 213,
        119, 248, 152,   2,  44, 154, 163,  70, 221, 153, 101, 155, 167,  43, 172,   9,
        129,  22,  39, 253,  19,  98, 108, 110,  79, 113, 224, 232, 178, 185, 112, 104,
        218, 246,  97, 228, 251,  34, 242, 193, 238, 210, 144,  12, 191, 179, 162, 241,
         81,  51, 145, 235, 249,  14, 239, 107,  49, 192, 214,  31, 181, 199, 106, 157,
        184,  84, 204, 176, 115, 121,  50,  45, 127,   4, 150, 254, 138, 236, 205,  93,
        222, 114,  67,  29,  24,  72, 243, 141, 128, 195,  78,  66, 215,  61, 156, 180
    };
    // Cell and fraction, before anything else.
    float cx = floor(x), cy = floor(y), cz = floor(z);
    x -= cx;
    y -= cy;
    z -= cz;
    // The cell modulo 256, as int. The mask changes nothing for finite inputs; for NaN it makes
    // both backends agree (the float-to-int conversion of NaN differs between them).
    int X = int(cx - 256 * floor(cx * 0.00390625)) & 255;
    int Y = int(cy - 256 * floor(cy * 0.00390625)) & 255;
    int Z = int(cz - 256 * floor(cz * 0.00390625)) & 255;
    float u = perlin_fade(x), v = perlin_fade(y), w = perlin_fade(z);
    // Hash the 8 corners of the cell.
    int A = PERLIN_P(X) + Y, AA = PERLIN_P(A) + Z, AB = PERLIN_P(A + 1) + Z;
    int B = PERLIN_P(X + 1) + Y, BA = PERLIN_P(B) + Z, BB = PERLIN_P(B + 1) + Z;
    // Blend the 8 corners' contributions.
    return perlin_lerp(w,
        perlin_lerp(v,
            perlin_lerp(u, perlin_grad(PERLIN_P(AA), x, y, z),
                           perlin_grad(PERLIN_P(BA), x - 1, y, z)),
            perlin_lerp(u, perlin_grad(PERLIN_P(AB), x, y - 1, z),
                           perlin_grad(PERLIN_P(BB), x - 1, y - 1, z))),
        perlin_lerp(v,
            perlin_lerp(u, perlin_grad(PERLIN_P(AA + 1), x, y, z - 1),
                           perlin_grad(PERLIN_P(BA + 1), x - 1, y, z - 1)),
            perlin_lerp(u, perlin_grad(PERLIN_P(AB + 1), x, y - 1, z - 1),
                           perlin_grad(PERLIN_P(BB + 1), x - 1, y - 1, z - 1))));
}

#undef PERLIN_P

// Perlin's improved noise at a point: perlin_improved_noise of its components.
float improved_noise(point p)
{
    return perlin_improved_noise(p[0], p[1], p[2]);
}

// The same at (x, y, z).
float improved_noise(float x, y, z)
{
    return perlin_improved_noise(x, y, z);
}

// The factor that brings improved noise into [-1, 1]: 0.9649 * 1.036354 = 0.99998 (the margin,
// 2e-5, is ten times the f32 error of the noise, 2e-6).
#define PATINA_SNOISE_SCALE 0.9649

// RenderMan's signed noise at a point, in [-1, 1] (T&M L2681's snoise convention): improved noise
// scaled by PATINA_SNOISE_SCALE (its range is [-0.99056, 0.99998]). 0 at the lattice points.
// Named snoise3 for now: a file-level function named `snoise` would hide every overload of the
// built-in `snoise` (calls are resolved by name first, compiler/src/sema/lower/call.rs).
float snoise3(point p)
{
    return PATINA_SNOISE_SCALE * perlin_improved_noise(p[0], p[1], p[2]);
}

// RenderMan's noise at a point, in [0, 1] (T&M L2676: 0.5 at the lattice points):
// 0.5 + 0.5 * snoise3(p). Named noise3 for now, for the reason given at snoise3.
float noise3(point p)
{
    return 0.5 + (0.5 * PATINA_SNOISE_SCALE) * perlin_improved_noise(p[0], p[1], p[2]);
}

#endif
