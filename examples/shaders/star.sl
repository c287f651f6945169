// Peachey's five-pointed star (Texturing & Modeling ch. 2, L1753-1816) in polar feature space:
// each point of the star is a wedge of 2 pi / npoints, and each half-wedge is bounded by one
// edge, from the tip at radius rmax to the inner vertex at radius rmin; a sample inside the
// triangle (centre, tip, inner vertex) of its half-wedge is inside the star. Departures from
// the listing: the angle within the half-wedge is a * starangle (the listing takes the fraction
// a in [0, 0.5] itself as an angle in radians, stdlib-catalogue §3.6), and the edge is
// box-filtered: the signed distance to the edge through filteredstep (compiler/stdlib/pattern.sl) over
// the pixel's width in (s, t), instead of step's hard edge. `samples` (the cost knob) splits the
// pixel's footprint into samples x samples sub-pixels, each filtered over its own width.
// `saspect` stretches s, so that the star is not squashed on a sphere, whose s runs twice as
// far as its t.
#include <pattern.sl>

// 1 inside the star centred at the origin, 0 outside, the edge box-filtered over width w.
float star_coverage(float x, y, rmin, rmax, npoints, w)
{
    float starangle = 2 * PI / npoints;
    point p0 = point(rmax, 0, 0);
    point pi = rmin * point(cos(starangle / 2), sin(starangle / 2), 0);
    vector d0 = pi - p0;
    float angle = atan(x, y) + PI;
    float r = sqrt(x * x + y * y);
    float a = mod(angle, starangle) / starangle;
    if (a >= 0.5)
        a = 1 - a;
    vector d1 = r * point(cos(a * starangle), sin(a * starangle), 0) - p0;
    // zcomp(d0 ^ d1) / |d0| is the signed distance from the edge's line, positive inside.
    float inside = zcomp(d0 ^ d1) / length(d0);
    return filteredstep(0, inside, w);
}

// The cost knob: samples^2 sub-pixels (past 65535 per side the interpreter's loop budget stops).
// sweep: samples in [1, 16]
surface star(float Ka = 1; float Kd = 1;
             color starcolor = color(1.0000, 0.5161, 0.0000);
             float npoints = 5; float sctr = 0.5; float tctr = 0.5;
             float rmin = 0.07; float rmax = 0.2; float saspect = 1;
             float samples = 1)
{
    // Not faceforward: on a closed ball N faces the eye wherever it is seen, and at the
    // silhouette, where N . I is 0 to rounding, the two backends would flip it on different pixels.
    normal Nf = normalize(N);
    float ss = (s - sctr) * saspect, tt = t - tctr;
    float n = max(1, floor(samples));
    float dsu = Du(ss) * du, dsv = Dv(ss) * dv, dtu = Du(tt) * du, dtv = Dv(tt) * dv;
    float w = max(filterwidth(ss), filterwidth(tt)) / n;
    float in_out = 0;
    for (float i = 0; i < n; i += 1) {
        for (float j = 0; j < n; j += 1) {
            float a = (i + 0.5) / n - 0.5, b = (j + 0.5) / n - 0.5;
            in_out += star_coverage(ss + a * dsu + b * dsv, tt + a * dtu + b * dtv, rmin, rmax, npoints, w);
        }
    }
    in_out /= n * n;
    color Ct = mix(Cs, starcolor, in_out);
    Oi = Os;
    Ci = Os * Ct * (Ka * ambient() + Kd * diffuse(Nf));
}
