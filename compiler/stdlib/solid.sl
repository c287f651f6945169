// Hart's parameterized solid texture (Hart, Carr, Kameya, Tibbitts & Coleman, "Antialiased
// Parameterized Solid Texturing", 1999: shared/seeds/004_dc0e594aa54d1617.txt L85-297, digest
// shared/notes/seed-digest.md §3.1): one formula for wood, marble, clouds and fire,
//
//     p(s) = c( q(s) + sum_i a_i n(T_i(s)) )                                  (1), L93
//
// with q the quadric [s t r 1] Q [s t r 1]^T (3)-(4), L108-115, n Perlin noise, a_i amplitudes,
// T_i affine maps, and c a colour map indexed modulo 1 or clamped (2), L102. Its antialiasing
// (L176-297): the analytic gradient of f = q + sum a_i n_i (10)-(12) gives the spread of colour
// indices over a pixel, and the colour map is box-filtered over that spread (9), L193. Here the
// noise terms finer than the pixel also fade to their mean (Musgrave's filteredsnoise fade,
// T&M L10447-10450), so a filtered texture loses its octaves as the filter width grows.
// docs/stdlib/solid.md has the formulas, the errata decisions and the measured precision.
//
// Conventions. n is RenderMan's unsigned noise, noise3 (compiler/stdlib/noise.sl: Perlin's improved
// noise scaled into [0, 1], 0.5 at lattice points): APST's noise is in [0, 1] too (Rayshade's
// lattice noise, L346), and the seed's colour maps (clamped blue to white for clouds) expect
// non-negative indices. The noise terms are T_i(s) = lacunarity^i (s T) + phase for
// i = 0 .. nterms - 1, with s T the affine map of the row vector s by the 4x4 matrix T (its upper
// 3x3 part and its translation row; the fourth column is ignored), and a_i = amp gain^i: the
// seed's fractal sums sum_{i=1}^{4} 2^-i n(2^i s) are T = 2 I, lacunarity 2, amp 1/2, gain 1/2,
// nterms 4. Q is used as given (q = sum_jk x_j Q_jk x_k with x = (s, t, r, 1)), so a
// non-symmetric Q means its symmetric part.
//
// Errata (seed-digest §7): E8, the colour map printed `clut[round(n mod clamp(f))]`, is read as
// "modulo 1 or clamp to [0, 1] by a flag", and the table is interpolated linearly through its
// entries (the wood map is "a modulo-one linear interpolation", L137); E9, the gradient of q
// printed as 2 [s t r 0] Q J, is 2 [s t r 1] Q J (the linear terms D, G, I count) and J's third
// row is (dr/dx, dr/dy); E12, the unbalanced parentheses of (7) and (8), are read as in the
// digest. APST's summed-area colour table (13)-(15) is replaced by its exact equivalent for a
// piecewise-linear map: the box average is the difference of the map's closed-form integral
// (hart_colormap). APST's rule "w >= N: return the mean of the table" is not used: the box
// average tends to that mean by itself in the modulo mode, and in the clamp mode it tends to the
// mean of the two end colours (the map is extended by them), which keeps it continuous.
//
// Guards, so that every finite input gives a finite result on both backends: coordinates are
// clamped to +-1e9 (above 2^23 the f32 noise is 0 anyway), Q's entries to +-1e18, T's entries
// and the phase to +-1e9, nterms to [0, 8] (APST: "typically between four and eight", L126),
// amp to +-1e6, gain to [-8, 8], lacunarity to [1, 8], filter widths to [0, 1e30] (their
// absolute value). Then |q| < 2e37, the noise sum < 2e13 and every gradient component < 1e30.

#ifndef PATINA_SOLID_SL
#define PATINA_SOLID_SL

#include <noise.sl>

#define HART_CLAMP 0
#define HART_MOD 1
#define HART_MAX_TERMS 8
#define HART_MAX_PROBES 8

