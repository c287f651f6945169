// compiler/stdlib/lattice.sl: integer lattice hashes and Peachey's lattice noises (value noise, gradient
// noise, value-gradient noise, lattice convolution noise, sparse convolution noise).
// See docs/stdlib/lattice.md for formulas, sources, errata decisions and measured precision.
//
// Sources: Peachey, "Building Procedural Textures", T&M 3rd ed. ch. 2
// (shared/seeds/002_a44091d2843c02ac.txt): lattice hashing L2207-2244, value noise L2246-2332,
// gradient noise L2334-2483, value-gradient noise L2485-2493, lattice convolution noise
// L2495-2577, sparse convolution noise L2579-2658. The hash is PCG's (O'Neill 2014) in the form
// Jarzynski and Olano recommend for GPUs ("Hash Functions for GPU Rendering", JCGT 9(3), 2020:
// `pcg`, nested for several dimensions).
//
// Every function here uses only u32/i32 integer arithmetic, + - * /, floor, sqrt, comparisons and
// selections, which the interpreter and the GPU compute identically, except gnoise and vgnoise,
// whose gradient directions use sin and cos (measured GPU difference in docs/stdlib/lattice.md).
// The cell is split off with floor before any arithmetic on the fraction, and the integer cell
// wraps with period 2^32 (lattice_cell), so every finite input gives a finite result and the
// accuracy at large coordinates is limited only by the coordinate's own rounding.

#ifndef PATINA_LATTICE_SL
#define PATINA_LATTICE_SL

// ---------------------------------------------------------------------------------------------
// Hashes

// PCG's RXS-M-XS output permutation of a u32 (Jarzynski & Olano 2020, `pcg`): one step of the
// LCG state = v * 747796405 + 2891336453 (O'Neill's 32-bit multiplier and increment), then a
// random xorshift by 4 + (state >> 28), a multiply by 277803737 and a final xorshift by 22.
// A bijection of the 2^32 values; every operation wraps and is exact on both backends.
uint lattice_pcg(uint v)
{
    uint state = v * 747796405u + 2891336453u;
    uint word = ((state >> ((state >> 28u) + 4u)) ^ state) * 277803737u;
    return (word >> 22u) ^ word;
}

// The integer lattice coordinate of a float that is already an integer (a floor): int(c) for
// |c| < 2^31, otherwise c modulo 2^32 taken into [-2^31, 2^31) (exact: c is then a multiple of
// its ulp, which divides 2^32 up to 2^56; above that c mod 2^32 is 0). So the lattice repeats
// with period 2^32 and every finite c has a cell. (A plain int(c) saturates beyond 2^31: every
// cell there would be the same one.)
int lattice_cell(float c)
{
    float w = c - 4294967296.0 * floor(c * 2.3283064365386963e-10);
    w = w >= 2147483648.0 ? w - 4294967296.0 : w;
    return abs(c) < 2147483648.0 ? int(c) : int(w);
}

// The nested PCG hash of 1 to 4 lattice coordinates and a seed:
// pcg(x + pcg(y + pcg(z + pcg(w + pcg(seed))))) with the coordinates' bits read as u32
// (Jarzynski & Olano's nesting; Perlin's P[P[P[x] + y] + z] with a permutation of 2^32 values
// instead of 256, so the period is 2^32 on every axis instead of Peachey's 256, L2207).
uint lattice_hash1(int x; int seed)
{
    return lattice_pcg(uint(x) + lattice_pcg(uint(seed)));
}

uint lattice_hash2(int x, y; int seed)
{
    return lattice_pcg(uint(x) + lattice_pcg(uint(y) + lattice_pcg(uint(seed))));
}

uint lattice_hash3(int x, y, z; int seed)
{
    return lattice_pcg(uint(x) + lattice_pcg(uint(y) + lattice_pcg(uint(z) + lattice_pcg(uint(seed)))));
}

uint lattice_hash4(int x, y, z, w; int seed)
{
    return lattice_pcg(uint(x) + lattice_pcg(uint(y) + lattice_pcg(uint(z)
        + lattice_pcg(uint(w) + lattice_pcg(uint(seed))))));
}

