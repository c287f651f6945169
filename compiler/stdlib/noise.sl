// The gradient-noise family: Perlin's improved noise (2002) over 1 to 4 dimensions with
// RenderMan's signed and unsigned conventions, periodic noise (RenderMan's pnoise), Perlin's
// original noise (1985), vector noise, the analytic gradient of improved noise, and flow noise.
// docs/stdlib/noise.md documents every function (formulas, sources, ranges, precision).
//
// Sources: Perlin, "Recent improvements to the noise function", T&M ch. 12
// (shared/seeds/002_a44091d2843c02ac.txt L8436-8447: the fade 6t^5 - 15t^4 + 10t^3 and the 12
// gradient directions), with the details the text leaves out (the permutation table, how a hash
// picks one of the 12 gradients) taken from his reference implementation, ImprovedNoise.java
// (Perlin 2002, mrl.nyu.edu/~perlin/noise/), which this file reproduces operation for operation.
// Perlin's original noise: T&M ch. 12 "Constructing the noise function", L8166-8425 (and
// Peachey's gnoise, L2334-2483). RenderMan's ranges: Peachey, T&M ch. 2, L2676-2681 (noise in
// [0, 1], 0.5 at the lattice points; `snoise(x) = 2 * noise(x) - 1`); pnoise L2701-2712.
// Vector noise: Musgrave's VecNoise, L10370-10380. Flow noise: Perlin, L9286-9304.
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
// computes the same operations and agrees bit for bit (runtime/tests/stdlib/noise_gpu.rs). The
// other functions here share that design; runtime/tests/stdlib/noise_family.rs measures them.
// Derivatives (Du, filterwidth, ...) go through this code by automatic differentiation.

#ifndef PATINA_NOISE_SL
#define PATINA_NOISE_SL

// Perlin's permutation of 0..255, as published in ImprovedNoise.java. Every function here
// declares it as a local table (one constant composite store per call on the GPU, uniform
// registers in the interpreter): a file-level table cannot be used yet, because the semantic
// stage checks a function that no shader calls without the file's global declarations in scope.
#define PATINA_PERLIN_PERMUTATION { \
        151, 160, 137,  91,  90,  15, 131,  13, 201,  95,  96,  53, 194, 233,   7, 225, \
        140,  36, 103,  30,  69, 142,   8,  99,  37, 240,  21,  10,  23, 190,   6, 148, \
        247, 120, 234,  75,   0,  26, 197,  62,  94, 252, 219, 203, 117,  35,  11,  32, \
         57, 177,  33,  88, 237, 149,  56,  87, 174,  20, 125, 136, 171, 168,  68, 175, \
         74, 165,  71, 134, 139,  48,  27, 166,  77, 146, 158, 231,  83, 111, 229, 122, \
         60, 211, 133, 230, 220, 105,  92,  41,  55,  46, 245,  40, 244, 102, 143,  54, \
         65,  25,  63, 161,   1, 216,  80,  73, 209,  76, 132, 187, 208,  89,  18, 169, \
        200, 196, 135, 130, 116, 188, 159,  86, 164, 100, 109, 198, 173, 186,   3,  64, \
         52, 217, 226, 250, 124, 123,   5, 202,  38, 147, 118, 126, 255,  82,  85, 212, \
        207, 206,  59, 227,  47,  16,  58,  17, 182, 189,  28,  42, 223, 183, 170, 213, \
        119, 248, 152,   2,  44, 154, 163,  70, 221, 153, 101, 155, 167,  43, 172,   9, \
        129,  22,  39, 253,  19,  98, 108, 110,  79, 113, 224, 232, 178, 185, 112, 104, \
        218, 246,  97, 228, 251,  34, 242, 193, 238, 210, 144,  12, 191, 179, 162, 241, \
         81,  51, 145, 235, 249,  14, 239, 107,  49, 192, 214,  31, 181, 199, 106, 157, \
        184,  84, 204, 176, 115, 121,  50,  45, 127,   4, 150, 254, 138, 236, 205,  93, \
        222, 114,  67,  29,  24,  72, 243, 141, 128, 195,  78,  66, 215,  61, 156, 180 \
}

// Perlin's table in pairs: entry i is p[i] + 256 p[(i + 1) mod 256], so that one read gives the
// two entries the hash takes at consecutive indices (X and X + 1, A + Y and A + Y + 1, AA + Z and
// AA + Z + 1), and improved noise reads 7 entries instead of 14. A read at an index that varies
// per point is a gather (a load per lane on the GPU and in the interpreter), the larger part of a
// noise's cost and of its code. compiler/src/stdlib.rs's tests check it against the table above.
#define PATINA_PERLIN_PAIRS { \
    41111, 35232, 23433, 23131,  3930, 33551,  3459, 51469, 24521, 24671, 13664, 49717, \
    59842,  2025, 57607, 36065,  9356, 26404,  7783, 17694, 36421,  2190, 25352,  9571, \
    61477,  5616,  2581,  5898, 48663,  1726, 37894, 63380, 30967, 60024, 19434,    75, \
     6656, 50458, 16069, 24126, 64606, 56316, 52187, 30155,  9077,  2851,  8203, 14624, \
    45369,  8625, 22561, 60760, 38381, 14485, 22328, 44631,  5294, 32020, 34941, 43912, \
    43179, 17576, 44868, 19119, 42314, 18341, 34375, 35718, 12427,  6960, 42523, 19878, \
    37453, 40594, 59294, 21479, 28499, 58735, 31461, 15482, 54076, 34259, 59013, 56550, \
    27100, 23657, 10588, 14121, 11831, 62766, 10485, 62504, 26356, 36710, 13967, 16694, \
     6465, 16153, 41279,   417, 55297, 20696, 18768, 53577, 19665, 33868, 48004, 53435, \
    22992,  4697, 43282, 51369, 50376, 34756, 33415, 29826, 48244, 40892, 22175, 42070, \
    25764, 28004, 50797, 44486, 47789,   954, 16387, 13376, 55604, 58073, 64226, 31994, \
    31612,  1403, 51717,  9930, 37670, 30355, 32374, 65406, 21247, 21842, 54357, 53204, \
    52943, 15310, 58171, 12259,  4143, 14864,  4410, 46609, 48566,  7357, 10780, 57130, \
    47071, 43703, 54698, 30677, 63607, 39160,   664, 11266, 39468, 41882, 18083, 56646, \
    39389, 26009, 39781, 42907, 11175, 44075,  2476, 33033,  5761, 10006, 64807,  5117, \
    25107, 27746, 28268, 20334, 29007, 57457, 59616, 45800, 47538, 28857, 26736, 55912, \
    63194, 25078, 58465, 64484,  8955, 61986, 49650, 61121, 53998, 37074,  3216, 48908, \
    46015, 41651, 61858, 20977, 13137, 37171, 60305, 63979,  3833, 61198, 27631, 12651, \
    49201, 54976,  8150, 46367, 51125, 27335, 40298, 47261, 21688, 52308, 45260, 29616, \
    31091, 12921, 11570, 32557,  1151, 38404, 65174, 35582, 60554, 52716, 24013, 56925, \
    29406, 17266,  7491,  6173, 18456, 62280, 36339, 32909, 50048, 20163, 16974, 55106, \
    15831, 39997, 46236, 38836 \
}

