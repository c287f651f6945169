// compiler/stdlib/cellular.sl: RenderMan's cellnoise and Worley's cellular texture basis (F1-F4 with the
// feature points' positions and ids). See docs/stdlib/cellular.md.
//
// Sources: RenderMan Interface 3.2 (cellnoise: constant on each unit cell, in [0, 1)); Worley,
// "Cellular Texturing", T&M 3rd ed. ch. 4 (shared/seeds/002_a44091d2843c02ac.txt): definitions
// L3929-3944, the algorithm L3979-4034, the Poisson population table and its density
// L4034-4054 and L4122-4133, the reference code L4093-4380 (DENSITY_ADJUSTMENT L4138, the 27-cube
// search L4150-4255, AddSamples L4263-4380). Hashes and exact hash-to-float conversions come
// from lattice.sl, so the interpreter and the GPU agree bit for bit on cellnoise and on which
// feature points are found (only sqrt and + - * / on small numbers follow).

#ifndef PATINA_CELLULAR_SL
#define PATINA_CELLULAR_SL

#include <lattice.sl>

// ---------------------------------------------------------------------------------------------
// cellnoise

// RenderMan's cellnoise: lattice_unit(lattice_hashN(floor of the coordinates, seed)): constant on
// each unit cell [i, i + 1), a float k / 2^24 in [0, 1), uniform, independent between cells and
// between seeds. Cells wrap with period 2^32 (lattice_cell), so also large coordinates keep
// distinct cells up to 2^32. The RenderMan built-in `cellnoise` uses seeds 0, 1, 2 for the
// components of its vector results.
float cellnoise1(float x; int seed)
{
    return lattice_unit(lattice_hash1(lattice_cell(floor(x)), seed));
}

float cellnoise2(float x, y; int seed)
{
    return lattice_unit(lattice_hash2(lattice_cell(floor(x)), lattice_cell(floor(y)), seed));
}

float cellnoise3(point p; int seed)
{
    return lattice_unit(lattice_hash3(lattice_cell(floor(p[0])), lattice_cell(floor(p[1])),
        lattice_cell(floor(p[2])), seed));
}

float cellnoise4(point p; float w; int seed)
{
    return lattice_unit(lattice_hash4(lattice_cell(floor(p[0])), lattice_cell(floor(p[1])),
        lattice_cell(floor(p[2])), lattice_cell(floor(w)), seed));
}

// ---------------------------------------------------------------------------------------------
// Worley's cellular basis

// Worley's DENSITY_ADJUSTMENT 0.398150 (L4138), which makes the mean of F1 equal to 1, rounded to
// 26093 / 65536 = 0.3981475830078125 (relative change -6e-6) so that the scaling can be done in
// integer arithmetic (worley_cell, worley_frac).
#define WORLEY_DA 0.3981475830078125
#define WORLEY_DA_NUM 26093
#define WORLEY_INV_DA 2.51163147204231

// DA x split into its integer cell (wrapping with period 2^32) and fraction in [0, 1), without
// rounding DA x as a whole: x = c + f (c = floor(x), exact), c = 65536 ch + cl (exact), and
// DA c = 26093 ch + (26093 cl) / 65536 in integers, whose remainder (26093 cl) mod 65536 is an
// exact fraction r / 65536. Only DA f rounds, so the fraction is accurate to the f32 precision
// of numbers below 2 whatever |x| is (Worley scales first, L4145, which at |x| = 1e5 leaves
// fractions with steps of 0.004). worley_frac is the fraction, worley_cell the cell (two
// functions rather than one with output parameters; see docs/stdlib/cellular.md).
float worley_sum(float x)
{
    float c = floor(x);
    float cl = c - 65536 * floor(c * 1.52587890625e-5);
    int m = WORLEY_DA_NUM * int(cl);
    return float(m & 65535) * 1.52587890625e-5 + WORLEY_DA * (x - c);
}

float worley_frac(float x)
{
    float g = worley_sum(x);
    return g - floor(g);
}

int worley_cell(float x)
{
    float c = floor(x);
    float ch = floor(c * 1.52587890625e-5);
    int m = WORLEY_DA_NUM * int(c - 65536 * ch);
    return WORLEY_DA_NUM * lattice_cell(ch) + (m >> 16) + int(floor(worley_sum(x)));
}

