// The built-in functions written in the language: RenderMan's `noise`, `snoise`, `pnoise` and
// `cellnoise` in every overload of docs/builtins.md, the light sums `diffuse`, `specular`,
// `phong` and the one-light `specularbrdf`, `ctransform` and the colour casts, and the geometry
// and matrix built-ins `faceforward`, `distance`, `reflect`, `refract`, `ptlined`, `rotate`, `translate`, `scale`,
// `determinant` and `fresnel`
// (`__fresnel_void`: a built-in's `output` arguments are written back as a user function's are).
// The semantic stage inlines `__NAME_RESULT`
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

// Colour spaces: `ctransform` and the casts `color "space" (a, b, c)` (the semantic stage inlines
// _patina_to_rgb for a cast), every conversion through linear RGB. The spaces are RenderMan's
// (RI 3.2, section 11.1 and 15.3): "rgb"; "hsv" and "hsl" (Smith 1978; Foley and van Dam, section
// 13.3), hue a fraction of the full circle (0 red, 1/3 green, 2/3 blue; it wraps); "xyz" = "XYZ",
// CIE XYZ of linear RGB with the Rec. 709 primaries and the D65 white (no transfer curve: shading
// colours are linear); "xyY", chromaticity and luminance of the same XYZ; "YIQ", NTSC luminance
// and chrominance (Foley and van Dam, eq. 13.36).
//
// A space name given as a literal decides the `if`s below when the call is inlined, so a shader
// runs only its own conversion; a name known only to the backends (a string parameter's value)
// is decided by them, or by binding. The piecewise parts (hue sextants, black, grey) are selects,
// both sides computed. The matrices are exact in f64: RGB to XYZ derived from the chromaticities
// (x / y, 1, (1 - x - y) / y per primary, scaled so that RGB white is D65 with Y = 1), the
// inverses by the adjugate, written out with every digit; docs/stdlib/color.md has the checks.

#define PATINA_ROW(a, b, c, v) ((a) * (v)[0] + (b) * (v)[1] + (c) * (v)[2])

color _patina_rgb_to_xyz(color c)
{
    return color(PATINA_ROW(0.4123907992659593, 0.357584339383878, 0.1804807884018343, c),
                 PATINA_ROW(0.21263900587151024, 0.715168678767756, 0.07219231536073371, c),
                 PATINA_ROW(0.01933081871559182, 0.11919477979462598, 0.9505321522496607, c));
}

color _patina_xyz_to_rgb(color c)
{
    return color(PATINA_ROW(3.2409699419045226, -1.537383177570094, -0.49861076029300344, c),
                 PATINA_ROW(-0.9692436362808796, 1.8759675015077204, 0.0415550574071756, c),
                 PATINA_ROW(0.05563007969699363, -0.2039769588889765, 1.0569715142428784, c));
}

// YIQ's I and Q rows sum to zero, so greys have no chrominance; the inverse is the exact inverse
// of this matrix rather than a published table, so that a round trip is exact up to rounding.
color _patina_rgb_to_yiq(color c)
{
    return color(PATINA_ROW(0.299, 0.587, 0.114, c), PATINA_ROW(0.596, -0.275, -0.321, c),
                 PATINA_ROW(0.212, -0.523, 0.311, c));
}

color _patina_yiq_to_rgb(color c)
{
    return color(PATINA_ROW(1.0000000000000002, 0.9556880603611568, 0.6198580944563707, c),
                 PATINA_ROW(1.0, -0.27158179694405865, -0.6468738161384013, c),
                 PATINA_ROW(1.0, -1.108177326682662, 1.7050645599191816, c));
}

// The hue (in turns, in [0, 1); 0 for greys), the largest and smallest channel and the chroma
// (their difference) of an RGB colour. The hue is the sextant pair of the largest channel:
// (g - b) / C near red, 2 + (b - r) / C near green, 4 + (r - g) / C near blue; red wins ties,
// then green. A grey's divisions give NaN, which the last select leaves out.
void _patina_hue_of(color c; output float hue; output float top; output float bottom;
                    output float chroma)
{
    float r = c[0], g = c[1], b = c[2];
    top = max(max(r, g), b);
    bottom = min(min(r, g), b);
    chroma = top - bottom;
    float near_r = (g - b) / chroma + 0, near_g = (b - r) / chroma + 2, near_b = (r - g) / chroma + 4;
    float h = top == r ? near_r : (top == g ? near_g : near_b);
    h = mod(h, 6) / 6;
    hue = chroma > 0 ? h : 0;
}

