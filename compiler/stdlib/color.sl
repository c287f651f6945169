// Colour tables with Hart's filtering (Hart, Carr, Kameya, Tibbitts & Coleman, "Antialiased
// Parameterized Solid Texturing", in Hart's course chapter 6: shared/seeds/004_dc0e594aa54d1617.txt,
// colour map eq. (2) at L101-105, table filtering eq. (9) at L199-203, summed-area colour table
// eqs. (13)-(15) and its boundary cases at L248-272). See docs/stdlib/color.md.
//
// A table is an array of N colours (a `constant` local or a shader parameter); x in [0, 1] maps
// onto it, entry j covering [j/N, (j + 1)/N) (the last entry includes x = 1). Outside [0, 1] the
// index is either clamped (wrap == 0) or taken modulo 1 (wrap != 0), Hart's modclamp flag.
//
// Filtering: filteredcolortable(table, sat, x, w, wrap) is the exact mean of the (clamped or
// periodic) table over the box [x - w/2, x + w/2], w in the units of x (pass filterwidth(x)),
// computed in constant time from the summed-area table `sat` (PATINA_COLORTABLE_SAT); the form
// without `sat` builds it on each call (N additions). w <= 0 gives the
// unfiltered colortable(table, x, wrap).
//
// MIP map: mipcolortable(mip, n, x, w, wrap) is Hart's colour-table MIP map (section 3.3.1,
// L237-243, errata E10) from the levels `mip` of a table of n = 2^k entries
// (PATINA_COLORTABLE_MIP), w as for filteredcolortable: an approximation of the box filter,
// exactly colortable for w <= 1/n and the table's mean for w >= 1.
//
// Table sizes: colortable and filteredcolortable are defined for arrays of 2 to 32, 48, 64, 128
// and 256 colours, each size its own overload, made by the macro PATINA_COLOR_TABLE(N) (written
// when open-length array parameters read every element as element 0, a compiler bug since fixed);
// write `PATINA_COLOR_TABLE(20)` at the top level of a shader file, after the #include, for
// another size. mipcolortable takes an open-length array (`color mip[]`) and the table's length.
//
// Colour spaces and colour splines are built in: ctransform and the colour casts
// (`color "hsv" (h, s, v)`) convert between rgb, hsv, hsl, xyz/XYZ, xyY and YIQ (written in
// compiler/stdlib/builtins.sl), and spline takes colour knots, listed or in an array
// (docs/builtins.md); docs/stdlib/color.md documents and tests them. Nothing of them is here.

#ifndef PATINA_COLOR_SL
#define PATINA_COLOR_SL

// The entry of an n-entry table at x, clamped or wrapped: floor(n * modclamp(x)), the last entry
// for modclamp(x) = 1 (Hart's round(n modclamp(f)) errata E8: entries are cells, so that the box
// filter below is the mean of exactly this function). x - floor(x) can round to 1 (x = -1e-40),
// which also gives the last entry.
float _patina_ctable_entry(float n, x, wrap)
{
    float u;
    if (wrap != 0)
        u = n * (x - floor(x));
    else
        u = n * clamp(x, 0, 1);
    return min(floor(u), n - 1);
}

// The summed-area table of a colour table of n entries (a literal or constant): the statement
// PATINA_COLORTABLE_SAT(table, sat, n) sets sat[j] = table[0] + ... + table[j] (Hart's csat,
// eq. 13, L252), for the arrays `color table[n]` and `color sat[n]`. It is a macro, not a function
// with an `output` array parameter, because of a second compiler bug when it was written (since
// fixed): a function with an `output` parameter that no shader calls failed to check (E0507). Its loop counter is a plain (varying) float, not `constant`, so
// that it may be used under a varying condition (a constant declaration there is E0605).
#define PATINA_COLORTABLE_SAT(table, sat, n) \
    { \
        color _patina_acc = 0; \
        float _patina_j; \
        for (_patina_j = 0; _patina_j < (n); _patina_j += 1) { \
            _patina_acc += (table)[_patina_j]; \
            (sat)[_patina_j] = _patina_acc; \
        } \
    }