// The guarded point: each coordinate clamped to +-1e9.
point hart_clamp_point(point p)
{
    return point(clamp(p[0], -1e9, 1e9), clamp(p[1], -1e9, 1e9), clamp(p[2], -1e9, 1e9));
}

// A guarded matrix entry.
float hart_entry(matrix m; float row, col; float bound)
{
    return clamp(comp(m, row, col), -bound, bound);
}

// The quadric q(s) = [s t r 1] Q [s t r 1]^T of APST (3)-(4), L108-115:
// A s^2 + 2B st + 2C sr + 2D s + E t^2 + 2F tr + 2G t + H r^2 + 2I r + J for the symmetric
// Q = [[A B C D] [B E F G] [C F H I] [D G I J]]. Computed as sum_k (sum_j x_j Q_jk) x_k with
// x = (s, t, r, 1).
float hart_quadric(point p; matrix Q)
{
    point s = hart_clamp_point(p);
    float x[4] = {s[0], s[1], s[2], 1};
    float q = 0;
    constant float j, k;
    for (k = 0; k < 4; k += 1) {
        float row = 0;
        for (j = 0; j < 4; j += 1) {
            row += x[j] * hart_entry(Q, j, k, 1e18);
        }
        q += row * x[k];
    }
    return q;
}

// The gradient of the quadric with respect to s: sum_j x_j (Q_jk + Q_kj) for k = 0 .. 2, that is
// 2 ([s t r 1] Q)_{1..3} for a symmetric Q (APST (11) with erratum E9: the 1 keeps the linear
// terms D, G, I).
vector hart_quadric_gradient(point p; matrix Q)
{
    point s = hart_clamp_point(p);
    float x[4] = {s[0], s[1], s[2], 1};
    float g[3] = {0, 0, 0};
    constant float j, k;
    for (k = 0; k < 3; k += 1) {
        for (j = 0; j < 4; j += 1) {
            g[k] += x[j] * hart_entry(Q, j, k, 1e18) + hart_entry(Q, k, j, 1e18) * x[j];
        }
    }
    return vector(g[0], g[1], g[2]);
}

// The affine map s T of a row vector: (s T)_k = sum_j s_j T_jk + T_3k, k = 0 .. 2, with T's
// entries clamped to +-1e9.
point hart_affine(point s; matrix T)
{
    float y[3] = {0, 0, 0};
    constant float j, k;
    for (k = 0; k < 3; k += 1) {
        y[k] = hart_entry(T, 3, k, 1e9);
        for (j = 0; j < 3; j += 1) {
            y[k] += s[j] * hart_entry(T, j, k, 1e9);
        }
    }
    return point(y[0], y[1], y[2]);
}

// The largest stretch of T's linear part: max over k of sum_j |T_jk| (the most any coordinate of
// s T moves when each coordinate of s moves by 1): a noise term's feature frequency.
float hart_stretch(matrix T)
{
    float sigma = 0;
    constant float j, k;
    for (k = 0; k < 3; k += 1) {
        float col = 0;
        for (j = 0; j < 3; j += 1) {
            col += abs(hart_entry(T, j, k, 1e9));
        }
        sigma = max(sigma, col);
    }
    return sigma;
}

// The analytic gradient of Perlin's improved noise, APST's DNoise (12), L226: dsnoise3 of
// compiler/stdlib/noise.sl (the same cell, hash, gradients and closed form: with u = fade(x),
// u' = 30 x^2 (x - 1)^2 and n_abc the corner dot products,
// dn/dx = u' lerp(w, lerp(v, n100 - n000, n110 - n010), lerp(v, n101 - n001, n111 - n011))
// plus the trilinear interpolation of the corners' gradient vectors, and alike in y and z)
// without snoise3's scale. Continuous (the noise is C2).
vector hart_noise_gradient(point p)
{
    return dsnoise3(p) / PATINA_SNOISE_SCALE;
}