// One channel from a hue: top - chroma * clamp(min(k, 4 - k), 0, 1) with k = (6 h + n) mod 6 and
// n = 5, 3, 1 for red, green, blue: the hexcone's six sextants as one piecewise-linear ramp.
float _patina_hue_channel(float h6, n, top, chroma)
{
    float k = mod(h6 + n, 6);
    return top - chroma * clamp(min(k, 4 - k), 0, 1);
}

color _patina_rgb_of_hue(float hue, top, chroma)
{
    float h6 = hue * 6;
    return color(_patina_hue_channel(h6, 5, top, chroma), _patina_hue_channel(h6, 3, top, chroma),
                 _patina_hue_channel(h6, 1, top, chroma));
}

color _patina_hsv_to_rgb(color c)
{
    return _patina_rgb_of_hue(c[0], c[2], c[2] * c[1]);
}

// Chroma (1 - |2L - 1|) S; the largest channel is L + chroma / 2.
color _patina_hsl_to_rgb(color c)
{
    float l = c[2];
    float chroma = (1 - abs(2 * l - 1)) * c[1];
    return _patina_rgb_of_hue(c[0], l + chroma * 0.5, chroma);
}

color _patina_rgb_to_hsv(color c)
{
    float hue, top, bottom, chroma;
    _patina_hue_of(c, hue, top, bottom, chroma);
    return color(hue, top != 0 ? chroma / top : 0, top);
}

// S = chroma / (1 - |2L - 1|), 0 where the denominator vanishes (black, white).
color _patina_rgb_to_hsl(color c)
{
    float hue, top, bottom, chroma;
    _patina_hue_of(c, hue, top, bottom, chroma);
    float sum = top + bottom;
    float spread = 1 - abs(sum - 1);
    return color(hue, spread != 0 ? chroma / spread : 0, sum * 0.5);
}

// (x, y, Y) to (X, Y, Z): X = x Y / y, Z = (1 - x - y) Y / y; 0 where y is 0.
color _patina_xyy_to_rgb(color c)
{
    float x = c[0], y = c[1], lum = c[2];
    float scale = lum / y;
    float big_x = x * scale, big_z = (1 - x - y) * scale;
    return _patina_xyz_to_rgb(color(y != 0 ? big_x : 0, lum, y != 0 ? big_z : 0));
}

// x = X / (X + Y + Z), y = Y / (X + Y + Z); black has no chromaticity and gets the white point's
// (D65), so that converting it back gives black again.
color _patina_rgb_to_xyy(color c)
{
    color xyz = _patina_rgb_to_xyz(c);
    float sum = xyz[0] + xyz[1] + xyz[2];
    float x = xyz[0] / sum, y = xyz[1] / sum;
    return color(sum != 0 ? x : 0.3127, sum != 0 ? y : 0.3290, xyz[1]);
}

color _patina_to_rgb(string space; color c)
{
    color rgb = c;
    if (space == "hsv")
        rgb = _patina_hsv_to_rgb(c);
    else if (space == "hsl")
        rgb = _patina_hsl_to_rgb(c);
    else if (space == "xyz" || space == "XYZ")
        rgb = _patina_xyz_to_rgb(c);
    else if (space == "xyY")
        rgb = _patina_xyy_to_rgb(c);
    else if (space == "YIQ")
        rgb = _patina_yiq_to_rgb(c);
    return rgb;
}

color _patina_from_rgb(string space; color rgb)
{
    color c = rgb;
    if (space == "hsv")
        c = _patina_rgb_to_hsv(rgb);
    else if (space == "hsl")
        c = _patina_rgb_to_hsl(rgb);
    else if (space == "xyz" || space == "XYZ")
        c = _patina_rgb_to_xyz(rgb);
    else if (space == "xyY")
        c = _patina_rgb_to_xyy(rgb);
    else if (space == "YIQ")
        c = _patina_rgb_to_yiq(rgb);
    return c;
}

// From `from` through RGB to `to`; within one space (xyz and XYZ are one) no conversion, which
// would only add rounding.
color __ctransform_color(string from, to; color c)
{
    __colour_space(from);
    __colour_space(to);
    color result;
    if (from == to || (from == "xyz" && to == "XYZ") || (from == "XYZ" && to == "xyz"))
        result = c;
    else
        result = _patina_from_rgb(to, _patina_to_rgb(from, c));
    return result;
}

color __ctransform_color(string to; color c)
{
    return __ctransform_color("rgb", to, c);
}