// The pair of entries i and i + 1 (indices modulo 256), and its two halves. Needs the local table
// `perlin_p2` (PATINA_PERLIN_PAIRS) in scope.
#define PERLIN_P2(i) perlin_p2[(i) & 255]
#define PERLIN_LO(pair) ((pair) & 255)
#define PERLIN_HI(pair) ((pair) >> 8)
// Declares the hashes of the cell (X, Y, Z)'s corners, in pairs: hAA holds p[AA + Z] (low half)
// and p[AA + Z + 1] (high half), and hAB, hBA and hBB the same for AB, BA and BB (the reference's
// names: A = p[X], AA = p[A + Y], AB = p[A + Y + 1], B = p[X + 1], ...). Four reads of
// perlin_p2 for the eight corners, three more for the corners' hashes on the way.
#define PERLIN_CORNER_PAIRS(X, Y, Z) \
    int AB2 = PERLIN_P2(X); \
    int AA2 = PERLIN_P2(PERLIN_LO(AB2) + (Y)), BA2 = PERLIN_P2(PERLIN_HI(AB2) + (Y)); \
    int hAA = PERLIN_P2(PERLIN_LO(AA2) + (Z)), hAB = PERLIN_P2(PERLIN_HI(AA2) + (Z)); \
    int hBA = PERLIN_P2(PERLIN_LO(BA2) + (Z)), hBB = PERLIN_P2(PERLIN_HI(BA2) + (Z))

// The reference's p[i] for an int i: Perlin's table entry i mod 256 (p[i & 255] reads the same
// entries as the reference's doubled table for its indices 0..511). Needs the local table
// `perlin_p` (PATINA_PERLIN_PERMUTATION) in scope.
#define PERLIN_P(i) perlin_p[(i) & 255]

// Perlin's fade curve 6t^5 - 15t^4 + 10t^3 (T&M L8438), in the reference's Horner form
// t * t * t * (t * (t * 6 - 15) + 10). fade(0) = 0, fade(1) = 1; first and second derivatives
// are 0 at both ends, so noise is C2 across cell faces.
// sweep: t in [0, 1] (the fade is used on a cell fraction)
float perlin_fade(float t)
{
    return t * t * t * (t * (t * 6 - 15) + 10);
}

// The derivative of perlin_fade: 30 t^2 (t - 1)^2, written 30 t^2 (t (t - 2) + 1).
// sweep: t in [0, 1]
float perlin_dfade(float t)
{
    return 30 * t * t * (t * (t - 2) + 1);
}

// The reference's lerp: a + t * (b - a) (not `mix`, which rounds differently).
// sweep: t in [0, 1]
float perlin_lerp(float t, a, b)
{
    return a + t * (b - a);
}

// The same for vectors (dsnoise3).
vector perlin_vlerp(float t; vector a, b)
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

// The 1D gradient of a lattice point times the offset x from it: hash bits 0-2 give the
// magnitude 1..8, bit 3 the sign (Gustavson's noise1234 choice, 2003: the 3D gradients' x
// components would be 0 at 6 of 16 lattice points, which leaves whole cells flat).
float perlin_grad1(int hash; float x)
{
    int h = hash & 15;
    float g = 1 + (h & 7);
    return (h & 8) == 0 ? g * x : -(g * x);
}

// The 4D gradient of a lattice point dotted with the offset (x, y, z, w): the low 5 bits of
// `hash` pick one of the 32 edge directions of the 4-cube (one component 0, the others +-1):
// codes 0-7 have w = 0, 8-15 z = 0, 16-23 y = 0, 24-31 x = 0; bits 0-2 are the signs.
float perlin_grad4(int hash; float x, y, z, w)
{
    int h = hash & 31;
    float u = h < 24 ? x : y;
    float v = h < 16 ? y : z;
    float t = h < 8 ? z : w;
    return ((h & 1) == 0 ? u : -u) + ((h & 2) == 0 ? v : -v) + ((h & 4) == 0 ? t : -t);
}

// A cell index (an integer-valued float) modulo 256, as int. Reduced in float first (exact: the
// cell and 256 floor(cell / 256) are integers, and multiplying by 2^-8 is exact), so every finite
// cell works; the mask changes nothing for finite inputs, and for NaN it makes both backends
// agree (the float-to-int conversion of NaN differs between them).
int perlin_cell(float c)
{
    return int(c - 256 * floor(c * 0.00390625)) & 255;
}

// A period as the periodic noises use it: rounded to the nearest integer (ties to even), at
// least 1 (anything below, and NaN, gives 1) and at most 2^24 (larger periods are 2^24: in f32
// no coordinate above 2^23 has a fraction, so a larger period could not be seen).
float perlin_period(float period)
{
    return clamp(round(period), 1, 16777216);
}

// A cell index c (an integer-valued float) modulo a period P from perlin_period, in [0, P), as
// int. Exact with integer arithmetic for |c| < 2^31; beyond (only coordinates above 2^31 reach
// it) the remainder is taken in float, c - P floor(c / P), brought into [0, P) and clamped there:
// finite and the same on both backends, exact when P is a power of two, rounded otherwise (so
// periodicity is exact for every period only below 2^31). NaN gives 0.
int perlin_pcell(float c, P)
{
    int pi = int(P);
    int m = int(clamp(c, -2147483520, 2147483520)) % pi;
    m = m < 0 ? m + pi : m;
    float q = c - P * floor(c / P);
    q = q < 0 ? q + P : (q >= P ? q - P : q);
    return abs(c) < 2147483520 ? m : int(clamp(q, 0, P - 1));
}

// The next cell index modulo the period: c1 = c0 + 1, or 0 where c0 + 1 is the period.
int perlin_pnext(int c0; float P)
{
    return c0 + 1 == int(P) ? 0 : c0 + 1;
}

// ImprovedNoise.noise's blend of a cell's 8 corners at the fraction (x, y, z): the gradient
// picked by each corner's hash (h000 at the lower corner, h100 one step along x, ...) dotted with
// the offset from that corner, blended with the fades of x, y and z.
// sweep: x in [0, 1]; y in [0, 1]; z in [0, 1]
float perlin_corners(int h000, h100, h010, h110, h001, h101, h011, h111; float x, y, z)
{
    float u = perlin_fade(x), v = perlin_fade(y), w = perlin_fade(z);
    return perlin_lerp(w,
        perlin_lerp(v,
            perlin_lerp(u, perlin_grad(h000, x, y, z), perlin_grad(h100, x - 1, y, z)),
            perlin_lerp(u, perlin_grad(h010, x, y - 1, z), perlin_grad(h110, x - 1, y - 1, z))),
        perlin_lerp(v,
            perlin_lerp(u, perlin_grad(h001, x, y, z - 1), perlin_grad(h101, x - 1, y, z - 1)),
            perlin_lerp(u, perlin_grad(h011, x, y - 1, z - 1), perlin_grad(h111, x - 1, y - 1, z - 1))));
}

// Improved noise in the unit cell with corner indices (X0, Y0, Z0) and (X1, Y1, Z1) (only their
// values modulo 256 matter) at the fraction (x, y, z) in [0, 1]^3: ImprovedNoise.noise's hash and
// blend, operation for operation, with the cell's upper corners given instead of X + 1 (the same
// table entries, since the table is indexed modulo 256), so that periodic noise can wrap them.
// sweep: x in [0, 1]; y in [0, 1]; z in [0, 1]
float perlin_improved_lattice(int X0, X1, Y0, Y1, Z0, Z1; float x, y, z)
{
    constant int perlin_p[256] = PATINA_PERLIN_PERMUTATION;
    // Hash the 8 corners of the cell (the reference's A + 1 is A1, AA + 1 is AA + Z1).
    int A = PERLIN_P(X0), B = PERLIN_P(X1);
    int AA = PERLIN_P(A + Y0), AB = PERLIN_P(A + Y1), BA = PERLIN_P(B + Y0), BB = PERLIN_P(B + Y1);
    return perlin_corners(PERLIN_P(AA + Z0), PERLIN_P(BA + Z0), PERLIN_P(AB + Z0), PERLIN_P(BB + Z0),
                          PERLIN_P(AA + Z1), PERLIN_P(BA + Z1), PERLIN_P(AB + Z1), PERLIN_P(BB + Z1),
                          x, y, z);
}