// The weight of a noise term of frequency k (cycles per unit of s) at filter width fw:
// 1 - smoothstep(0.4, 1.6, k fw), Musgrave's filteredsnoise fade (T&M L10447-10450) over a wider
// range: 1 while the term's features span more than 2.5 filter widths, 0 once they span fewer
// than 0.6. The range is measured: of (0.2, 0.6), (0.4, 1.6), (0.6, 3) and (1, 4) it gives the
// least error against 16 x 16 supersampling over the three bench planes (docs/error-vs-time.md).
float hart_term_weight(float k, fw)
{
    return 1 - smoothstep(0.4, 1.6, k * fw);
}

// A vector with its components clamped to +-1e9: the guard of phases and footprints.
vector hart_clamp_vector(vector v)
{
    return vector(clamp(v[0], -1e9, 1e9), clamp(v[1], -1e9, 1e9), clamp(v[2], -1e9, 1e9));
}

// d L: the linear part of T applied to a vector d (row-vector convention, as hart_affine).
vector hart_linear(vector d; matrix T)
{
    float y[3] = {0, 0, 0};
    constant float j, k;
    for (k = 0; k < 3; k += 1) {
        for (j = 0; j < 3; j += 1) {
            y[k] += d[j] * hart_entry(T, j, k, 1e9);
        }
    }
    return vector(y[0], y[1], y[2]);
}

// The isotropic blur fw in T space, stretch(T) |fw|, at most 1e30.
float _patina_hart_blur(matrix T; float fw)
{
    return min(hart_stretch(T) * min(abs(fw), 1e30), 1e30);
}

// A footprint from its parts: sqrt(iso^2 + (a2 + b2) / 2) for an isotropic blur iso and a
// parallelogram whose sides' squared lengths are a2 and b2 (below 1e38: the callers' clamped
// derivatives); past iso = 1e18 iso itself, so nothing overflows.
float _patina_hart_footprint(float iso, a2, b2)
{
    return iso > 1e18 ? iso : min(sqrt(iso * iso + 0.5 * (a2 + b2)), 1e30);
}

// The filter width a noise term of frequency 1 sees, its argument's footprint: the isotropic
// blur fw stretched by T (stretch(T) fw) and the parallelogram dpdx, dpdy carried through T's
// linear part L, sqrt((stretch(T) fw)^2 + (|dpdx L|^2 + |dpdy L|^2) / 2). The derivatives are
// clamped to +-1e9 and the isotropic part to 1e30; past 1e18 it is returned as it is, so nothing
// overflows.
float hart_term_footprint(matrix T; float fw; vector dpdx, dpdy)
{
    vector x = hart_linear(hart_clamp_vector(dpdx), T), y = hart_linear(hart_clamp_vector(dpdy), T);
    return _patina_hart_footprint(_patina_hart_blur(T, fw), x . x, y . y);
}

// The noise term of frequency k over a footprint: the box average of snoise3 along the
// footprint's major axis `major` (in T space, frequency 1) about k ts + phase, by a midpoint rule
// of `probes` points, each faded by hart_term_weight(k, width), width being the footprint one probe
// still covers. A probe per half a feature of the term along the major axis, at most
// HART_MAX_PROBES: a receding surface's footprint is long and thin, and one faded sample of it
// loses the features the thin side still resolves (Feline's probes along the major axis,
// McCormack et al. 1999). `probes` = n may be fractional, so that the average is continuous in
// the footprint: the axis [-1/2, 1/2] is cut into ceil(n) pieces of length 1/n from its start, the
// last one shorter, and each probe, at its piece's middle, weighs its piece's length (a probe
// enters with weight 0 as n passes a whole number; a whole count of probes was a step, where the
// picture jumped by ~1e-2 as a zoom changed the footprint, and f32 and f64 could land on its two
// sides). n is clamped to [1, HART_MAX_PROBES], so any input ends the loop; k and `major` are
// clamped to +-1e9, so the probes' offsets stay finite (a term that is not faded out has
// k |major| below 20, far inside).
float hart_term_probes(point kts; vector major; float k, probes, width)
{
    float w = hart_term_weight(k, width);
    float n = clamp(probes, 1, HART_MAX_PROBES);
    vector m = clamp(k, -1e9, 1e9) * hart_clamp_vector(major);
    float sum = 0;
    if (w > 0) {
        float count = ceil(n);
        float j;
        for (j = 0; j < count; j += 1) {
            float a = j / n - 0.5;
            float b = min((j + 1) / n - 0.5, 0.5);
            sum += (b - a) * snoise3(kts + (0.5 * (a + b)) * m);
        }
    }
    return w * sum;
}