// Angles (`radians`, `degrees`), geometry and matrices: `faceforward`, `distance`, `reflect`, `refract`, `ptlined`, `rotate` (of a point and of a matrix),
// `translate`, `scale`, `determinant` and `fresnel`. Each is written operation for operation as the interpreter computed
// it natively before it moved here, so that its bits stay the same (docs/numerics.md: exact on
// both backends): products and sums in the order written, sums left to right. `dot` is the
// built-in, never the `.` operator (which the GPU backend hands to WGSL's `dot`, whose order of
// summation is the driver's). Matrices are row by row (`m[i][j]`, row i, column j) in RenderMan's
// row-vector convention, points transformed as `(p, 1) m`.

// Angles: one product by pi / 180 or 180 / pi, the f64 constants written here (rounded once more
// to f32 where the program runs in f32), as both backends computed them natively.
float __radians_float(float angle)
{
    return angle * 0.017453292519943295;
}

float __degrees_float(float angle)
{
    return angle * 57.29577951308232;
}

// N turned to face against I: N where I and the reference normal Nref point opposite ways
// (dot(I, Nref) < 0), else -N, WGSL's `faceForward`. The semantic stage passes the geometric normal
// Ng as Nref to a two-argument call where the shader has one; elsewhere Nref is N itself.
normal __faceforward_normal(normal N; vector I; normal Nref)
{
    return dot(I, Nref) < 0 ? N : -N;
}

normal __faceforward_normal(normal N; vector I)
{
    return __faceforward_normal(N, I, N);
}

vector __faceforward_vector(vector N; vector I; vector Nref)
{
    return dot(I, Nref) < 0 ? N : -N;
}

vector __faceforward_vector(vector N; vector I)
{
    return __faceforward_vector(N, I, N);
}

// The distance between two points: the length of their difference.
float __distance_float(point a, b)
{
    return length(a - b);
}

// The reflection of I about N: I - 2 (N . I) N, WGSL's `reflect` (RI spec 3.2 section 15.3).
vector __reflect_vector(vector I; normal N)
{
    vector n = N;
    return I - (2 * dot(n, I)) * n;
}

// The refraction of I through a surface of normal N for the ratio of indices `eta`, WGSL's
// `refract`: with d = N . I and k = 1 - eta^2 (1 - d^2), eta I - (eta d + sqrt(k)) N, and 0 under
// total internal reflection (k < 0). Neither I nor N is normalized here.
vector __refract_vector(vector I; normal N; float eta)
{
    vector n = N;
    float d = dot(n, I);
    float k = 1 - eta * eta * (1 - d * d);
    vector r = eta * I - (eta * d + sqrt(k)) * n;
    return k < 0 ? vector(0) : r;
}

// The distance from q to the segment from a to b: to the nearest point a + t (b - a), with t
// clamped to [0, 1] (a point segment, whose t is 0/0 = NaN, clamps to a).
float __ptlined_float(point a, b, q)
{
    vector d = b - a, w = q - a;
    float t = clamp(dot(w, d) / dot(d, d), 0, 1);
    return length(w - d * t);
}

// The 3x3 rotation by `angle` radians about `axis` (normalized here), for row vectors, as its three
// columns: v R = v cos + (k x v) sin + k (k . v)(1 - cos) (Rodrigues), the matrix of RiRotate,
// which about +z turns +x towards +y. Entry (i, j) is ((1 - cos) k_i) k_j, plus cos on the
// diagonal, plus sin k_m at (0, 1), (1, 2) and (2, 0) and minus it at (1, 0), (2, 1) and (0, 2),
// m being the third index.
void _patina_rotation(float angle; vector axis; output vector c0, c1, c2)
{
    vector k = normalize(axis);
    float c = cos(angle), s = sin(angle);
    float t = 1 - c;
    float k0 = k[0], k1 = k[1], k2 = k[2];
    c0 = vector(t * k0 * k0 + c, t * k1 * k0 - s * k2, t * k2 * k0 + s * k1);
    c1 = vector(t * k0 * k1 + s * k2, t * k1 * k1 + c, t * k2 * k1 - s * k0);
    c2 = vector(t * k0 * k2 - s * k1, t * k1 * k2 + s * k0, t * k2 * k2 + c);
}

// The point q turned about the axis through p0 and p1: (q - p0) R + p0.
point __rotate_point(point q; float angle; point p0, p1)
{
    vector c0, c1, c2;
    _patina_rotation(angle, p1 - p0, c0, c1, c2);
    vector v = q - p0;
    return point(dot(v, c0), dot(v, c1), dot(v, c2)) + p0;
}

// Row i of m without its last column, times the rotation's columns; the last column unchanged.
#define PATINA_ROTATED_ROW(m, i) \
    dot(vector((m)[i][0], (m)[i][1], (m)[i][2]), c0), \
    dot(vector((m)[i][0], (m)[i][1], (m)[i][2]), c1), \
    dot(vector((m)[i][0], (m)[i][1], (m)[i][2]), c2), (m)[i][3]

