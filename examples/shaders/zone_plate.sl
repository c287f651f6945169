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

// sweep: s in [-1e4, 1e4]; t in [-1e4, 1e4] (texture coordinates: past 1e19 s^2 overflows f32)
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

// The exact average of frac(a + b t^2) over t in [t0, t1] (0 <= t0 < t1, b > 0): on each piece
// where floor(a + b t^2) = k is constant, the integral of a - k + b t^2; the pieces end where the
// ramp crosses an integer, at t = sqrt((k + 1 - a) / b). A segment of no length (t1 <= t0: a
// footprint without derivatives) averages over its point, frac(a + b t0^2). The loop visits every
// stripe the segment crosses, b (t1^2 - t0^2) of them, and needs a + b t^2 to keep whole numbers
// apart in f32 (|a| well below 2^24).
// sweep: a in [-1e6, 1e6]; b in [0, 1e4]; t0 in [0, 1]; t1 in [0, 1]
float zone_plate_line_average(float a, b, t0, t1)
{
    float sum = 0;
    float lo = t0;
    float k = floor(a + b * t0 * t0);
    if (t1 <= t0)
        return a + b * t0 * t0 - k;
    while (lo < t1) {
        // Clamped: rounding must not step backwards or past the segment.
        float hi = clamp(sqrt(max(k + 1 - a, 0) / b), lo, t1);
        sum += (a - k) * (hi - lo) + b * (hi * hi * hi - lo * lo * lo) / 3;
        lo = hi;
        k += 1;
    }
    return sum / (t1 - t0);
}

// The exact image of `zone_plate`, the reference `patina bench` measures its antialiasing
// against: the zebra ramp frac(f) averaged over each pixel's box in (s, t), exactly along t and by
// 5-point Gauss-Legendre quadrature on `panels` panels along s (the line average is continuous
// in s, so the quadrature converges fast; runtime/tests/gallery/solid.rs checks the same integral
// written independently in Rust). On this screen-aligned plane the box is ds by dt, with the
// analytic derivatives of the CPU reference.
// sweep: s in [-1e4, 1e4]; t in [-1e4, 1e4] (texture coordinates: past 1e19 s^2 overflows f32)
surface
zone_plate_exact(float frequency = 50; float panels = 64)
{
    float ds = filterwidth(s), dt = filterwidth(t);
    float s0 = max(s - 0.5 * ds, 0), t0 = max(t - 0.5 * dt, 0), t1 = t0 + dt;
    uniform float n = clamp(floor(panels), 1, 256);
    float h = ds / n;
    constant float node[5] = {0, -0.5384693101056831, 0.5384693101056831, -0.9061798459386640, 0.9061798459386640};
    constant float weight[5] = {0.5688888888888889, 0.4786286704993665, 0.4786286704993665, 0.2369268850561891, 0.2369268850561891};
    float sum = 0;
    uniform float i, j;
    for (i = 0; i < n; i += 1) {
        float mid = s0 + (i + 0.5) * h;
        for (j = 0; j < 5; j += 1) {
            float ss = mid + 0.5 * h * node[j];
            sum += 0.5 * weight[j] * zone_plate_line_average(frequency * ss * ss, frequency, t0, t1);
        }
    }
    Ci = sum / n;
    Oi = 1;
}