// APST's classification f(s) = q(s) + sum_{i < nterms} a_i n(T_i(s)) (1), filtered:
// a_i = amp gain^i, T_i(s) = lacunarity^i (s T) + phase, n = noise3, and each term is
// a_i (0.5 + w_i (n - 0.5)) with w_i = hart_term_weight(lacunarity^i stretch(T), filterwidth)
// (filterwidth: the filter width of p in texture space, or 0 for no filtering): a term finer
// than the filter fades to its mean 0.5 a_i, so f tends to q + 0.5 sum a_i as the width grows.
// A fractional nterms weights its last term by the fraction (continuous in nterms). Guards: see
// the file's header.
float hart_solid(point p; matrix Q; float nterms, amp, gain; matrix T; float lacunarity;
                 vector phase; float filterwidth)
{
    return hart_solid_footprint(p, Q, nterms, amp, gain, T, lacunarity, phase, filterwidth, vector(0), vector(0));
}

// hart_solid over a footprint: an isotropic blur fw and the parallelogram spanned by dpdx and
// dpdy (p's change across one pixel along each raster axis), carried into T space (dpdx L and
// dpdy L, the longer the major axis M). Term i of frequency k = lacunarity^i is the average along
// M by n_i = clamp(2 k |M| + 1/2, 1, HART_MAX_PROBES) probes, a fractional count (hart_term_probes:
// the half makes as many probes on average as the whole count ceil(2 k |M|) did),
// each faded by the footprint it covers, sqrt((stretch(T) fw)^2 + (|minor|^2 + (|M| / n_i)^2) / 2)
// (hart_term_footprint with the major axis cut into pieces of length |M| / n_i). Continuous in the
// footprint while the major axis stays the same raster axis. With dpdx = dpdy = 0 it is
// hart_solid.
float hart_solid_footprint(point p; matrix Q; float nterms, amp, gain; matrix T; float lacunarity;
                           vector phase; float fw; vector dpdx, dpdy)
{
    point s = hart_clamp_point(p);
    float nt = clamp(nterms, 0, HART_MAX_TERMS);
    float lac = clamp(lacunarity, 1, 8);
    float iso = _patina_hart_blur(T, fw);
    vector x = hart_linear(hart_clamp_vector(dpdx), T), y = hart_linear(hart_clamp_vector(dpdy), T);
    float xx = x . x, yy = y . y;
    vector major = xx >= yy ? x : y;
    float lmajor = sqrt(max(xx, yy)), minor2 = min(xx, yy);
    vector ph = hart_clamp_vector(phase);
    point ts = hart_affine(s, T);
    float f = hart_quadric(s, Q);
    float a = clamp(amp, -1e6, 1e6), g = clamp(gain, -8, 8), k = 1;
    float i;
    for (i = 0; i < nt; i += 1) {
        float probes = clamp(2 * k * lmajor + 0.5, 1, HART_MAX_PROBES);
        float piece = lmajor / probes;
        float width = _patina_hart_footprint(iso, minor2, piece * piece);
        float n = hart_term_probes(k * ts + ph, major, k, probes, width);
        f += clamp(nt - i, 0, 1) * a * (0.5 + 0.5 * n);
        a *= g;
        k *= lac;
    }
    return f;
}

