// A reference panel of the standard library's noises: the unit (s, t) square cut into 6 x 5
// tiles, each a z-slice (z = `slice`) of one variant over `frequency` lattice cells per tile side,
// mapped to grey. Tiles, left to right, top to bottom (tile index k = 6 row + column):
//   row 0, gradient noise: snoise3 (improved noise, signed), noise3 (unsigned), snoise2 (2D
//     improved noise), psnoise3 (period 2 cells), flownoise3 (angle 1), snoise4 (w = 0.3)
//   row 1, lattice noise: vnoise (value, Catmull-Rom), vnoise_linear, gnoise (Peachey's gradient),
//     vgnoise (value-gradient), vcnoise (lattice convolution), scnoise (sparse convolution)
//   row 2: cellnoise3, worley_f1, worley_f2_f1, worley_manhattan_f1, distnoise (distortion 1),
//     distfbm
//   row 3, fractal sums: fbm, fbm_filtered (octaves limited by the pixel's filter width),
//     turbulence, ridged_multifractal, hybrid_multifractal, hetero_terrain
//   row 4, the rest of noise.sl: perlin_noise3 (Perlin's 1985 noise), snoise1 (1D improved
//     noise of x), noise2 (unsigned 2D), pnoise3 (unsigned, period 2 cells), vsnoise3's x
//     (vector noise) and dsnoise3's x (the analytic gradient of improved noise)
// The grey of tile k is `offset + gain * value` with the pair chosen per variant from its range
// (docs/stdlib/*.md), so every tile spans a visible range; the grey is not clamped, so a test can
// read the value back. Between the tiles is a blue gutter (never grey: R, G and B differ).
// The cost knob is `octaves`, used by the fractal tiles (rows 2 and 3 from distfbm on).
#include <fractal.sl>
#include <lattice.sl>
#include <cellular.sl>

#define COLUMNS 6
#define ROWS 5

surface noise_panel(float octaves = 6; float frequency = 4; float slice = 0.37;
                    float gutter = 0.05)
{
    float cs = s * COLUMNS, ct = t * ROWS;
    float col = clamp(floor(cs), 0, COLUMNS - 1), row = clamp(floor(ct), 0, ROWS - 1);
    float u = cs - col, v = ct - row;
    float k = row * COLUMNS + col;
    // Each tile sees its own region of noise space (the offsets keep tiles from repeating one
    // another), z fixed: a z-slice. Two pairs share a region, so that their identities can be
    // checked pixel for pixel: noise3 (tile 1) with snoise3 (tile 0), and Manhattan F1 (tile 15)
    // with Euclidean F1 (tile 13).
    float region = k == 1 ? 0 : (k == 15 ? 13 : k);
    point p = point(frequency * u + 17 * region, frequency * v + 5 * region, slice);
    float value = 0, offset = 0.5, gain = 0.5;
    if (k < 6) {
        if (k == 0) {
            value = snoise3(p);
        } else if (k == 1) {
            value = noise3(p);
            offset = 0;
            gain = 1;
        } else if (k == 2) {
            value = snoise2(p[0], p[1]);
        } else if (k == 3) {
            value = psnoise3(p, point(2, 2, 2));
        } else if (k == 4) {
            value = flownoise3(p, 1);
        } else {
            value = snoise4(p, 0.3);
            gain = 0.6;
        }
    } else if (k < 12) {
        if (k == 6) {
            value = vnoise(p);
            gain = 0.4;
        } else if (k == 7) {
            value = vnoise_linear(p);
        } else if (k == 8) {
            value = gnoise(p);
            gain = 0.85;
        } else if (k == 9) {
            value = vgnoise(p);
            gain = 0.7;
        } else if (k == 10) {
            value = vcnoise(p);
            gain = 0.38;
        } else {
            value = scnoise(p);
            gain = 0.7;
        }
    } else if (k < 18) {
        if (k == 12) {
            value = cellnoise3(p, 0);
            offset = 0;
            gain = 1;
        } else if (k < 16) {
            // Worley's F1 (13), F2 - F1 (14) and Manhattan F1 (15) from one inlined basis.
            matrix wb = worley_basis(p, k == 15 ? 1 : 0);
            value = k == 14 ? wb[0][1] - wb[0][0] : wb[0][0];
            offset = 0;
            gain = k == 13 ? 0.5 : (k == 14 ? 1 : 0.33);
        } else if (k == 16) {
            value = distnoise(p, 1);
        } else {
            value = distfbm(p, 0.5, 2, octaves, 1);
            gain = 0.45;
        }
    } else if (k < 24) {
        if (k == 18) {
            value = fbm(p, 0.5, 2, octaves);
            gain = 0.45;
        } else if (k == 19) {
            float w = max(filterwidth(p[0]), filterwidth(p[1]));
            value = fbm_filtered(p, 0.5, 2, octaves, w);
            gain = 0.45;
        } else if (k == 20) {
            value = turbulence(p, octaves);
            offset = 0;
            gain = 1.2;
        } else if (k == 21) {
            value = ridged_multifractal(p, 1, 2, octaves, 1, 2);
            offset = 0;
            gain = 0.5;
        } else if (k == 22) {
            value = hybrid_multifractal(p, 0.25, 2, octaves, 0.7);
            offset = 0;
            gain = 0.3;
        } else {
            value = hetero_terrain(p, 0.25, 2, octaves, 0.3);
            offset = 0.3;
            gain = 0.3;
        }
    } else {
        if (k == 24) {
            value = perlin_noise3(p);
            gain = 0.6;
        } else if (k == 25) {
            value = snoise1(p[0]);
        } else if (k == 26) {
            value = noise2(p[0], p[1]);
            offset = 0;
            gain = 1;
        } else if (k == 27) {
            value = pnoise3(p, point(2, 2, 2));
            offset = 0;
            gain = 1;
        } else if (k == 28) {
            value = vsnoise3(p)[0];
        } else {
            value = dsnoise3(p)[0];
            gain = 0.25;
        }
    }
    float edge = min(min(u, 1 - u), min(v, 1 - v));
    Ci = edge < gutter ? color(0.1, 0.15, 0.3) : color(offset + gain * value);
    Oi = 1;
}