// A hash to a float in [0, 1): the top 24 bits times 2^-24, exact in f32 (every value k / 2^24).
float lattice_unit(uint h)
{
    return float(h >> 8u) * 5.9604644775390625e-8;
}

// A hash to a float in (-1, 1), symmetric about 0: (2k + 1) / 2^23 - 1 for the top 23 bits k,
// exact in f32. The lattice values of the value noises (Peachey's valueTab, L2256-2264).
float lattice_signed(uint h)
{
    return (float(h >> 9u) + 0.5) * 2.384185791015625e-7 - 1;
}

// Worley's LCG step (T&M L4302): seed * 1402024253 + 586950981 modulo 2^32. Used to draw several
// numbers from one cell hash; only the high bits are used (the low bits of an LCG are poor).
uint lattice_lcg(uint s)
{
    return s * 1402024253u + 586950981u;
}

// A hash to a float in (0, 1), never 0 or 1: ((h >> 9) + 0.5) / 2^23, exact in f32.
float lattice_open_unit(uint h)
{
    return (float(h >> 9u) + 0.5) * 1.1920928955078125e-7;
}

// ---------------------------------------------------------------------------------------------
// Interpolation kernels

// The Catmull-Rom cubic through k0..k3 on the span k1..k2, t in [0, 1]: Peachey's spline
// (L1390-1440) specialised to four knots as L2326 suggests, with his basis coefficients
// (CR00..CR33) and Horner's rule. t = 0 gives k1, t = 1 gives k2; C1 across spans.
// sweep: t in [0, 1]
float lattice_catrom4(float t, k0, k1, k2, k3)
{
    float c3 = -0.5 * k0 + 1.5 * k1 - 1.5 * k2 + 0.5 * k3;
    float c2 = k0 - 2.5 * k1 + 2 * k2 - 0.5 * k3;
    float c1 = -0.5 * k0 + 0.5 * k2;
    return ((c3 * t + c2) * t + c1) * t + k1;
}

// a + t (b - a): Peachey's LERP (L2431).
// sweep: t in [0, 1] (the fraction between two knots)
float lattice_lerp(float t, a, b)
{
    return a + t * (b - a);
}

// The radial Catmull-Rom filter of radius 2 as a function of the squared distance d2
// (Peachey's catrom2, L2505-2530): with x = sqrt(d2), 1 - 2.5 x^2 + 1.5 x^3 for x < 1,
// 2 - 4 x + 2.5 x^2 - 0.5 x^3 for 1 <= x < 2, 0 beyond (each in the printed Horner form).
// Erratum decision (catalogue H-P10): evaluated exactly, not read from a 401-entry table at the
// nearest entry, so the noises built on it are C1 instead of piecewise constant in d2. The inner
// branch uses d2 for x^2 (more accurate, and the same on the GPU, which folds sqrt(d2) * sqrt(d2)
// into d2 where the interpreter rounds the product).
float lattice_catrom2(float d2)
{
    float x = sqrt(max(d2, 0));
    float inner = 0.5 * (2 + d2 * (-5 + x * 3));
    float outer = 0.5 * (4 + x * (-8 + x * (5 - x)));
    return d2 >= 4 ? 0 : (x < 1 ? inner : outer);
}

// ---------------------------------------------------------------------------------------------
// Value noise (Peachey L2246-2332)