// perlin_improved_lattice for the cell whose upper corners are (X + 1, Y + 1, Z + 1), the
// corners improved noise takes away from a period: the same entries and blend, read in pairs
// (PATINA_PERLIN_PAIRS: 7 table reads instead of 14).
// sweep: x in [0, 1]; y in [0, 1]; z in [0, 1]
float perlin_improved_cell(int X, Y, Z; float x, y, z)
{
    constant int perlin_p2[256] = PATINA_PERLIN_PAIRS;
    PERLIN_CORNER_PAIRS(X, Y, Z);
    return perlin_corners(PERLIN_LO(hAA), PERLIN_LO(hBA), PERLIN_LO(hAB), PERLIN_LO(hBB),
                          PERLIN_HI(hAA), PERLIN_HI(hBA), PERLIN_HI(hAB), PERLIN_HI(hBB), x, y, z);
}

// Perlin's improved noise at (x, y, z): ImprovedNoise.noise(x, y, z), operation for operation.
// Signed; 0 at every lattice point; C2; period 256 in each coordinate.
// Range [-1.0266, 1.0364]: measured by local maximisation in every one of the 256^3 cells (a
// search outside the tests, which check the two extreme points); the maximum, 1.036354 at
// (12.3553, 187.5185, 5.5), is also the bound for any choice of the 12 gradients.
// Departure from the reference: the cell is reduced modulo 256 in float (perlin_cell) before the
// conversion to int, so the period holds for every finite input; the reference's (int) cast
// saturates beyond 2^31, which changes the hash there (only the f64 mode has fractions at such
// coordinates). Every finite input gives a finite result; an infinite or NaN one gives NaN.
float perlin_improved_noise(float x, y, z)
{
    // Cell and fraction, before anything else.
    float cx = floor(x), cy = floor(y), cz = floor(z);
    int X = perlin_cell(cx), Y = perlin_cell(cy), Z = perlin_cell(cz);
    return perlin_improved_cell(X, Y, Z, x - cx, y - cy, z - cz);
}

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

// Improved noise over 1D: the lattice of improved noise on a line, with the quintic fade and the
// 1D gradients of perlin_grad1, hashed as the 3D noise hashes (X, 0, 0): p[p[p[X]]].
// 0 at the integers; C2; period 256. Range [-4, 4], attained (at 155.5 and 148.5: gradients 8
// and -8 on both sides of a cell centre; the bound for any of the 16 gradients).
// sweep: x in [0, 1] (the fraction within the cell)
float perlin_improved_noise1(int X0, X1; float x)
{
    constant int perlin_p[256] = PATINA_PERLIN_PERMUTATION;
    return perlin_lerp(perlin_fade(x),
        perlin_grad1(PERLIN_P(PERLIN_P(PERLIN_P(X0))), x),
        perlin_grad1(PERLIN_P(PERLIN_P(PERLIN_P(X1))), x - 1));
}

// Improved noise over 2D: exactly improved noise on the plane z = 0 (equal to
// perlin_improved_noise(x, y, 0) wherever that is not a signed zero), computed over the 4
// corners that matter. On that plane the 16 gradient codes project to (+-1, +-1), (+-1, 0) and
// (0, +-1): none is zero, so the slice is a full 2D gradient noise. 0 at the lattice points; C2;
// period 256. Range [-0.8919, 1]: measured over every one of the 256^2 cells; 1 (attained at
// (136.5, 64.5)) is also the bound for any choice of the gradients.
// sweep: x in [0, 1]; y in [0, 1] (the fractions within the cell)
float perlin_improved_noise2(int X0, X1, Y0, Y1; float x, y)
{
    constant int perlin_p[256] = PATINA_PERLIN_PERMUTATION;
    float u = perlin_fade(x), v = perlin_fade(y);
    int A = PERLIN_P(X0), B = PERLIN_P(X1);
    int AA = PERLIN_P(A + Y0), AB = PERLIN_P(A + Y1), BA = PERLIN_P(B + Y0), BB = PERLIN_P(B + Y1);
    return perlin_lerp(v,
        perlin_lerp(u, perlin_grad(PERLIN_P(AA), x, y, 0), perlin_grad(PERLIN_P(BA), x - 1, y, 0)),
        perlin_lerp(u, perlin_grad(PERLIN_P(AB), x, y - 1, 0),
                       perlin_grad(PERLIN_P(BB), x - 1, y - 1, 0)));
}

// Improved noise over 4D: the 16 corners hashed as the 3D noise hashes, one more level
// (p[p[p[p[X] + Y] + Z] + W]), the quintic fade in each coordinate and the 32 gradients of
// perlin_grad4. 0 at the lattice points; C2; period 256. Range: at least [-1.3448, 1.2542]
// (local maximisation from the 15 000 best of 2e7 random points: the whole 256^4 period cannot
// be searched); the bound for any choice of the gradients is 1.5 (at a cell's centre).
// sweep: x in [0, 1]; y in [0, 1]; z in [0, 1]; w in [0, 1] (the fractions within the cell)
float perlin_improved_noise4(int X0, X1, Y0, Y1, Z0, Z1, W0, W1; float x, y, z, w)
{
    constant int perlin_p[256] = PATINA_PERLIN_PERMUTATION;
    float fx = perlin_fade(x), fy = perlin_fade(y), fz = perlin_fade(z), fw = perlin_fade(w);
    // Corner (i, j, k) of the x, y, z cell: letters A (lower) or B (upper) for x, y, z in turn.
    int A = PERLIN_P(X0), B = PERLIN_P(X1);
    int AA = PERLIN_P(A + Y0), AB = PERLIN_P(A + Y1), BA = PERLIN_P(B + Y0), BB = PERLIN_P(B + Y1);
    int AAA = PERLIN_P(AA + Z0), AAB = PERLIN_P(AA + Z1), ABA = PERLIN_P(AB + Z0);
    int ABB = PERLIN_P(AB + Z1), BAA = PERLIN_P(BA + Z0), BAB = PERLIN_P(BA + Z1);
    int BBA = PERLIN_P(BB + Z0), BBB = PERLIN_P(BB + Z1);
    float x1 = x - 1, y1 = y - 1, z1 = z - 1, w1 = w - 1;
    return perlin_lerp(fw,
        perlin_lerp(fz,
            perlin_lerp(fy,
                perlin_lerp(fx, perlin_grad4(PERLIN_P(AAA + W0), x, y, z, w),
                                perlin_grad4(PERLIN_P(BAA + W0), x1, y, z, w)),
                perlin_lerp(fx, perlin_grad4(PERLIN_P(ABA + W0), x, y1, z, w),
                                perlin_grad4(PERLIN_P(BBA + W0), x1, y1, z, w))),
            perlin_lerp(fy,
                perlin_lerp(fx, perlin_grad4(PERLIN_P(AAB + W0), x, y, z1, w),
                                perlin_grad4(PERLIN_P(BAB + W0), x1, y, z1, w)),
                perlin_lerp(fx, perlin_grad4(PERLIN_P(ABB + W0), x, y1, z1, w),
                                perlin_grad4(PERLIN_P(BBB + W0), x1, y1, z1, w)))),
        perlin_lerp(fz,
            perlin_lerp(fy,
                perlin_lerp(fx, perlin_grad4(PERLIN_P(AAA + W1), x, y, z, w1),
                                perlin_grad4(PERLIN_P(BAA + W1), x1, y, z, w1)),
                perlin_lerp(fx, perlin_grad4(PERLIN_P(ABA + W1), x, y1, z, w1),
                                perlin_grad4(PERLIN_P(BBA + W1), x1, y1, z, w1))),
            perlin_lerp(fy,
                perlin_lerp(fx, perlin_grad4(PERLIN_P(AAB + W1), x, y, z1, w1),
                                perlin_grad4(PERLIN_P(BAB + W1), x1, y, z1, w1)),
                perlin_lerp(fx, perlin_grad4(PERLIN_P(ABB + W1), x, y1, z1, w1),
                                perlin_grad4(PERLIN_P(BBB + W1), x1, y1, z1, w1)))));
}

