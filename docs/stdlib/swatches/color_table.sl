// Swatch for docs/stdlib/color.md: an 8-colour table over a zone plate f = 150 (s^2 + t^2),
// wrapped; left half unfiltered (colortable), right half box-filtered over the index's filter
// width (filteredcolortable, Hart's summed-area colour table).
#include <color.sl>

surface color_table_swatch()
{
    constant color tab[8] = {color(0.9, 0.9, 0.8), color(0.9, 0.6, 0.2), color(0.7, 0.2, 0.1), color(0.2, 0.1, 0.1),
                             color(0.1, 0.3, 0.5), color(0.2, 0.6, 0.8), color(0.6, 0.8, 0.9), color(1, 1, 1)};
    float f = 150 * (s * s + t * t);
    if (s < 0.5)
        Ci = colortable(tab, f, 1);
    else
        Ci = filteredcolortable(tab, f, filterwidth(f), 1);
    Oi = 1;
}