// Peachey's value noise vnoise: the lattice values lattice_signed(lattice_hash3(ix, iy, iz, seed))
// interpolated by Catmull-Rom cubics in x, then y, then z over the 4 x 4 x 4 lattice points
// around p (L2288-2322). C1 (the Catmull-Rom spline is C1; the text's "second derivative
// continuous", L2283, does not hold for Catmull-Rom). Equal to the lattice value at lattice
// points. Range: |vnoise| < 1.25^3 = 1.953 (the bound of the Catmull-Rom weights); in practice
// most values lie within [-1, 1].
float vnoise(point p; int seed)
{
    float cx = floor(p[0]), cy = floor(p[1]), cz = floor(p[2]);
    float fx = p[0] - cx, fy = p[1] - cy, fz = p[2] - cz;
    int ix = lattice_cell(cx), iy = lattice_cell(cy), iz = lattice_cell(cz);
    uint s = lattice_pcg(uint(seed));
    float zk[4], yk[4];
    constant int j, k;
    for (k = 0; k < 4; k += 1) {
        uint hz = lattice_pcg(uint(iz + k - 1) + s);
        for (j = 0; j < 4; j += 1) {
            uint hy = lattice_pcg(uint(iy + j - 1) + hz);
            yk[j] = lattice_catrom4(fx,
                lattice_signed(lattice_pcg(uint(ix - 1) + hy)),
                lattice_signed(lattice_pcg(uint(ix) + hy)),
                lattice_signed(lattice_pcg(uint(ix + 1) + hy)),
                lattice_signed(lattice_pcg(uint(ix + 2) + hy)));
        }
        zk[k] = lattice_catrom4(fy, yk[0], yk[1], yk[2], yk[3]);
    }
    return lattice_catrom4(fz, zk[0], zk[1], zk[2], zk[3]);
}

// vnoise with Peachey's seed 665 (L2300).
float vnoise(point p)
{
    return vnoise(p, 665);
}

// Value noise with trilinear interpolation of the 8 corners' lattice values (the "linear
// interpolation" Peachey describes and rejects as boxy, L2283): C0, not C1; in [-1, 1].
float vnoise_linear(point p; int seed)
{
    float cx = floor(p[0]), cy = floor(p[1]), cz = floor(p[2]);
    float fx = p[0] - cx, fy = p[1] - cy, fz = p[2] - cz;
    int ix = lattice_cell(cx), iy = lattice_cell(cy), iz = lattice_cell(cz);
    uint s = lattice_pcg(uint(seed));
    uint hz0 = lattice_pcg(uint(iz) + s), hz1 = lattice_pcg(uint(iz + 1) + s);
    uint h00 = lattice_pcg(uint(iy) + hz0), h10 = lattice_pcg(uint(iy + 1) + hz0);
    uint h01 = lattice_pcg(uint(iy) + hz1), h11 = lattice_pcg(uint(iy + 1) + hz1);
    float v000 = lattice_signed(lattice_pcg(uint(ix) + h00));
    float v100 = lattice_signed(lattice_pcg(uint(ix + 1) + h00));
    float v010 = lattice_signed(lattice_pcg(uint(ix) + h10));
    float v110 = lattice_signed(lattice_pcg(uint(ix + 1) + h10));
    float v001 = lattice_signed(lattice_pcg(uint(ix) + h01));
    float v101 = lattice_signed(lattice_pcg(uint(ix + 1) + h01));
    float v011 = lattice_signed(lattice_pcg(uint(ix) + h11));
    float v111 = lattice_signed(lattice_pcg(uint(ix + 1) + h11));
    return lattice_lerp(fz,
        lattice_lerp(fy, lattice_lerp(fx, v000, v100), lattice_lerp(fx, v010, v110)),
        lattice_lerp(fy, lattice_lerp(fx, v001, v101), lattice_lerp(fx, v011, v111)));
}

float vnoise_linear(point p)
{
    return vnoise_linear(p, 665);
}

// ---------------------------------------------------------------------------------------------
// Gradient noise (Peachey L2334-2483), the gradient half of value-gradient noise