// The colour-table MIP map (Hart's section 3.3.1, L237-243): the statement
// PATINA_COLORTABLE_MIP(table, mip, n) fills `color mip[2n - 1]` with the levels of the n-entry
// table, n a power of two: level 0 (the table itself) at mip[0 .. n), level k, of n/2^k entries,
// at mip[2n - 2n/2^k ..), each entry the mean of the two entries of level k - 1 it covers, up to
// the one-entry level log2(n) at mip[2n - 2] (the table's mean). A macro, as the summed-area table
// is, with plain (varying) loop counters.
#define PATINA_COLORTABLE_MIP(table, mip, n) \
    { \
        float _patina_j, _patina_src = 0, _patina_dst = (n), _patina_len = (n) / 2; \
        for (_patina_j = 0; _patina_j < (n); _patina_j += 1) \
            (mip)[_patina_j] = (table)[_patina_j]; \
        while (_patina_len >= 1) { \
            for (_patina_j = 0; _patina_j < _patina_len; _patina_j += 1) \
                (mip)[_patina_dst + _patina_j] = \
                    ((mip)[_patina_src + 2 * _patina_j] + (mip)[_patina_src + 2 * _patina_j + 1]) / 2; \
            _patina_src = _patina_dst; \
            _patina_dst += _patina_len; \
            _patina_len /= 2; \
        } \
    }

// The MIP-mapped lookup of an n-entry table (n a power of two) from its levels `mip`
// (PATINA_COLORTABLE_MIP), x as in colortable, w in the units of x as in filteredcolortable (pass
// filterwidth(x)): the width in entries is m = n w, the level i = clamp(floor(log2 m), 0, log2 n)
// (Hart's clut_i[f/i], errata E10: entry floor(n/2^i modclamp(x)) of level i), blended linearly
// with level i + 1 by the fractional part of log2 m (Hart's "more accurately the linear
// interpolation"). m <= 1 is exactly colortable; m >= n the table's mean. The level is found by
// halving m (at most log2 n times, exact), not from floor(log2 m), so the level choice does not
// depend on the accuracy of log; only the blend weight t = log2 of a number in [1, 2) uses it.
// sweep: mip length 7; n in {1, 2, 4} (a power of two, with its 2n - 1 levels' entries)
color mipcolortable(color mip[]; float n, x, w, wrap)
{
    float m = n * max(w, 0), ni = n;
    if (m <= 1)
        return mip[_patina_ctable_entry(n, x, wrap)];
    while (ni > 1 && m >= 2) {
        m /= 2;
        ni /= 2;
    }
    float off = 2 * n - 2 * ni;
    color lo = mip[off + _patina_ctable_entry(ni, x, wrap)];
    if (ni <= 1)
        return lo;
    float t = clamp(log(m, 2), 0, 1);
    color hi = mip[off + ni + _patina_ctable_entry(ni / 2, x, wrap)];
    return lo + t * (hi - lo);
}