// Worley's population table (L4122-4133): an approximately Poisson count of feature points per
// cube, mean density 2.5 with 75% of the 0 and 1 populations incremented (L4052). The printed
// table has 255 entries: the fifth 2 of its second row (entry 38) is lost in the seed text and
// restored here from Worley's distributed source. Histogram for m = 0..5: 6, 41, 92, 55, 35, 27
// (mean 665/256 = 2.598). Indexed by the top 8 bits of the cube's hash (L4011).
#define WORLEY_POISSON_TABLE constant int worley_poisson[256] = { \
    4,3,1,1,1,2,4,2,2,2,5,1,0,2,1,2,2,0,4,3,2,1,2,1,3,2,2,4,2,2,5,1,2,3, \
    2,2,2,2,2,3,2,4,2,5,3,2,2,2,5,3,3,5,2,1,3,3,4,4,2,3,0,4,2,2,2,1,3,2, \
    2,2,3,3,3,1,2,0,2,1,1,2,2,2,2,5,3,2,3,2,3,2,2,1,0,2,1,1,2,1,2,2,1,3, \
    4,2,2,2,5,4,2,4,2,2,5,4,3,2,2,5,4,3,3,3,5,2,2,2,2,2,3,1,1,4,2,1,3,3, \
    4,3,2,4,3,3,3,4,5,1,4,2,4,3,1,2,3,5,3,2,1,3,1,3,3,3,2,3,1,5,5,4,2,2, \
    4,1,3,4,1,5,3,3,5,3,4,3,2,2,1,1,1,1,1,2,4,5,4,5,4,2,1,5,1,1,2,3,3,3, \
    2,5,2,3,3,2,0,2,1,1,4,2,1,3,2,1,2,2,3,2,5,5,3,4,5,5,2,4,4,5,3,2,2,2, \
    1,4,2,3,3,4,2,5,4,2,4,2,2,2,4,5,3,2}

// The distance from the fraction g to the neighbour column at offset o (-1, 0, 1): g, 0, 1 - g
// (the square roots of Worley's x2 and mx2, L4160-4168).
float worley_reach(float o, g)
{
    return o < 0 ? g : (o > 0 ? 1 - g : 0);
}