// The factor that brings improved noise into [-1, 1]: 0.9649 * 1.036354 = 0.99998 (the margin,
// 2e-5, is ten times the f32 error of the noise, 2e-6).
#define PATINA_SNOISE_SCALE 0.9649
// The same for 1D (range [-4, 4], attained) and 4D (measured range [-1.3448, 1.2542]:
// 0.74 * 1.3448 = 0.9952; the result is clamped to [-1, 1] in case an unsearched cell goes
// further, up to the bound 1.5). 2D needs no scale (its bound is 1).
#define PATINA_SNOISE1_SCALE 0.25
#define PATINA_SNOISE4_SCALE 0.74

// ---- RenderMan's signed noise (snoise, in [-1, 1]) and noise (in [0, 1], 0.5 at the lattice
// points, T&M L2676-2681) over 1 to 4 dimensions. Named with their dimension: a file-level
// function named `snoise` would hide every overload of the built-in `snoise` (calls are resolved
// by name first, compiler/src/sema/lower/call.rs).

// Signed 1D noise: clamp(0.25 * perlin_improved_noise1, -1, 1), in [-1, 1] (both attained).
float snoise1(float x)
{
    float cx = floor(x);
    int X = perlin_cell(cx);
    return clamp(PATINA_SNOISE1_SCALE * perlin_improved_noise1(X, X + 1, x - cx), -1, 1);
}

// Signed 2D noise: improved noise on the plane z = 0, in [-0.8919, 1] (clamped to [-1, 1]
// against rounding).
float snoise2(float x, y)
{
    float cx = floor(x), cy = floor(y);
    int X = perlin_cell(cx), Y = perlin_cell(cy);
    return clamp(perlin_improved_noise2(X, X + 1, Y, Y + 1, x - cx, y - cy), -1, 1);
}

// RenderMan's signed noise at a point, in [-1, 1] (T&M L2681's snoise convention): improved noise
// scaled by PATINA_SNOISE_SCALE (its range is [-0.99056, 0.99998]). 0 at the lattice points.
float snoise3(point p)
{
    return PATINA_SNOISE_SCALE * perlin_improved_noise(p[0], p[1], p[2]);
}

// Signed 4D noise: clamp(0.74 * perlin_improved_noise4, -1, 1); measured range
// [-0.9952, 0.9281].
float snoise4(point p; float w)
{
    float cx = floor(p[0]), cy = floor(p[1]), cz = floor(p[2]), cw = floor(w);
    int X = perlin_cell(cx), Y = perlin_cell(cy), Z = perlin_cell(cz), W = perlin_cell(cw);
    return clamp(PATINA_SNOISE4_SCALE * perlin_improved_noise4(X, X + 1, Y, Y + 1, Z, Z + 1,
        W, W + 1, p[0] - cx, p[1] - cy, p[2] - cz, w - cw), -1, 1);
}

// Unsigned noise: 0.5 + 0.5 * snoiseN, in [0, 1].
float noise1(float x)
{
    return 0.5 + 0.5 * snoise1(x);
}

float noise2(float x, y)
{
    return 0.5 + 0.5 * snoise2(x, y);
}

// RenderMan's noise at a point, in [0, 1] (T&M L2676: 0.5 at the lattice points):
// 0.5 + 0.5 * snoise3(p), written 0.5 + (0.5 * PATINA_SNOISE_SCALE) * improved noise.
float noise3(point p)
{
    return 0.5 + (0.5 * PATINA_SNOISE_SCALE) * perlin_improved_noise(p[0], p[1], p[2]);
}

float noise4(point p; float w)
{
    return 0.5 + 0.5 * snoise4(p, w);
}

// ---- Periodic noise (RenderMan's pnoise, T&M L2701-2712: integer periods, made periodic by
// wrapping the lattice): each coordinate's cell index is taken modulo its period (perlin_period:
// rounded, at least 1, at most 2^24) before hashing, and the upper corner of the last cell of a
// period is cell 0. psnoiseN(..., periods) equals snoiseN wherever every period is a multiple of
// 256 (the plain noise's own period); the signed forms have the ranges of snoiseN, and the
// unsigned ones are 0.5 + 0.5 * psnoiseN. Periodicity is exact, for any period, for cells below
// 2^31 in magnitude (perlin_pcell).

float psnoise1(float x, px)
{
    float P = perlin_period(px);
    float cx = floor(x);
    int X = perlin_pcell(cx, P);
    return clamp(PATINA_SNOISE1_SCALE * perlin_improved_noise1(X, perlin_pnext(X, P), x - cx), -1, 1);
}

float psnoise2(float x, y, px, py)
{
    float Px = perlin_period(px), Py = perlin_period(py);
    float cx = floor(x), cy = floor(y);
    int X = perlin_pcell(cx, Px), Y = perlin_pcell(cy, Py);
    return clamp(perlin_improved_noise2(X, perlin_pnext(X, Px), Y, perlin_pnext(Y, Py),
        x - cx, y - cy), -1, 1);
}

float psnoise3(point p, period)
{
    float Px = perlin_period(period[0]), Py = perlin_period(period[1]);
    float Pz = perlin_period(period[2]);
    float cx = floor(p[0]), cy = floor(p[1]), cz = floor(p[2]);
    int X = perlin_pcell(cx, Px), Y = perlin_pcell(cy, Py), Z = perlin_pcell(cz, Pz);
    return PATINA_SNOISE_SCALE * perlin_improved_lattice(X, perlin_pnext(X, Px),
        Y, perlin_pnext(Y, Py), Z, perlin_pnext(Z, Pz), p[0] - cx, p[1] - cy, p[2] - cz);
}

float psnoise4(point p; float w; point pp; float pw)
{
    float Px = perlin_period(pp[0]), Py = perlin_period(pp[1]), Pz = perlin_period(pp[2]);
    float Pw = perlin_period(pw);
    float cx = floor(p[0]), cy = floor(p[1]), cz = floor(p[2]), cw = floor(w);
    int X = perlin_pcell(cx, Px), Y = perlin_pcell(cy, Py), Z = perlin_pcell(cz, Pz);
    int W = perlin_pcell(cw, Pw);
    return clamp(PATINA_SNOISE4_SCALE * perlin_improved_noise4(X, perlin_pnext(X, Px),
        Y, perlin_pnext(Y, Py), Z, perlin_pnext(Z, Pz), W, perlin_pnext(W, Pw),
        p[0] - cx, p[1] - cy, p[2] - cz, w - cw), -1, 1);
}

float pnoise1(float x, px)
{
    return 0.5 + 0.5 * psnoise1(x, px);
}

float pnoise2(float x, y, px, py)
{
    return 0.5 + 0.5 * psnoise2(x, y, px, py);
}

float pnoise3(point p, period)
{
    return 0.5 + 0.5 * psnoise3(p, period);
}

float pnoise4(point p; float w; point pp; float pw)
{
    return 0.5 + 0.5 * psnoise4(p, w, pp, pw);
}

