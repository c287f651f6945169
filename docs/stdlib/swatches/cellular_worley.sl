// Swatch for docs/stdlib/cellular.md: Worley's basis over (16s, 16t): F1 (top left), F2 - F1 (top right), F1 Manhattan (bottom left), flagstones: the nearest point's id as a colour, darkened near the cell edges (bottom right).
#include <cellular.sl>

surface cellular_worley_swatch(float scale = 16)
{
    point p = point(scale * s, scale * t, 0.5);
    float manhattan = t >= 0.5 && s < 0.5 ? 1 : 0;
    matrix w = worley_basis(p, manhattan);
    float f1 = w[0][0], f2 = w[0][1];
    float id = w[1][3];
    color flag = color(0.4 + 0.5 * id, 0.35 + 0.3 * mod(id * 7, 1), 0.3) * smoothstep(0, 0.15, f2 - f1);
    Ci = t < 0.5 ? (s < 0.5 ? color(0.6 * f1) : color(2 * (f2 - f1))) : (s < 0.5 ? color(0.5 * f1) : flag);
    Oi = 1;
}