// Worley's cellular basis at p, as a matrix (the language has no structures, and functions with
// output parameters cannot be put in a library yet: docs/stdlib/cellular.md):
//   row 0: f1, f2, f3, f4, the distances from p to the 1st..4th nearest feature points
//          (f1 <= f2 <= f3 <= f4);
//   rows 1, 2, 3: the position of the 1st, 2nd, 3rd nearest feature point (columns 0-2) and its
//          id as a float in [0, 1) (column 3: the top 24 bits of Worley's 32-bit id).
// `manhattan` = 0 measures Euclidean distance, non-zero Manhattan distance |dx| + |dy| + |dz|
// (L4062). Distances are in p's units, scaled so that the mean of F1 is 1 (Euclidean).
//
// The algorithm is Worley's (L4093-4380): scale by DENSITY_ADJUSTMENT (here worley_cell and
// worley_frac), test the central cube and every neighbour cube whose nearest face, edge or
// corner is closer than the current 4th distance (the same test as his 26 hand-written ones,
// L4170-4250, in one loop), and in each cube (AddSamples) draw the population from the table and
// each point's id and position by his LCG, keeping the four nearest by insertion. The pruning
// never skips a cube that could hold one of the four nearest points, so the result is that of
// the exhaustive 27-cube search. Departures, each decided in docs/stdlib/cellular.md: the cube's
// seed is the PCG hash lattice_hash3(cube, 0) instead of his linear 702395077 x + 915488749 y +
// 2120969693 z, which he says "might be better if it were a nonlinear hash" (L4282); positions
// use the top 23 bits of the LCG state, ((s >> 9) + 0.5) / 2^23, instead of (s + 0.5) / 2^32,
// which in f32 rounds to 1 (catalogue H-P5); his code's xj/yj/zj are xi/yi/zi and its duplicated
// insertion block is one (catalogue §3.6, L4318-4395). With fewer than n points in the 27 cubes
// (probability below 1e-9 for n = 4) f_n is Worley's initial 999999.9 in squared scaled units
// (about 2512).
matrix worley_basis(point p; float manhattan)
{
    WORLEY_POISSON_TABLE;
    int cx = worley_cell(p[0]), cy = worley_cell(p[1]), cz = worley_cell(p[2]);
    float gx = worley_frac(p[0]), gy = worley_frac(p[1]), gz = worley_frac(p[2]);
    // Squared (Euclidean) or plain (Manhattan) distances in scaled units while searching;
    // e = feature point - p (Worley's delta), i = id.
    float d1 = 999999.9, d2 = 999999.9, d3 = 999999.9, d4 = 999999.9;
    vector e1 = 0, e2 = 0, e3 = 0;
    uint i1 = 0u, i2 = 0u, i3 = 0u;
    constant float t;
    for (t = 0; t < 27; t += 1) {
        // The central cube first (t = 0 is offset (0, 0, 0)), then the other 26.
        float u = mod(t + 13, 27);
        float ox = floor(u / 9) - 1, oy = mod(floor(u / 3), 3) - 1, oz = mod(u, 3) - 1;
        float rx = worley_reach(ox, gx), ry = worley_reach(oy, gy), rz = worley_reach(oz, gz);
        float bound = manhattan != 0 ? rx + ry + rz : rx * rx + ry * ry + rz * rz;
        if (bound < d4) {
            uint s = lattice_hash3(cx + int(ox), cy + int(oy), cz + int(oz), 0);
            int count = worley_poisson[int(s >> 24u)];
            s = lattice_lcg(s);
            for (int n = 0; n < count; n += 1) {
                uint id = s;
                s = lattice_lcg(s);
                float dx = ox + lattice_open_unit(s) - gx;
                s = lattice_lcg(s);
                float dy = oy + lattice_open_unit(s) - gy;
                s = lattice_lcg(s);
                float dz = oz + lattice_open_unit(s) - gz;
                s = lattice_lcg(s);
                float d = manhattan != 0 ? abs(dx) + abs(dy) + abs(dz) : dx * dx + dy * dy + dz * dz;
                vector e = vector(dx, dy, dz);
                // Insertion into the sorted four (branch-free).
                bool b1 = d < d1, b2 = d < d2, b3 = d < d3, b4 = d < d4;
                d4 = b3 ? d3 : (b4 ? d : d4);
                d3 = b2 ? d2 : (b3 ? d : d3);
                e3 = b2 ? e2 : (b3 ? e : e3);
                i3 = b2 ? i2 : (b3 ? id : i3);
                d2 = b1 ? d1 : (b2 ? d : d2);
                e2 = b1 ? e1 : (b2 ? e : e2);
                i2 = b1 ? i1 : (b2 ? id : i2);
                d1 = b1 ? d : d1;
                e1 = b1 ? e : e1;
                i1 = b1 ? id : i1;
            }
        }
    }
    // Back to p's units (L4258-4265).
    float k = WORLEY_INV_DA;
    vector q1 = p + e1 * k, q2 = p + e2 * k, q3 = p + e3 * k;
    float f1 = manhattan != 0 ? d1 : sqrt(d1), f2 = manhattan != 0 ? d2 : sqrt(d2);
    float f3 = manhattan != 0 ? d3 : sqrt(d3), f4 = manhattan != 0 ? d4 : sqrt(d4);
    return matrix (f1 * k, f2 * k, f3 * k, f4 * k,
                   q1[0], q1[1], q1[2], lattice_unit(i1),
                   q2[0], q2[1], q2[2], lattice_unit(i2),
                   q3[0], q3[1], q3[2], lattice_unit(i3));
}

// F1..F4 (Euclidean) alone.
float worley_f1(point p)
{
    return worley_basis(p, 0)[0][0];
}

float worley_f2(point p)
{
    return worley_basis(p, 0)[0][1];
}

float worley_f3(point p)
{
    return worley_basis(p, 0)[0][2];
}

float worley_f4(point p)
{
    return worley_basis(p, 0)[0][3];
}

// F2 - F1: 0 on the Voronoi boundaries (veins, L3946).
float worley_f2_f1(point p)
{
    matrix w = worley_basis(p, 0);
    return w[0][1] - w[0][0];
}

// F1 with the Manhattan metric (rectangular cells, L4062).
float worley_manhattan_f1(point p)
{
    return worley_basis(p, 1)[0][0];
}

// The id of the nearest feature point as a float in [0, 1) (its top 24 bits): constant over each
// Voronoi cell, for per-cell colours (flagstones, L3975).
float worley_id1(point p)
{
    return worley_basis(p, 0)[1][3];
}

// The position of the nearest feature point.
point worley_point1(point p)
{
    matrix w = worley_basis(p, 0);
    return point(w[1][0], w[1][1], w[1][2]);
}

#undef WORLEY_POISSON_TABLE

#endif