// The analytic gradient of hart_solid with respect to p (APST (10)-(12) with E9): the quadric's
// 2 ([s t r 1] Q)_{1..3} plus, per term, a_i w_i lacunarity^i L dn, with L the linear part of T
// and dn the gradient of noise3 at T_i(s) (0.5 dsnoise3). The
// faded weights w_i depend on the filter width only, so this is the gradient of the filtered f.
// The screen-space filter width of f is |J^T grad| with J the Jacobian of p over the pixel;
// hart_filterwidth approximates it by |grad| times p's filter width.
vector hart_solid_gradient(point p; matrix Q; float nterms, amp, gain; matrix T; float lacunarity;
                           vector phase; float filterwidth)
{
    return hart_solid_gradient_footprint(p, Q, nterms, amp, gain, T, lacunarity, phase, filterwidth,
                                         vector(0), vector(0));
}

// The gradient of hart_solid_footprint (as hart_solid_gradient, with its fade).
vector hart_solid_gradient_footprint(point p; matrix Q; float nterms, amp, gain; matrix T; float lacunarity;
                                     vector phase; float fw; vector dpdx, dpdy)
{
    point s = hart_clamp_point(p);
    float nt = clamp(nterms, 0, HART_MAX_TERMS);
    float lac = clamp(lacunarity, 1, 8);
    float tf = hart_term_footprint(T, fw, dpdx, dpdy);
    vector ph = hart_clamp_vector(phase);
    point ts = hart_affine(s, T);
    vector grad = hart_quadric_gradient(s, Q);
    float a = clamp(amp, -1e6, 1e6), g = clamp(gain, -8, 8), k = 1;
    float i;
    for (i = 0; i < nt; i += 1) {
        float w = hart_term_weight(k, tf);
        // noise3 = 0.5 + 0.5 snoise3.
        vector dn = 0.5 * dsnoise3(k * ts + ph);
        // The chain rule through s T: (L dn)_j = sum_k T_jk dn_k.
        vector ldn = vector(
            hart_entry(T, 0, 0, 1e9) * dn[0] + hart_entry(T, 0, 1, 1e9) * dn[1] + hart_entry(T, 0, 2, 1e9) * dn[2],
            hart_entry(T, 1, 0, 1e9) * dn[0] + hart_entry(T, 1, 1, 1e9) * dn[1] + hart_entry(T, 1, 2, 1e9) * dn[2],
            hart_entry(T, 2, 0, 1e9) * dn[0] + hart_entry(T, 2, 1, 1e9) * dn[1] + hart_entry(T, 2, 2, 1e9) * dn[2]);
        grad += (clamp(nt - i, 0, 1) * a * w * k) * ldn;
        a *= g;
        k *= lac;
    }
    return grad;
}

// The colour-index filter width of APST (9), L193: |grad f| times the filter width of p (an
// isotropic footprint), clamped to [0, 1e30]. The gradient's components are first clamped to
// +-1e18 so that the length cannot overflow.
float hart_filterwidth(vector grad; float filterwidth)
{
    vector g = vector(clamp(grad[0], -1e18, 1e18), clamp(grad[1], -1e18, 1e18), clamp(grad[2], -1e18, 1e18));
    return min(min(abs(filterwidth), 1e30) * length(g), 1e30);
}

// The piecewise-linear colour ramp through clut[0 .. m] at x in segment units (knot j at x = j;
// x outside [0, m] extrapolates an end segment, which the callers avoid).
// sweep: clut length 4; m in {0, 1, 2, 3} (a whole number of segments, at most the table's length less one)
color hart_ramp_at(float x; color clut[]; float m)
{
    // One segment (m at most 1) is segment 0, written out so that a compiler that knows m reads
    // the table at constant indices (the clamp gives 0 there too, NaN included).
    float j = m > 1 ? clamp(floor(x), 0, m - 1) : 0;
    int k = int(j);
    return clut[k] + (x - j) * (clut[k + 1] - clut[k]);
}