// ---- Perlin's original noise (1985; T&M L8307-8425, the "noise3" listing).
// Cubic s-curve t^2 (3 - 2t) (L8360), 256 unit gradients g[], the corner (i, j, k)'s gradient
// g[p[p[i] + j] + k] (L8345-8351, L8372), trilinear blend, times 1.5 (L8391). Departures from
// the listing (errata and portability, docs/stdlib/noise.md): the cell is split with floor
// instead of adding 10000 and truncating (L8321), which keeps the fraction exact at every
// magnitude; the permutation p is Perlin's 2002 table (the listing shuffles with the C library's
// random(), whose sequence is not portable, and its shuffle loop is broken, L8412); the gradient
// table is generated by the listing's procedure (L8400-8409) with a documented generator:
// draw n = 0, 1, 2, ... gives r = lowbias32(n) (Wellons' integer hash: x ^= x >> 16;
// x *= 0x7feb352d; x ^= x >> 15; x *= 0x846ca68b; x ^= x >> 16), each component is
// ((r mod 512) - 256) / 256, a triple with squared length s > 1 or s = 0 is rejected (the
// listing divides by zero for s = 0), and the accepted ones are divided by sqrt(s) in f64 (the
// values below, shortest round-trip decimals; the test regenerates them).
// Signed; 0 at the lattice points; C1 (not C2: the cubic's second derivative jumps); period 256.
// Range: at least [-1.0512, 1.1410] (local maximisation from 3e6 random points); the bound for
// any unit gradients is 1.5 sqrt(3) / 2 = 1.299. Not clamped: Perlin's scale 1.5 is kept.
float perlin_noise3(point p)
{
    constant int perlin_p[256] = PATINA_PERLIN_PERMUTATION;
    constant float perlin_g[768] = {
        0.9432565609884229, -0.20060207405636143, 0.2646240125849874, -0.7819143083038499, -0.6128517551570716, -0.1141172233740754,
        -0.7463444464674425, -0.5856730725751459, -0.3161598002396805, -0.020563250824583625, -0.35780056434775503, 0.9335715874360965,
        0.8308466818633403, 0.03701792146915873, -0.5552688220373809, -0.477111888627415, -0.857112507888188, -0.194222538733284,
        0.8861956076785157, 0.2613958267253176, 0.3825304781346111, 0.11941364809207114, 0.8847465745003452, 0.4505151268928138,
        0.3264157131832891, 0.30310030509876845, -0.895311670445593, 0.7505345058624309, 0.6592532821764596, 0.045640611842985665,
        0.7232009256977773, -0.0896001146882202, -0.6848008765456829, -0.590441386936072, -0.63136306721877, -0.5027520720445762,
        0.4856146525556612, 0.01079143672345914, 0.8741063746001903, 0.30442681997688703, 0.13530080887861645, -0.9428775118728584,
        0.4488760350770329, 0.8587193714517151, 0.24720709178155434, 0.2316098208427565, -0.816148892493523, -0.5293938762120148,
        -0.48359470356085704, -0.4247223048664918, -0.7653411830267477, 0.06842771062235126, -0.9655910276709567, -0.25090160561528796,
        0.9701306163141533, -0.004949646001602823, -0.24253265407853833, 0.896009974003918, 0.07090726412980647, 0.43833581462062177,
        -0.06286819354834577, 0.6152101797230979, -0.7858524193543222, -0.6336203162268882, 0.6531764988264835, -0.4145910711114207,
        -0.3268178737134896, 0.22625852795549278, -0.9176040300417208, 0.7089648902276959, -0.12925879214096112, -0.6932971578469733,
        -0.9428014384979441, -0.3294125508004865, 0.0511157406414548, -0.19125012579812095, 0.32599453261043343, -0.925824472613631,
        0.25142618919102167, -0.25142618919102167, -0.9346495293840154, -0.8918017337276041, 0.25752563433845255, 0.3719814718222092,
        -0.6338221331366558, -0.7723042798723957, -0.042609891303304594, -0.6609746163159788, 0.6140969839531434, 0.43127421773808544,
        -0.6539874207688694, -0.7532533685641443, 0.07007008079666457, -0.5402615627001988, 0.29091007222318394, -0.7896130531772135,
        -0.9009348439195958, -0.1683990362466534, -0.39994771108580185, -0.9540690201019654, -0.07374446532189105, 0.29036883220494597,
        0.3997316829616742, -0.35344696177663826, 0.8457480871083843, 0.44332496014420253, 0.8752826136180409, 0.19324421339619086,
        -0.037625089061153014, 0.42798538807061554, 0.9030021374676723, -0.8721425060332614, -0.05946426177499509, 0.48562480449579326,
        -0.19090932541622363, 0.9677127874546508, -0.1645770046691583, 0.36064494777607514, -0.6762092770801409, -0.6423988132261339,
        0.3643745874318493, 0.5075217467800758, 0.7808026873539627, -0.7067957751345733, -0.32621343467749536, 0.6277137303642714,
        -0.0712604747635272, 0.7749576630533583, -0.6279829338535835, 0.5856948897967396, 0.6781730302909617, -0.4438950743722658,
        0.5377734982350276, 0.5005430252802949, 0.6784219516195733, -0.7487562306574131, 0.07849863708505138, -0.6581808801746616,
        -0.03348937308172828, 0.21528882695396753, 0.9759760155246529, 0.3820298408158949, -0.01776882980539046, 0.9239791498803039,
        0.2214975734526837, -0.9598228182949627, -0.17227589046319844, -0.026310096249578974, 0.6380198340522901, 0.7695703153001849,
        0.4100927347568101, -0.6415966979259771, 0.6482110968736675, 0.7188966215341839, -0.6949334008163777, -0.015975480478537418,
        0.9005847953216374, 0.08187134502923976, -0.4269005847953216, -0.8845315641736929, 0.04422657820868465, 0.46437907119118876,
        -0.5815639691662707, 0.32045361566304714, -0.7477251032137766, -0.3600990408562262, 0.43511967436793997, 0.8252269686288517,
        -0.5659773988969453, 0.575652226228517, 0.5901644672258746, -0.747612356653803, -0.5634988658360753, -0.3514893915611163,
        -0.17086287083062998, 0.5481850439149378, -0.8187179227301019, -0.2227405756212763, 0.19014439382304074, -0.9561546660815764,
        0.2762679632873505, 0.31573481518554336, 0.9077375936584372, -0.9965552773970144, 0.0786754166366064, 0.0262251388788688,
        0.8449049099068253, 0.19202384316064214, 0.49926199221766954, -0.8424083599849175, 0.5378087269960208, 0.03331558485816058,
        0.4181151357068222, 0.5008670896487974, -0.7578336834686152, 0.23495767197385853, -0.9707461710498891, 0.04946477304712811,
        0.2527400326146412, -0.4825036986279514, 0.8386373809485821, -0.3145068739744688, -0.042887300996518475, 0.9482858775896863,
        0.8360356703394793, 0.47346918065143984, 0.2772567274085008, -0.5959938523900401, -0.791554335205522, -0.13502985718211846,
        0.31288312053180056, 0.9259649107630313, 0.2114075138728382, -0.32014468687036135, 0.9348224856614552, -0.15366944969777346,
        -0.7344396512638081, 0.6242737035742368, 0.2662343735831304, 0.2860965657854677, -0.397853036795416, 0.8717004738775969,
        0.12183852529187639, 0.9259727922182605, 0.35739300752283737, 0.5626847846428664, -0.7998162295995029, -0.20899720572449323,
        -0.4447052793343012, -0.30821157973664437, 0.8409773104242725, -0.20570201763825166, -0.5142550440956292, 0.8326034047262567,
        0.5269319375510274, -0.8496777493010318, 0.01975994765816353, 0.14514565657208017, -0.9494945034090245, -0.2781958417631537,
        -0.759845476275387, 0.004221363757085483, 0.6500900185911644, -0.22805245076946995, -0.39492009767396014, -0.8899607834906144,
        0.10976425998969036, 0.5617347423001801, 0.8200035893347456, 0.5186349673925407, 0.8503744510400216, -0.08877535477890336,
        -0.3699704101531545, -0.1263313595644918, 0.9204141911127259, -0.7930538757858331, 0.2283033884838004, 0.5647504873020326,
        -0.7366516724529988, 0.5862087252618934, 0.3371997092214431, -0.8538944719219778, 0.517262997414275, -0.05747366637936389,
        0.5644671154711912, -0.4159231377156146, 0.7130110932267679, -0.07974522228289, -0.996815278536125, 0,
        -0.9924802433485527, 0.048217663644464094, 0.1125078818370829, 0.9555444364030145, 0.10266179895238998, -0.27639715102566537,
        0.9876924213321391, -0.12346155266651739, -0.09602565207395797, -0.5241765033825111, -0.6773973274481682, -0.5161122494843186,
        0.030019427017435624, 0.9220252583926656, 0.3859640616527438, -0.09843144284370256, 0.5955102292044004, -0.7972946870339908,
        0.00972479257846436, 0.7585338211202199, 0.651561102757112, -0.7052225554744064, -0.6565865171658266, -0.2674982106971886,
        -0.14992713645869649, -0.4914278361701718, -0.8579163919580964, -0.8609236892988069, 0.29037071177533724, 0.41772628711539744,
        0.8786297311802429, -0.4637212470117949, 0.11389644663447594, -0.5205253385036676, -0.06456128229502854, 0.8514019102656888,
        -0.9650695978858372, -0.09953632623934644, 0.24234931606101742, 0.4415758592276454, -0.6984107977580106, 0.5632345143209763,
        -0.6606089674246689, -0.32137733550389297, -0.6784632638415518, -0.36095413781069857, -0.8536077583361115, 0.37558741366788906,
        -0.8294360718559045, 0.2537098572735708, -0.4976616431135427, 0.11549232723338068, -0.04724686114092846, 0.9921840839594976,
        -0.8899782907137104, 0.04975033923244344, -0.45328086856226246, 0.12995594773249874, -0.9887952544864034, 0.07345336176184711,
        0.19283952230515589, -0.795463029508768, 0.5745010768674436, 0.4644457082440095, -0.518731570246556, -0.7177797309225601,
        -0.4660896875012764, -0.40924948170843783, -0.7843948399411725, -0.3471216440383208, -0.13073412567677017, -0.928663099634988,
        0.10100237232108017, 0.7928686227204793, 0.6009641153104269, -0.783373975537104, 0.2294731847532931, 0.5776393961031171,
        0.40347582976136254, 0.9101664066709806, -0.09383158831659594, -0.22993008651462485, -0.8234705424012145, 0.5186794974864792,
        -0.3430779039969242, -0.39797036863643215, -0.8508332019123721, -0.8997251086803524, -0.34726232264855705, 0.26439290474378774,
        0.5211733788469844, -0.5312932502809065, 0.6679115146388538, -0.7337478478282297, -0.27593936157642823, -0.6208635635469636,
        -0.45335590037041884, 0.538894749496913, -0.7099724477499012, -0.7812937239906359, -0.05502068478807295, -0.6217337381052244,
        -0.6593983846105075, 0.5382843956004143, -0.5248272857104039, 0.16643306086176698, -0.98236099337921, 0.08524620190480747,
        -0.24829369738992688, 0.9488366293115063, 0.1950879050920854, -0.7428670410148874, 0.6691071929708561, 0.021074242298294677,
        -0.013995599076027095, -0.8467337440996393, -0.5318327648890296, -0.450346781498516, -0.09346819993365425, -0.8879478993697154,
        -0.04143131687273828, 0.30037704732735254, -0.9529202880729805, 0.22770281163517675, -0.9365889233295949, 0.2663693268185086,
        0, 0.899235088745796, -0.4374657188493062, -0.8840748222470096, -0.10236655836544321, -0.4559964872642471,
        0.3679980212435827, 0.3431891658788468, -0.8641751285383009, 0.5276292932385517, -0.0665078941056998, -0.8468671849459107,
        -0.5013774237971651, -0.8172057222520723, -0.28424546860941646, 0.18274137834796217, 0.8460248997590841, 0.5008467406573778,
        0.6443345444035162, -0.7029104120765632, -0.3012473194613842, 0.6631210306331438, 0.7151305232318217, -0.22104034354438126,
        -0.6156293928546236, -0.5901550731502944, -0.5222235539387498, -0.7001244545295404, -0.4711117824871674, -0.5365439744992739,
        -0.6156422596328541, 0.3150924950876812, -0.7222889502779155, 0.8155672053581076, -0.23870259669017782, -0.5271349010241427,
        -0.16370666796650407, 0.23926359164335212, -0.9570543665734085, 0.8344579960633802, -0.4699820897368463, 0.2877441365735794,
        -0.6042376825259784, 0.5674934991291284, -0.5593281250409395, 0.843529950985408, -0.4778617948932114, -0.24516387737999543,
        0.13022599756270026, -0.9220000627439179, 0.36463279317556074, -0.49161886240369435, 0.7675274076302575, -0.41135455833778506,
        0.8110771025597816, 0.3697557379316651, 0.453248969077525, -0.8266583887846036, 0.5625869590339664, -0.011481366510897272,
        0.6685182266229902, 0.3258324129759112, 0.6685182266229902, -0.9362970001591687, -0.34828439136355555, -0.045231739138124095,
        0.4225889740478609, 0.46902732284432913, -0.7755204249010195, 0.5809174966369816, -0.7569531016784911, -0.29926052857056623,
        -0.8754463039514734, -0.10328299091562326, 0.4721508156142778, -0.5582594326970527, -0.7262792619553889, 0.40107959242312524,
        -0.7486859688371789, 0.37434298441858943, 0.5471166695348615, 0.28568550908377555, 0.8363546787669951, 0.46786177574589327,
        -0.3509640378770581, 0.9108352411571269, -0.2172634520191312, 0.20906217698847882, 0.7807832324263597, -0.5887873556002057,
        -0.75096603568328, -0.12761514331872734, -0.6478922660796925, -0.6315809309675278, 0.5012547071170855, -0.5914805543981609,
        -0.8865377340540426, -0.23429925828571124, -0.39894198032431916, -0.48581049496015466, 0.843420998194713, -0.2294105115089619,
        -0.9961264171378311, -0.006264946019734787, 0.08770924427628701, -0.12106406141528717, -0.9909317619547579, -0.058290103644397524,
        0.37309277433743776, -0.40294019628443273, 0.8357278145158605, 0.7860529998542363, 0.303248873040213, 0.538665761321431,
        0.4595627043591886, -0.547479047801816, 0.6993345501118087, -0.17805523794177514, -0.9665855773982079, -0.18441435358255281,
        -0.25833072477732266, 0.8488009528397745, 0.4613048656737905, 0.38900898581105664, 0.34718006260556666, -0.8533100333919952,
        0.9379931855042609, 0.261298101676187, 0.2277983450510348, -0.17616480162412285, 0.21594395037795702, 0.9603823056282826,
        -0.0656522338546911, 0.9683704493566937, 0.2407248574672007, -0.06823568365880239, 0.5699686517382317, 0.8188282039056288,
        0.7057827200601691, 0.06116783573854798, 0.7057827200601691, 0.10945681564893643, -0.19035967938945467, -0.9755933568709552,
        -0.2803423657546121, -0.26505096398617867, -0.9225812400288143, 0.597307197058941, 0.7024332637413145, -0.38705506369419374,
        -0.465495620689163, 0.18102607471245227, 0.8663390718381645, -0.5742284081553651, 0.6259606971783711, 0.5276693480346599,
        0.8889492234860108, 0.3298363634653977, -0.31776917943617583, -0.34962581732356196, 0.7360543522601305, 0.5796428024048528,
        0.7960541793750477, 0.3573197736967544, -0.48848779188923386, 0.3818512941225167, -0.897547371751895, 0.2204502316583602,
        0.08210281198710903, 0.7024351692230439, -0.7069964365556611, -0.7892902660975449, 0.6138924291869794, -0.012528416922183254,
        0.7204293586244405, -0.6154661408116081, 0.3196607087936259, 0.10504991056409352, 0.7253446205615981, -0.6803232303198438,
        -0.08898938133667073, 0.1151627287886327, 0.9893525336841628, -0.14126383564972378, -0.9824257661094427, -0.12200058533385234,
        0.48510827888352454, -0.6563229655482979, -0.57784956749361, -0.46589918528169577, 0.8263117625750831, 0.31645982396492545,
        -0.9876221292160328, 0.1541654055361612, -0.028906013538030226, -0.9971218484901271, 0.07478413863675953, -0.01246402310612659,
        -0.4208886647799233, -0.7766914535629513, 0.46861830717764663, -0.8813707881407025, 0.23608146110911674, -0.40920786592246905,
        0.6646688749138905, -0.596971119135624, 0.4492669247103149, -0.9411990244874764, 0.14861037228749627, 0.3034128434203049,
        -0.36193239509382263, -0.8561093191642343, -0.36889263346101153, -0.8617784611145463, 0.4752454748793454, -0.17742497728828893,
        0.5853416728806126, -0.796715054754167, -0.15040029094849072, -0.8541148439221821, -0.2615471292393285, -0.4495341283800958,
        -0.13724372633593943, 0.5832858369277425, -0.8005884036263132, 0.9386118808654675, 0.23165740038381752, 0.2556219590442124,
        0.9877185357859041, -0.14965432360392486, -0.044896297081177455, 0.5282299619575843, 0.7296735915176801, -0.43422293482953966,
        -0.8618043059355207, 0.2676129160536617, -0.43090215296776035, 0.44728136483366066, -0.4308673697938933, 0.7837682631488916,
        0.23143662339054527, -0.9728183491670378, 0.00784530926747611, 0.30432481562867036, -0.791244520634543, 0.5303946786671112,
        0.0344361564369421, 0.9125581455789656, -0.4074945178371482, 0.9568531343149591, 0.14297805455280999, 0.25296117343958685,
        0.3451341695428218, -0.6783671608255463, 0.648614215175303, -0.9622786511193336, -0.17878401168337346, 0.20507577810739896,
        0.7045356507192267, 0.7085386941892223, 0.04003043469995606, 0.21123250797343632, -0.04384070920203395, -0.9764521594998471,
        -0.7540675077191281, 0.43469773974396797, -0.49236172562837194, 0.09692481004307106, 0.9530939654235321, -0.28673589637741853,
        0.6830202222781699, 0.6468337204356179, -0.33924845477392546, 0.6366302013296519, -0.7552181800087048, -0.15603681405138528,
        -0.37757178254163265, -0.5359083365107044, 0.7551435650832653, -0.03832555515866985, 0.2363409234784641, 0.9709140640196363,
        -0.6283425320979119, 0.7626447526989922, -0.15348825211552045, 0.7235453759778324, -0.6712893210461001, -0.1607878613284072,
        0.42918850218717064, -0.8927120845493149, 0.1373403206998946, 0.11346305708602605, -0.5969143438003979, 0.7942413996021823,
        0.9258614337949295, 0.3356247697506619, 0.17359901883654927, 0.8499209907806243, 0.1680634727532308, -0.4993886047524572,
        -0.28216632399155017, 0.8464989719746505, 0.45146611838648026, -0.1506896765235832, -0.9615436501981023, 0.2296223642264125,
        -0.25511827473686605, -0.7483469392281404, 0.6122838593684785, 0.7168346944912568, 0.04167643572623586, 0.6959964766281389,
        0.07225727773565263, -0.021677183320695792, 0.9971504327520064, -0.21536440122439032, -0.20691873843127698, -0.9543598956218081,
        -0.660005185887518, 0.7510403839409687, 0.018207039610690152, -0.7610800189555257, -0.3682645253010608, -0.5339835616865382,
        -0.48582686272407866, 0.28609804138195744, 0.8259056666309338, 0.6684303107332384, -0.6368509259741878, 0.3842158479017827,
        0, 0.22527079570262123, -0.9742961914138369, 0.7197049822924231, 0.5813001780054186, -0.379624606044355,
        -0.2265524048892909, -0.9638775044380741, 0.1400505775679253, 0.8409008345666743, 0.5362266191439663, 0.07312181170144995,
        0.3416505852742013, 0.2922553199333529, -0.8932310482470083, 0.7091175926988604, 0.6432709590911091, 0.2887121627416789,
        0.5790753451408703, 0.7002771615657036, -0.41747292324109253, 0.3693352763752749, -0.6915213685324296, -0.6207975922052493,
        0.2469797060115893, -0.96789344247785, -0.046725890326516896, -0.6332709276617707, 0.2793842327919577, -0.7217426013792241,
        -0.663372722626695, 0.5970354503640255, 0.4510934513861526, 0.0049240774574112215, -0.9404987943655433, 0.3397613445613743,
        0.30653510006396417, -0.3984956300831535, 0.864428982180379, -0.22605770475675968, 0.9544658645285409, 0.19466080131832084
    };
    float cx = floor(p[0]), cy = floor(p[1]), cz = floor(p[2]);
    float rx0 = p[0] - cx, ry0 = p[1] - cy, rz0 = p[2] - cz;
    float rx1 = rx0 - 1, ry1 = ry0 - 1, rz1 = rz0 - 1;
    int bx0 = perlin_cell(cx), by0 = perlin_cell(cy), bz0 = perlin_cell(cz);
    int bx1 = bx0 + 1, by1 = by0 + 1, bz1 = bz0 + 1;
    int i = PERLIN_P(bx0), j = PERLIN_P(bx1);
    int b00 = PERLIN_P(i + by0), b10 = PERLIN_P(j + by0);
    int b01 = PERLIN_P(i + by1), b11 = PERLIN_P(j + by1);
    float sx = rx0 * rx0 * (3 - 2 * rx0);
    float sy = ry0 * ry0 * (3 - 2 * ry0);
    float sz = rz0 * rz0 * (3 - 2 * rz0);
#define PATINA_AT(b, rx, ry, rz) \
    ((rx) * perlin_g[3 * ((b) & 255)] + (ry) * perlin_g[3 * ((b) & 255) + 1] \
        + (rz) * perlin_g[3 * ((b) & 255) + 2])
    float a = perlin_lerp(sx, PATINA_AT(b00 + bz0, rx0, ry0, rz0), PATINA_AT(b10 + bz0, rx1, ry0, rz0));
    float b = perlin_lerp(sx, PATINA_AT(b01 + bz0, rx0, ry1, rz0), PATINA_AT(b11 + bz0, rx1, ry1, rz0));
    float c = perlin_lerp(sy, a, b);
    a = perlin_lerp(sx, PATINA_AT(b00 + bz1, rx0, ry0, rz1), PATINA_AT(b10 + bz1, rx1, ry0, rz1));
    b = perlin_lerp(sx, PATINA_AT(b01 + bz1, rx0, ry1, rz1), PATINA_AT(b11 + bz1, rx1, ry1, rz1));
    float d = perlin_lerp(sy, a, b);
#undef PATINA_AT
    return 1.5 * perlin_lerp(sz, c, d);
}