// The gradient of lattice point hash h dotted with the offset (x, y, z) from it. The gradient is
// uniform on the unit sphere (Peachey's gradientTabInit, L2350-2380): z = 1 - 2 u1,
// r = sqrt(1 - z^2), theta = 2 pi u2 - pi, g = (r cos theta, r sin theta, z), with u1, u2 the
// top 24 bits of pcg(h) and pcg(pcg(h)). Erratum decision (catalogue H-L7): the printed RANDNBR
// (random() & 0xffffffff) / 0xffffffff lies in [0, 0.5] for POSIX random(), which gives only
// z >= 0 and theta in [0, pi): a quarter sphere. The hash gives the whole sphere. (theta is
// taken in [-pi, pi) so that sin and cos stay where the GPU's are accurate.)
float lattice_glattice(uint h; float x, y, z)
{
    uint h1 = lattice_pcg(h);
    float gz = 1 - 2 * lattice_unit(h1);
    float r = sqrt(max(1 - gz * gz, 0));
    float theta = 6.283185307179586 * lattice_unit(lattice_pcg(h1)) - 3.141592653589793;
    return r * cos(theta) * x + r * sin(theta) * y + gz * z;
}

// Peachey's gradient noise gnoise (L2430-2481): the 8 corners' gradient terms blended by
// trilinear interpolation with the weights 3t^2 - 2t^3 (SMOOTHSTEP, L2430). 0 at every lattice
// point; C1 (the cubic's second derivative jumps across cell faces, catalogue H-L4); range within
// [-1, 1] (measured). Seed 665 by default as printed.
float gnoise(point p; int seed)
{
    float cx = floor(p[0]), cy = floor(p[1]), cz = floor(p[2]);
    float fx0 = p[0] - cx, fy0 = p[1] - cy, fz0 = p[2] - cz;
    float fx1 = fx0 - 1, fy1 = fy0 - 1, fz1 = fz0 - 1;
    float wx = fx0 * fx0 * (3 - 2 * fx0), wy = fy0 * fy0 * (3 - 2 * fy0), wz = fz0 * fz0 * (3 - 2 * fz0);
    int ix = lattice_cell(cx), iy = lattice_cell(cy), iz = lattice_cell(cz);
    uint s = lattice_pcg(uint(seed));
    uint hz0 = lattice_pcg(uint(iz) + s), hz1 = lattice_pcg(uint(iz + 1) + s);
    uint h00 = lattice_pcg(uint(iy) + hz0), h10 = lattice_pcg(uint(iy + 1) + hz0);
    uint h01 = lattice_pcg(uint(iy) + hz1), h11 = lattice_pcg(uint(iy + 1) + hz1);
    float vy0 = lattice_lerp(wx, lattice_glattice(lattice_pcg(uint(ix) + h00), fx0, fy0, fz0),
                                 lattice_glattice(lattice_pcg(uint(ix + 1) + h00), fx1, fy0, fz0));
    float vy1 = lattice_lerp(wx, lattice_glattice(lattice_pcg(uint(ix) + h10), fx0, fy1, fz0),
                                 lattice_glattice(lattice_pcg(uint(ix + 1) + h10), fx1, fy1, fz0));
    float vz0 = lattice_lerp(wy, vy0, vy1);
    vy0 = lattice_lerp(wx, lattice_glattice(lattice_pcg(uint(ix) + h01), fx0, fy0, fz1),
                           lattice_glattice(lattice_pcg(uint(ix + 1) + h01), fx1, fy0, fz1));
    vy1 = lattice_lerp(wx, lattice_glattice(lattice_pcg(uint(ix) + h11), fx0, fy1, fz1),
                           lattice_glattice(lattice_pcg(uint(ix + 1) + h11), fx1, fy1, fz1));
    float vz1 = lattice_lerp(wy, vy0, vy1);
    return lattice_lerp(wz, vz0, vz1);
}

float gnoise(point p)
{
    return gnoise(p, 665);
}

// Value-gradient noise, Peachey's simple form (L2489-2491): a weighted sum of value noise and
// gradient noise, (1 - w) gnoise(p) + w vnoise(p). The text gives no weights; w = 0.5 by
// default. The gradient half uses the stream seed + 1, so that the two halves are independent.
// The weight is clamped to [0, 1]. C1.
float vgnoise(point p; float w; int seed)
{
    float k = clamp(w, 0, 1);
    return (1 - k) * gnoise(p, seed + 1) + k * vnoise(p, seed);
}

float vgnoise(point p)
{
    return vgnoise(p, 0.5, 665);
}

// ---------------------------------------------------------------------------------------------
// Convolution noises (Peachey L2495-2658)