// The ramp's integral from 0 to y in segment units, y in [0, m]: the whole segments' trapezoids
// plus the part of the segment holding y.
// sweep: clut length 4; m in {0, 1, 2, 3}; y in [0, 3]
color hart_ramp_integral(float y; color clut[]; float m)
{
    float j = clamp(floor(y), 0, max(m - 1, 0));
    int kj = int(j);
    float t = y - j;
    color acc = 0;
    // One segment (m = 1, a two-colour map such as the wood's) has no whole segment below y.
    // The test lets a compiler that knows m leave the loop out: a GPU pays for a loop's
    // bookkeeping even when it runs no iteration, and lavapipe runs all three of the colour
    // map's integrals for every pixel (its branches are masks): 10% of the wood's shading.
    if (m > 1) {
        float k;
        for (k = 0; k < j; k += 1) {
            int ik = int(k);
            acc += 0.5 * (clut[ik] + clut[ik + 1]);
        }
    }
    return acc + t * clut[kj] + (0.5 * t * t) * (clut[kj + 1] - clut[kj]);
}

// The ramp with the mode's extension at x in segment units: modulo m, or clamped to [0, m]. With
// m = 0 (one knot) both are clut[0].
// sweep: clut length 4; m in {0, 1, 2, 3}
color hart_ramp_ext(float x; color clut[]; float m; float mode)
{
    float y = mode == HART_MOD ? (m > 0 ? x - m * floor(x / m) : 0) : clamp(x, 0, m);
    return hart_ramp_at(y, clut, m);
}

// APST's colour map c(f) (2) with its box filter (9): the average over [f - width/2,
// f + width/2] of the piecewise-linear ramp through the n colours clut[0 .. n-1] (n at most the
// table's length) at f = 0, 1/(n-1), .., 1, extended modulo 1 (mode HART_MOD: the ramp repeats,
// jumping from clut[n-1] back to clut[0] at each integer, as the wood map does) or clamped
// (HART_CLAMP: clut[0] below 0, clut[n-1] above 1). Width 0 gives the point value. The average
// is exact for any width: below 1e-6 segments, the point value; below one segment (the interval
// holds at most one knot), the length-weighted midpoint values of its two linear pieces;
// otherwise the difference of the ramp's closed-form integral over the width (whole periods
// times the period's integral in the modulo mode; the end colours times the lengths outside
// [0, 1] in the clamp mode). As the width grows the result tends to the ramp's mean (modulo) or
// to the mean of the end colours (clamp). n below 2 gives clut[0]. Widths are taken as |width|,
// at most 1e30.
// sweep: clut length 4; n in [0, 4] (n at most the table's length)
color hart_colormap(float f, width; float mode; color clut[]; float n)
{
    float m = max(floor(n) - 1, 0);
    if (m == 0)
        return clut[0];
    float h = min(0.5 * m * min(abs(width), 1e30), 1e30);
    float u = mode == HART_MOD ? m * (f - floor(f)) : m * f;
    float a = u - h, b = u + h;
    if (mode != HART_MOD) {
        if (b <= 0)
            return clut[0];
        if (a >= m)
            return clut[int(m)];
    }
    if (h < 5e-7)
        return hart_ramp_ext(u, clut, m, mode);
    if (h < 0.5) {
        float kb = floor(b);
        if (floor(a) == kb)
            return hart_ramp_ext(u, clut, m, mode);
        return ((kb - a) * hart_ramp_ext(0.5 * (a + kb), clut, m, mode)
              + (b - kb) * hart_ramp_ext(0.5 * (kb + b), clut, m, mode)) / (b - a);
    }
    if (mode == HART_MOD) {
        color period = hart_ramp_integral(m, clut, m);
        float pa = floor(a / m), pb = floor(b / m);
        color rest = hart_ramp_integral(b - m * pb, clut, m) - hart_ramp_integral(a - m * pa, clut, m);
        // Whole periods and the rest, each divided by the width before they meet, so that many
        // periods of a bright table do not overflow (the sweep found (pb - pa) period = inf).
        return ((pb - pa) / (b - a)) * period + rest / (b - a);
    }
    float lo = max(a, 0), hi = min(b, m);
    color inside = hart_ramp_integral(hi, clut, m) - hart_ramp_integral(lo, clut, m);
    return ((lo - a) / (b - a)) * clut[0] + inside / (b - a) + ((b - hi) / (b - a)) * clut[int(m)];
}