// ---- Vector noise: Musgrave's VecNoise (T&M L10370-10380): three signed improved noises,
// snoise3 at p, at p + (3.33, 3.33, 3.33) and at p + (7.77, 7.77, 7.77) (Musgrave's offsets;
// fractional, so the three lattices' zeros do not coincide). Each component in [-1, 1]. The
// offsets are added after the cell is split off (the fraction gets 0.33 or 0.77 and carries into
// the integer cell index), so large coordinates lose nothing to them.
// sweep: fx in [0, 1]; fy in [0, 1]; fz in [0, 1]; of in [0, 1] (fractions within the cell, and the fractional offset)
float perlin_improved_offset(float cx, cy, cz, fx, fy, fz; int oi; float of)
{
    float gx = fx + of, gy = fy + of, gz = fz + of;
    int X = perlin_cell(cx) + oi + (gx >= 1 ? 1 : 0);
    int Y = perlin_cell(cy) + oi + (gy >= 1 ? 1 : 0);
    int Z = perlin_cell(cz) + oi + (gz >= 1 ? 1 : 0);
    gx = gx >= 1 ? gx - 1 : gx;
    gy = gy >= 1 ? gy - 1 : gy;
    gz = gz >= 1 ? gz - 1 : gz;
    return perlin_improved_cell(X, Y, Z, gx, gy, gz);
}