// The matrix builders postconcatenate (RI 3.2, section 15.4): the result is m T, so that
// transform(translate(m, t), p) = transform(m, p) + t.
matrix __rotate_matrix(matrix m; float angle; vector axis)
{
    vector c0, c1, c2;
    _patina_rotation(angle, axis, c0, c1, c2);
    return matrix(PATINA_ROTATED_ROW(m, 0), PATINA_ROTATED_ROW(m, 1), PATINA_ROTATED_ROW(m, 2),
                  PATINA_ROTATED_ROW(m, 3));
}

// (m T)[i][j] = m[i][j] + m[i][3] t[j], the last column unchanged.
#define PATINA_TRANSLATED_ROW(m, i, t) \
    (m)[i][0] + (m)[i][3] * (t)[0], (m)[i][1] + (m)[i][3] * (t)[1], \
    (m)[i][2] + (m)[i][3] * (t)[2], (m)[i][3]

matrix __translate_matrix(matrix m; vector t)
{
    return matrix(PATINA_TRANSLATED_ROW(m, 0, t), PATINA_TRANSLATED_ROW(m, 1, t),
                  PATINA_TRANSLATED_ROW(m, 2, t), PATINA_TRANSLATED_ROW(m, 3, t));
}

// (m S)[i][j] = m[i][j] s[j], the last column unchanged.
#define PATINA_SCALED_ROW(m, i, s) \
    (m)[i][0] * (s)[0], (m)[i][1] * (s)[1], (m)[i][2] * (s)[2], (m)[i][3]

matrix __scale_matrix(matrix m; point s)
{
    return matrix(PATINA_SCALED_ROW(m, 0, s), PATINA_SCALED_ROW(m, 1, s), PATINA_SCALED_ROW(m, 2, s),
                  PATINA_SCALED_ROW(m, 3, s));
}

// The determinant of the 3x3 matrix of rows a, b, c, by Laplace expansion along the first row:
// each 2x2 minor as x_0 y_1 - x_1 y_0, the signed terms summed left to right (the order in which
// the backends' `invert` still computes its minors).
float _patina_det3(vector a, b, c)
{
    return a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
           + a[2] * (b[0] * c[1] - b[1] * c[0]);
}

// The minor of m's first row and column j: rows 1 to 3, the columns x < y < z other than j.
#define PATINA_MINOR(m, x, y, z) \
    _patina_det3(vector((m)[1][x], (m)[1][y], (m)[1][z]), vector((m)[2][x], (m)[2][y], (m)[2][z]), \
                 vector((m)[3][x], (m)[3][y], (m)[3][z]))

// By Laplace expansion along the first row, as `_patina_det3`.
float __determinant_float(matrix m)
{
    return m[0][0] * PATINA_MINOR(m, 1, 2, 3) - m[0][1] * PATINA_MINOR(m, 0, 2, 3)
           + m[0][2] * PATINA_MINOR(m, 0, 1, 3) - m[0][3] * PATINA_MINOR(m, 0, 1, 2);
}

// The Fresnel reflectance of a dielectric for unpolarized light, Kr = (rs^2 + rp^2) / 2, with
// `eta` the ratio of the index on the side of I to the index of the side entered (as for
// `refract`), and Kt = 1 - Kr; under total internal reflection Kr = 1 and Kt = 0. The angle comes
// from I and N normalized, its cosine taken as positive whichever way N faces; Snell's law gives
// sin_t^2 = eta^2 (1 - cos_i^2), and rs = (eta cos_i - cos_t) / (eta cos_i + cos_t),
// rp = (cos_i - eta cos_t) / (cos_i + eta cos_t).
void __fresnel_void(vector I; normal N; float eta; output float Kr, Kt)
{
    float cos_i = abs(dot(normalize(I), normalize(N)));
    float sin_t2 = eta * eta * (1 - cos_i * cos_i);
    float cos_t = sqrt(max(1 - sin_t2, 0));
    float eta_cos_i = eta * cos_i, eta_cos_t = eta * cos_t;
    float rs = (eta_cos_i - cos_t) / (eta_cos_i + cos_t);
    float rp = (cos_i - eta_cos_t) / (cos_i + eta_cos_t);
    Kr = sin_t2 > 1 ? 1 : (rs * rs + rp * rp) * 0.5;
    Kt = 1 - Kr;
}

// With the reflected and refracted directions: reflect(I, N) and refract(I, N, eta).
void __fresnel_void(vector I; normal N; float eta; output float Kr, Kt; output vector R, T)
{
    __fresnel_void(I, N, eta, Kr, Kt);
    R = reflect(I, N);
    T = refract(I, N, eta);
}