// The unfiltered colour map: hart_colormap at width 0.
// sweep: clut length 4; n in [0, 4]
color hart_colormap(float f; float mode; color clut[]; float n)
{
    return hart_colormap(f, 0, mode, clut, n);
}

// The colour-index filter width over a footprint made of an isotropic blur of width fw in p
// and the parallelogram spanned by dpdx and dpdy (p's change across one pixel along each raster
// axis): sqrt((fw |grad|)^2 + (grad . dpdx)^2 + (grad . dpdy)^2). The last two are APST's
// ||grad_xy f|| (9), the screen-space gradient J^T grad; the first is hart_filterwidth. Each
// part is at most 1e30, and the sum is not squared once a part passes 1e18, so nothing overflows.
float hart_footprint_width(vector grad; float fw; vector dpdx, dpdy)
{
    vector g = vector(clamp(grad[0], -1e18, 1e18), clamp(grad[1], -1e18, 1e18), clamp(grad[2], -1e18, 1e18));
    float iso = hart_filterwidth(g, fw);
    float x = min(abs(g . hart_clamp_vector(dpdx)), 1e30), y = min(abs(g . hart_clamp_vector(dpdy)), 1e30);
    float m = max(iso, max(x, y));
    return m > 1e18 ? m : sqrt(iso * iso + x * x + y * y);
}

// A solid texture's filtered colour: hart_colormap(f, width, mode, clut, n) with f and its
// gradient from hart_solid_footprint and hart_solid_gradient_footprint over the footprint, and the
// width hart_footprint_width(grad f, fw, dpdx, dpdy). fw = 0 with dpdx, dpdy the pixel's
// derivatives of p is APST's filter; dpdx = dpdy = 0 the isotropic filter of width fw; all zero,
// unfiltered.
// sweep: clut length 4; n in [0, 4]
color hart_texture(point p; matrix Q; float nterms, amp, gain; matrix T; float lacunarity;
                   vector phase; float fw; vector dpdx, dpdy; float mode; color clut[]; float n)
{
    float f = hart_solid_footprint(p, Q, nterms, amp, gain, T, lacunarity, phase, fw, dpdx, dpdy);
    vector g = hart_solid_gradient_footprint(p, Q, nterms, amp, gain, T, lacunarity, phase, fw, dpdx, dpdy);
    return hart_colormap(f, hart_footprint_width(g, fw, dpdx, dpdy), mode, clut, n);
}

// The presets: APST's four fundamental textures (§2.2, L128-166) with the seed's parameters, each
// as hart_texture over a footprint (`hart_X_footprint(p, fw, dpdx, dpdy)`: an isotropic blur fw and
// p's pixel derivatives dpdx, dpdy, as hart_texture) and over an isotropic filter width alone
// (`hart_X(p, fw)`, fw the filter width of p in texture space, 0: unfiltered). The colours are
// this library's choice where the seed names them only in words.

// Wood (5), L132-139: f = s^2 + t^2 + n(4s, 4t, r): concentric cylinders about the r axis (Q with
// A = E = 1), one noise term of amplitude 1 with T = diag(4, 4, 1); a modulo-one linear map from
// a light earlywood to a darker latewood (rings of f = k, radius sqrt(k): the early rings wider).
color hart_wood_footprint(point p; float fw; vector dpdx, dpdy)
{
    matrix Q = (1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 0, 0,  0, 0, 0, 0);
    matrix T = (4, 0, 0, 0,  0, 4, 0, 0,  0, 0, 1, 0,  0, 0, 0, 1);
    constant color clut[2] = {color(0.86, 0.66, 0.42), color(0.50, 0.30, 0.14)};
    return hart_texture(p, Q, 1, 1, 1, T, 1, vector(0), fw, dpdx, dpdy, HART_MOD, clut, 2);
}