vector vsnoise3(point p)
{
    float cx = floor(p[0]), cy = floor(p[1]), cz = floor(p[2]);
    float fx = p[0] - cx, fy = p[1] - cy, fz = p[2] - cz;
    int X = perlin_cell(cx), Y = perlin_cell(cy), Z = perlin_cell(cz);
    return PATINA_SNOISE_SCALE * vector(
        perlin_improved_cell(X, Y, Z, fx, fy, fz),
        perlin_improved_offset(cx, cy, cz, fx, fy, fz, 3, 0.33),
        perlin_improved_offset(cx, cy, cz, fx, fy, fz, 7, 0.77));
}

// ---- The analytic gradient of snoise3: PATINA_SNOISE_SCALE times the gradient of improved
// noise, in closed form. With corner values a_ijk = G_ijk . (offset from corner ijk) and
// u = fade(x), ...: d/dx = fade'(x) * lerp(w, lerp(v, a100 - a000, a110 - a010),
// lerp(v, a101 - a001, a111 - a011)) + the trilinear blend (weights u, v, w) of the corner
// gradients' x components, and likewise for y and z. Finite for every finite input; each
// component is at most 0.9649 * (3 * 1.875 + 2) in magnitude (fade' <= 1.875).
vector dsnoise3(point p)
{
    constant int perlin_p2[256] = PATINA_PERLIN_PAIRS;
    float cx = floor(p[0]), cy = floor(p[1]), cz = floor(p[2]);
    float x = p[0] - cx, y = p[1] - cy, z = p[2] - cz;
    int X = perlin_cell(cx), Y = perlin_cell(cy), Z = perlin_cell(cz);
    float u = perlin_fade(x), v = perlin_fade(y), w = perlin_fade(z);
    float du = perlin_dfade(x), dv = perlin_dfade(y), dw = perlin_dfade(z);
    PERLIN_CORNER_PAIRS(X, Y, Z);
    int h000 = PERLIN_LO(hAA), h100 = PERLIN_LO(hBA), h010 = PERLIN_LO(hAB);
    int h110 = PERLIN_LO(hBB), h001 = PERLIN_HI(hAA), h101 = PERLIN_HI(hBA);
    int h011 = PERLIN_HI(hAB), h111 = PERLIN_HI(hBB);
    float a000 = perlin_grad(h000, x, y, z), a100 = perlin_grad(h100, x - 1, y, z);
    float a010 = perlin_grad(h010, x, y - 1, z), a110 = perlin_grad(h110, x - 1, y - 1, z);
    float a001 = perlin_grad(h001, x, y, z - 1), a101 = perlin_grad(h101, x - 1, y, z - 1);
    float a011 = perlin_grad(h011, x, y - 1, z - 1), a111 = perlin_grad(h111, x - 1, y - 1, z - 1);
    // The corner gradients themselves: perlin_grad is linear in the offset.
#define PATINA_GV(h) vector(perlin_grad(h, 1, 0, 0), perlin_grad(h, 0, 1, 0), perlin_grad(h, 0, 0, 1))
    vector g = perlin_vlerp(w,
        perlin_vlerp(v, perlin_vlerp(u, PATINA_GV(h000), PATINA_GV(h100)),
                        perlin_vlerp(u, PATINA_GV(h010), PATINA_GV(h110))),
        perlin_vlerp(v, perlin_vlerp(u, PATINA_GV(h001), PATINA_GV(h101)),
                        perlin_vlerp(u, PATINA_GV(h011), PATINA_GV(h111))));
#undef PATINA_GV
    float gx = du * perlin_lerp(w, perlin_lerp(v, a100 - a000, a110 - a010),
                                   perlin_lerp(v, a101 - a001, a111 - a011));
    float gy = dv * perlin_lerp(w, perlin_lerp(u, a010 - a000, a110 - a100),
                                   perlin_lerp(u, a011 - a001, a111 - a101));
    float gz = dw * perlin_lerp(v, perlin_lerp(u, a001 - a000, a101 - a100),
                                   perlin_lerp(u, a011 - a010, a111 - a110));
    return PATINA_SNOISE_SCALE * (vector(gx, gy, gz) + g);
}