// Everything below depends on the table's length, so it is written once as a macro and made for
// each size. (No `//` comments inside: the macro is one joined line.)
//
// colortable: the unfiltered lookup.
// _patina_ctable_cells(sat, total, i): the sum of the whole entries [0, i) of the table repeated
//   twice, for an integer i in [0, 2N].
// _patina_ctable_integral(table, sat, a, b, top): the integral over [a, b] (index units, one unit
//   per entry) of the table repeated (top = 2N, 0 <= a <= b <= 2N) or of the table alone (top = N,
//   0 <= a <= b <= N): the partial first and last entries weighted exactly, the whole ones between
//   from the summed-area table, so a narrow box loses nothing to cancellation.
// filteredcolortable: the box filter (see docs/stdlib/color.md for the cases); a box of 2^24 periods
//   or more is the mean of the table (the remainder is below f32's resolution, and periods times
//   the sum of large colours would overflow).
#define PATINA_COLOR_TABLE(N) \
color colortable(color table[N]; float x, wrap) \
{ \
    return table[_patina_ctable_entry(N, x, wrap)]; \
} \
color _patina_ctable_cells(color sat[N]; float i) \
{ \
    color part = 0; \
    float r = i; \
    if (r > N) { \
        part = sat[N - 1]; \
        r -= N; \
    } \
    if (r > 0) \
        part += sat[r - 1]; \
    return part; \
} \
color _patina_ctable_integral(color table[N]; color sat[N]; float a, b, top) \
{ \
    float ka = min(floor(a), top - 1), kb = min(floor(b), top - 1); \
    float ea = ka >= N ? ka - N : ka, eb = kb >= N ? kb - N : kb; \
    if (ka == kb) \
        return (b - a) * table[ea]; \
    return (ka + 1 - a) * table[ea] + (_patina_ctable_cells(sat, kb) - _patina_ctable_cells(sat, ka + 1)) \
           + (b - kb) * table[eb]; \
} \
color filteredcolortable(color table[N]; color sat[N]; float x, w, wrap) \
{ \
    if (w <= 0) \
        return colortable(table, x, wrap); \
    float len = N * w; \
    if (wrap != 0) { \
        float c = N * (x - floor(x)); \
        float periods = floor(len / N); \
        float r = clamp(len - periods * N, 0, N); \
        float a = c - len / 2; \
        a = a - N * floor(a / N); \
        a = clamp(a, 0, N); \
        float b = a + r; \
        float ka = min(floor(a), 2 * N - 1); \
        if (periods == 0 && ka == min(floor(b), 2 * N - 1)) \
            return table[ka >= N ? ka - N : ka]; \
        if (periods >= 16777216) \
            return sat[N - 1] / N; \
        return (periods * sat[N - 1] + _patina_ctable_integral(table, sat, a, b, 2 * N)) / (periods * N + (b - a)); \
    } \
    float c = N * x; \
    float a = c - len / 2, b = c + len / 2; \
    if (b <= 0) \
        return table[0]; \
    if (a >= N) \
        return table[N - 1]; \
    float a1 = max(a, 0), b1 = min(b, N); \
    if (a >= 0 && b <= N && floor(a) == min(floor(b), N - 1)) \
        return table[floor(a)]; \
    color sum = max(-a, 0) * table[0] + max(b - N, 0) * table[N - 1] \
                + _patina_ctable_integral(table, sat, a1, b1, N); \
    return sum / (b - a); \
} \
color filteredcolortable(color table[N]; float x, w, wrap) \
{ \
    color sat[N]; \
    PATINA_COLORTABLE_SAT(table, sat, N); \
    return filteredcolortable(table, sat, x, w, wrap); \
}

PATINA_COLOR_TABLE(2)
PATINA_COLOR_TABLE(3)
PATINA_COLOR_TABLE(4)
PATINA_COLOR_TABLE(5)
PATINA_COLOR_TABLE(6)
PATINA_COLOR_TABLE(7)
PATINA_COLOR_TABLE(8)
PATINA_COLOR_TABLE(9)
PATINA_COLOR_TABLE(10)
PATINA_COLOR_TABLE(11)
PATINA_COLOR_TABLE(12)
PATINA_COLOR_TABLE(13)
PATINA_COLOR_TABLE(14)
PATINA_COLOR_TABLE(15)
PATINA_COLOR_TABLE(16)
PATINA_COLOR_TABLE(17)
PATINA_COLOR_TABLE(18)
PATINA_COLOR_TABLE(19)
PATINA_COLOR_TABLE(20)
PATINA_COLOR_TABLE(21)
PATINA_COLOR_TABLE(22)
PATINA_COLOR_TABLE(23)
PATINA_COLOR_TABLE(24)
PATINA_COLOR_TABLE(25)
PATINA_COLOR_TABLE(26)
PATINA_COLOR_TABLE(27)
PATINA_COLOR_TABLE(28)
PATINA_COLOR_TABLE(29)
PATINA_COLOR_TABLE(30)
PATINA_COLOR_TABLE(31)
PATINA_COLOR_TABLE(32)
PATINA_COLOR_TABLE(48)
PATINA_COLOR_TABLE(64)
PATINA_COLOR_TABLE(128)
PATINA_COLOR_TABLE(256)

#endif