color hart_wood(point p; float fw)
{
    return hart_wood_footprint(p, fw, vector(0), vector(0));
}

// Marble (7), L150-157: f = r + sum_{i=1}^{4} 2^-i n(2^i s) (Q with I = 1/2; T = 2 I,
// lacunarity 2, amp and gain 1/2, 4 terms); a modulo-one table from a marble cross-section
// (white, grey, a dark vein, grey, white: the same colour at both ends, so the repeat is seamless).
color hart_marble_footprint(point p; float fw; vector dpdx, dpdy)
{
    matrix Q = (0, 0, 0, 0,  0, 0, 0, 0,  0, 0, 0, 0.5,  0, 0, 0.5, 0);
    matrix T = (2, 0, 0, 0,  0, 2, 0, 0,  0, 0, 2, 0,  0, 0, 0, 1);
    constant color clut[6] = {
        color(0.93, 0.92, 0.89), color(0.85, 0.84, 0.82), color(0.62, 0.62, 0.66),
        color(0.30, 0.30, 0.36), color(0.70, 0.70, 0.72), color(0.93, 0.92, 0.89)};
    return hart_texture(p, Q, 4, 0.5, 0.5, T, 2, vector(0), fw, dpdx, dpdy, HART_MOD, clut, 6);
}

color hart_marble(point p; float fw)
{
    return hart_marble_footprint(p, fw, vector(0), vector(0));
}

// Clouds (6), L141-148: f = sum_{i=1}^{4} 2^-i n(2^i s) (Q = 0; T = 2 I, lacunarity 2, amp and
// gain 1/2, 4 terms); a clamped linear map from blue to white.
color hart_clouds_footprint(point p; float fw; vector dpdx, dpdy)
{
    matrix Q = 0;
    matrix T = (2, 0, 0, 0,  0, 2, 0, 0,  0, 0, 2, 0,  0, 0, 0, 1);
    constant color clut[2] = {color(0.25, 0.45, 0.85), color(1, 1, 1)};
    return hart_texture(p, Q, 4, 0.5, 0.5, T, 2, vector(0), fw, dpdx, dpdy, HART_CLAMP, clut, 2);
}

color hart_clouds(point p; float fw)
{
    return hart_clouds_footprint(p, fw, vector(0), vector(0));
}

// Fire (8), L159-166: f = r + sum_{i=1}^{4} 2^-i n(2^i s, 0, 2^i r + phase) (Q with I = 1/2;
// T = diag(2, 0, 2), lacunarity 2, amp and gain 1/2, 4 terms, phase (0, 0, phase): animating the
// phase animates the flames). The seed states no colour map: a clamped black, red, orange,
// yellow, white ramp.
color hart_fire_footprint(point p; float phase, fw; vector dpdx, dpdy)
{
    matrix Q = (0, 0, 0, 0,  0, 0, 0, 0,  0, 0, 0, 0.5,  0, 0, 0.5, 0);
    matrix T = (2, 0, 0, 0,  0, 0, 0, 0,  0, 0, 2, 0,  0, 0, 0, 1);
    constant color clut[5] = {
        color(0, 0, 0), color(0.75, 0.1, 0), color(1, 0.5, 0), color(1, 0.9, 0.3), color(1, 1, 1)};
    return hart_texture(p, Q, 4, 0.5, 0.5, T, 2, vector(0, 0, phase), fw, dpdx, dpdy, HART_CLAMP, clut, 5);
}

color hart_fire(point p; float phase, fw)
{
    return hart_fire_footprint(p, phase, fw, vector(0), vector(0));
}

#endif
