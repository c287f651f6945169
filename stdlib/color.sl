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
// Table sizes: the functions are defined for arrays of 2 to 32, 48, 64, 128 and 256 colours. The
// language's open-length array parameters (`color table[]`) cannot be used for this yet (a compiler
// bug: inside an inlined function every element of such a parameter reads as element 0), so each
// size is its own overload, made by the macro PATINA_COLOR_TABLE(N); write
// `PATINA_COLOR_TABLE(20)` at the top level of a shader file, after the #include, for another
// size.
//
// Colour spaces and colour splines are built in: ctransform and the colour casts
// (`color "hsv" (h, s, v)`) convert between rgb, hsv, hsl, xyz/XYZ, xyY and YIQ, and spline takes
// colour knots, listed or in an array (docs/builtins.md); docs/stdlib/color.md documents and tests
// them. Nothing of them is rewritten here.

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
// with an `output` array parameter, because of a second compiler bug: a function with an `output`
// parameter that no shader calls fails to check (E0507 on the parameter), and every size but the
// one a shader uses is uncalled. Its loop counter is a plain (varying) float, not `constant`, so
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
// filteredcolortable: the box filter (see docs/stdlib/color.md for the cases).
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