// Peachey's lattice convolution noise vcnoise (L2532-2575): the lattice values as impulses
// convolved with the radial Catmull-Rom filter of radius 2, over the 4 x 4 x 4 lattice points
// within reach: sum of lattice_signed(hash(ix + i, iy + j, iz + k)) catrom2(|(i, j, k) - f|^2).
// Not normalised (as printed). C1.
float vcnoise(point p; int seed)
{
    float cx = floor(p[0]), cy = floor(p[1]), cz = floor(p[2]);
    float fx = p[0] - cx, fy = p[1] - cy, fz = p[2] - cz;
    int ix = lattice_cell(cx), iy = lattice_cell(cy), iz = lattice_cell(cz);
    uint s = lattice_pcg(uint(seed));
    float sum = 0;
    constant int i, j, k;
    for (k = -1; k <= 2; k += 1) {
        uint hz = lattice_pcg(uint(iz + k) + s);
        float dz = k - fz;
        dz = dz * dz;
        for (j = -1; j <= 2; j += 1) {
            uint hy = lattice_pcg(uint(iy + j) + hz);
            float dy = j - fy;
            dy = dy * dy;
            for (i = -1; i <= 2; i += 1) {
                float dx = i - fx;
                dx = dx * dx;
                sum += lattice_signed(lattice_pcg(uint(ix + i) + hy)) * lattice_catrom2(dx + dy + dz);
            }
        }
    }
    return sum;
}

float vcnoise(point p)
{
    return vcnoise(p, 665);
}

// Peachey's sparse convolution noise (L2587-2658; printed as `snoise`, renamed scnoise as his
// text calls it, catalogue §3.6: RenderMan's snoise is signed noise). Three impulses per lattice
// cell (NIMPULSES, L2607) at positions (px, py, pz) in [0, 1)^3 with amplitudes a in (-1, 1),
// convolved with the radial Catmull-Rom filter over the 5 x 5 x 5 cells within reach:
// sum over cells and impulses of a catrom2(|f - ((i, j, k) + (px, py, pz))|^2), divided by 3.
// Each cell's impulses come from its hash h = lattice_hash3(cell, seed) by Worley's LCG steps
// (position x, y, z, amplitude, from the top bits of successive states). Erratum decisions:
// the printed table RANDNBR values lie in [0, 0.5] (catalogue H-L7), which puts every impulse in
// one octant of its cell with a positive amplitude; and the printed NEXT(h) makes neighbouring
// cells share impulses (h, h+1, h+2 of one 256-entry table). Here every cell has its own three
// impulses, uniform in the cell, with symmetric amplitudes. C1.
float scnoise(point p; int seed)
{
    float cx = floor(p[0]), cy = floor(p[1]), cz = floor(p[2]);
    float fx = p[0] - cx, fy = p[1] - cy, fz = p[2] - cz;
    int ix = lattice_cell(cx), iy = lattice_cell(cy), iz = lattice_cell(cz);
    uint s = lattice_pcg(uint(seed));
    float sum = 0;
    constant int i, j, k, n;
    for (k = -2; k <= 2; k += 1) {
        uint hz = lattice_pcg(uint(iz + k) + s);
        for (j = -2; j <= 2; j += 1) {
            uint hy = lattice_pcg(uint(iy + j) + hz);
            for (i = -2; i <= 2; i += 1) {
                uint h = lattice_pcg(uint(ix + i) + hy);
                for (n = 0; n < 3; n += 1) {
                    h = lattice_lcg(h);
                    float dx = fx - (i + lattice_unit(h));
                    h = lattice_lcg(h);
                    float dy = fy - (j + lattice_unit(h));
                    h = lattice_lcg(h);
                    float dz = fz - (k + lattice_unit(h));
                    h = lattice_lcg(h);
                    sum += lattice_catrom2(dx * dx + dy * dy + dz * dz) * lattice_signed(h);
                }
            }
        }
    }
    return sum / 3;
}

float scnoise(point p)
{
    return scnoise(p, 665);
}

#endif
