// Swatch for docs/stdlib/pattern.md: Peachey's brick, box-filtered by filteredbrick with the
// filter widths of s and t, over a rising frequency (left: few bricks, right: many).
#include <pattern.sl>

surface pattern_brick_swatch()
{
    float ss = s * (1 + 6 * s) * 2, tt = t * 2;
    float b = filteredbrick(ss, tt, filterwidth(ss), filterwidth(tt), 0.25, 0.08, 0.02);
    Ci = mix(color(0.5, 0.5, 0.5), color(0.55, 0.16, 0.12), b);
    Oi = 1;
}