// ---- Flow noise (Perlin & Neyret 2001; T&M L9286-9304): improved noise whose lattice gradients
// rotate by `angle`. Each of the 12 gradients G = s_u e_u + s_v e_v (perlin_grad: two non-zero
// axes u, v) turns in its own (u, v) plane: G(angle) = cos(angle) G + sin(angle) P with
// P = s_u e_v - s_v e_u (G turned by 90 degrees), the sense reversed where hash bit 4 is set, so
// neighbouring gradients spin both ways. Lengths stay sqrt(2), so it is still a gradient noise:
// 0 at the lattice points, C2 in p, and at angle 0 exactly snoise3. Smooth and 2 pi-periodic in
// angle: the angle is reduced to [0, 2 pi] (angle - 2 pi floor(angle / 2 pi), clamped) before
// sin and cos, so any finite angle works. Scaled by PATINA_SNOISE_SCALE and clamped to [-1, 1]:
// the bound for any rotation is 1.0385 (0.9649 * 1.0385 = 1.002), so the clamp acts at most in
// a band of 0.002 near the extremes (never in the tests' samples).
// sweep: x in [-1, 1]; y in [-1, 1]; z in [-1, 1]; c in [-1, 1]; s in [-1, 1] (offsets from a corner, and the angle's cosine and sine)
float perlin_flow_grad(int hash; float x, y, z, c, s)
{
    int h = hash & 15;
    float u = h < 8 ? x : y;
    float v = h < 4 ? y : ((h == 12 || h == 14) ? x : z);
    float gd = ((h & 1) == 0 ? u : -u) + ((h & 2) == 0 ? v : -v);
    float pd = ((h & 1) == 0 ? v : -v) - ((h & 2) == 0 ? u : -u);
    return c * gd + ((hash & 16) == 0 ? s : -s) * pd;
}

float flownoise3(point p; float angle)
{
    constant int perlin_p2[256] = PATINA_PERLIN_PAIRS;
    float a = clamp(angle - 6.283185307179586 * floor(angle * 0.15915494309189535),
                    0, 6.283185307179586);
    float c = cos(a), s = sin(a);
    float cx = floor(p[0]), cy = floor(p[1]), cz = floor(p[2]);
    float x = p[0] - cx, y = p[1] - cy, z = p[2] - cz;
    int X = perlin_cell(cx), Y = perlin_cell(cy), Z = perlin_cell(cz);
    float u = perlin_fade(x), v = perlin_fade(y), w = perlin_fade(z);
    PERLIN_CORNER_PAIRS(X, Y, Z);
    return clamp(PATINA_SNOISE_SCALE * perlin_lerp(w,
        perlin_lerp(v,
            perlin_lerp(u, perlin_flow_grad(PERLIN_LO(hAA), x, y, z, c, s),
                           perlin_flow_grad(PERLIN_LO(hBA), x - 1, y, z, c, s)),
            perlin_lerp(u, perlin_flow_grad(PERLIN_LO(hAB), x, y - 1, z, c, s),
                           perlin_flow_grad(PERLIN_LO(hBB), x - 1, y - 1, z, c, s))),
        perlin_lerp(v,
            perlin_lerp(u, perlin_flow_grad(PERLIN_HI(hAA), x, y, z - 1, c, s),
                           perlin_flow_grad(PERLIN_HI(hBA), x - 1, y, z - 1, c, s)),
            perlin_lerp(u, perlin_flow_grad(PERLIN_HI(hAB), x, y - 1, z - 1, c, s),
                           perlin_flow_grad(PERLIN_HI(hBB), x - 1, y - 1, z - 1, c, s)))),
        -1, 1);
}

#undef PERLIN_P
#undef PERLIN_P2
#undef PERLIN_LO
#undef PERLIN_HI
#undef PERLIN_CORNER_PAIRS

#endif
