// Swatch for docs/stdlib/pattern.md: top half Peachey's sinusoid sum unfiltered (w = 0), bottom
// half with the terms above the Nyquist limit of filterwidth faded out; the frequency rises to the
// right.
#include <pattern.sl>

surface pattern_sinesum_swatch()
{
    float x = s * (1 + 20 * s);
    float w = t < 0.5 ? 0 : filterwidth(x);
    Ci = 0.5 + 0.3 * sinesum(x, w, 1, 4096);
    Oi = 1;
}
