// Hart's zone plate (APST (16), shared/seeds/004_dc0e594aa54d1617.txt L284-288; digest §3.1 and
// §12 S9): f = 50 s^2 + 50 t^2 over the unit square through a two-entry "zebra" colour map taken
// modulo one (hart_colormap of <solid.sl>: each ring ramps from black to white and jumps back).
//
// `aa` chooses the colour-index filter width w of the box filter (APST (9)):
//   0: none (point sampling);
//   1: analytic, ||grad f|| times the pixel's footprint in (s, t), grad f = (100 s, 100 t);
//   2: fwidth: filterwidth(f), |df/dx| + |df/dy| by automatic differentiation;
//   3: Hart's width (100 s ds + 100 t dt) (L288), the analytic gradient's L1 form.
// `split` 1 point-samples the lower-left half (t > s) whatever `aa` is: f is symmetric in s and t,
// so the two halves are mirror images, unfiltered and filtered. `samples` k (the cost knob)
// averages k x k evaluations spread over the pixel, each filtered at a k-th of the width: aa 0
// with a large k is the supersampled reference.
#include <solid.sl>

surface
zone_plate(float aa = 1;
           float split = 1;
           float samples = 1;
           float frequency = 50)
{
    constant color zebra[2] = {color (0, 0, 0), color (1, 1, 1)};
    float ds = filterwidth(s), dt = filterwidth(t);
    float f = frequency * (s * s + t * t);
    float wa = 2 * frequency * sqrt(s * s + t * t) * 0.5 * (ds + dt);
    float wf = filterwidth(f);
    float wh = 2 * frequency * (abs(s) * ds + abs(t) * dt);
    float w = aa < 0.5 ? 0 : (aa < 1.5 ? wa : (aa < 2.5 ? wf : wh));
    w = split > 0.5 && t > s ? 0 : w;

    // Supersampling across the pixel: on this screen-aligned plane s follows the raster x axis
    // and t the y axis, so the footprint is ds by dt.
    uniform float k = clamp(floor(samples), 1, 16);
    color c = 0;
    uniform float i, j;
    for (j = 0; j < k; j += 1) {
        for (i = 0; i < k; i += 1) {
            float ss = s + ((i + 0.5) / k - 0.5) * ds, tt = t + ((j + 0.5) / k - 0.5) * dt;
            float fs = frequency * (ss * ss + tt * tt);
            c += hart_colormap(fs, w / k, HART_MOD, zebra, 2);
        }
    }
    Ci = c / (k * k);
    Oi = 1;
}
