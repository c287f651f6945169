// Shaping and pattern functions from Peachey's chapter of Texturing & Modeling
// (shared/seeds/002_a44091d2843c02ac.txt, lines 1160-1560 and 2040-2145), Perlin & Hoffert's bias
// and gain (same seed, L8126-8164), Schlick's rational bias and gain (Graphics Gems IV, 1994; cited
// at L1548 without a formula) and the box-filtered forms of Apodaca & Gritz's Advanced RenderMan
// (not in the seeds; see shared/notes/stdlib-catalogue.md §0).
//
// Argument order: the shaping parameter comes first and the value last, `bias(b, x)`,
// `gain(g, x)`, `gammacorrect(gamma, x)`, as in Peachey's listings (L1504, L1522, L1534) and the
// facial-animation code `gain(.9, bias(.3, T))` (L9710). Perlin's hypertexture code writes the
// other order, `bias(density, Bias)` (L8726); the library follows Peachey because it is the
// chapter the other functions here come from, and so that every shaping function of this file
// reads (parameters..., x).
//
// Filter convention: a filtered function `filteredf(..., x, w)` is the mean of `f` over the box
// [x - w/2, x + w/2] (centred, as in Advanced RenderMan; Peachey's chapter filters over
// [x, x + w], L2045). Each one returns the unfiltered `f(x)` for w <= 0, and tends to the mean of
// `f` over the whole line as w grows.
//
// Domains: bias, gain, schlickbias and schlickgain clamp x and their parameter to [0, 1] and are
// total there, corners included (seed errata H-D7: pow(0, 0), log(0) and the exponent
// ln(b)/ln(0.5) at b = 0 or 1 are never evaluated). No function here produces NaN or infinity for
// finite arguments of magnitude up to 1e30 with w >= 0.

#ifndef PATINA_PATTERN_SL
#define PATINA_PATTERN_SL

// The pulse: 1 on [a, b), 0 elsewhere. step(a, x) - step(b, x) (Peachey's PULSE macro, L1220).
// For b < a it is -1 on [b, a).
float pulse(float a, b, x)
{
    return step(a, x) - step(b, x);
}

// A linear ramp from 0 at a to 1 at b, clamped: clamp((x - a) / (b - a), 0, 1) (L2050). Defined
// for b > a; with b == a it is step(a, x) instead of 0/0 (errata H-D8).
float boxstep(float a, b, x)
{
    if (b == a)
        return step(a, x);
    return clamp((x - a) / (b - a), 0, 1);
}

// Gamma correction: x^(1/gamma) (L1504). For x <= 0 it is 0; gamma <= 0 is the limit
// gamma -> 0+ on [0, 1], step(1, x) (errata H-D7: no division by zero). A result beyond f32's
// range (x > 1 with a small gamma) is 1e38.
float gammacorrect(float gamma, x)
{
    if (x <= 0)
        return 0;
    if (gamma <= 0)
        return step(1, x);
    return min(pow(x, 1 / gamma), 1e38);
}

// Perlin's bias: x^(ln b / ln 0.5) (Peachey L1522; Perlin L8126-8138), with x and b clamped to
// [0, 1]. bias(b, 0) = 0, bias(b, 0.5) = b, bias(b, 1) = 1; bias(0.5, x) = x. At b = 0 and b = 1
// it is the pointwise limit: 0 on [0, 1) (b = 0), 1 on (0, 1] (b = 1).
float bias(float b, x)
{
    float t = clamp(x, 0, 1);
    if (t <= 0)
        return 0;
    if (t >= 1)
        return 1;
    if (b <= 0)
        return 0;
    if (b >= 1)
        return 1;
    return pow(t, log(b) / log(0.5));
}

// Perlin's gain, in Peachey's (correct) form (L1534-1545; Perlin's printed form has its
// condition reversed, L8144): bias(1 - g, 2x) / 2 for x < 0.5, else 1 - bias(1 - g, 2 - 2x) / 2.
// gain(g, 0.5) = 0.5, gain(g, 0.25) = (1 - g) / 2; gain(0.5, x) = x; an S curve for g > 0.5, an
// inverted one for g < 0.5. x and g are clamped to [0, 1] through bias.
float gain(float g, x)
{
    if (x < 0.5)
        return bias(1 - g, 2 * x) / 2;
    else
        return 1 - bias(1 - g, 2 - 2 * x) / 2;
}

// Schlick's rational bias with its parameter b given twice, as b and as 1 - b, for
// schlickgain, which knows 1 - b = g exactly: b x / ((1 - b)(1 - x) + b x) with x clamped to
// [0, 1]. b in [0, 1] (callers clamp it).
float _patina_schlickbias(float b, one_minus_b, x)
{
    float t = clamp(x, 0, 1);
    if (t <= 0)
        return 0;
    if (t >= 1)
        return 1;
    return b * t / (one_minus_b * (1 - t) + b * t);
}

// Schlick's rational bias (Graphics Gems IV, 1994; cited by Peachey at L1548):
// x / ((1/b - 2)(1 - x) + 1), written as b x / ((1 - b)(1 - x) + b x) so that b = 0 needs no
// division by zero. Same shape and fixed points as bias: schlickbias(b, 0.5) = b, 0 at x = 0, 1 at
// x = 1, the identity at b = 0.5. x and b are clamped to [0, 1]; the denominator is then positive
// except at the corners (b, x) = (1, 0) and (0, 1), which return 0 and 1.
float schlickbias(float b, x)
{
    float c = clamp(b, 0, 1);
    return _patina_schlickbias(c, 1 - c, x);
}

// Schlick's rational gain, built from schlickbias exactly as Peachey builds gain from bias
// (L1534-1545), so that it takes the same parameter: schlickbias(1 - g, 2x) / 2 for x < 0.5, else
// 1 - schlickbias(1 - g, 2 - 2x) / 2. schlickgain(g, 0.5) = 0.5, schlickgain(g, 0.25) = (1 - g)/2.
// g is clamped to [0, 1], and 1 - (1 - g) is taken as g itself, which keeps small g accurate.
float schlickgain(float g, x)
{
    float c = clamp(g, 0, 1);
    if (x < 0.5)
        return _patina_schlickbias(1 - c, c, 2 * x) / 2;
    else
        return 1 - _patina_schlickbias(1 - c, c, 2 - 2 * x) / 2;
}

// Peachey's pulse train, the mortar pattern of his brick (L1559-1620): in every period of length
// `period`, 0 on the first and last `edge` of it and 1 between, that is
// pulse(e, 1 - e, frac(x / period)) with e = edge / period clamped to [0, 0.5]. (Advanced
// RenderMan's pulsetrain is 0 only on the first `edge`; this one is symmetric, as the brick's.)
float pulsetrain(float edge, period, x)
{
    float e = clamp(edge / period, 0, 0.5);
    float t = x / period;
    return pulse(e, 1 - e, t - floor(t));
}

// The box-filtered step: the mean of step(edge, .) over [x - w/2, x + w/2],
// clamp((x - edge) / w + 1/2, 0, 1), the ramp boxstep(edge - w/2, edge + w/2, x) (Peachey
// L2045-2050, centred). step(edge, x) for w <= 0; tends to 1/2 as w grows.
float filteredstep(float edge, x, w)
{
    if (w <= 0)
        return step(edge, x);
    return clamp((x - edge) / w + 0.5, 0, 1);
}

// Advanced RenderMan's name for the antialiased step; here with an explicit filter width w
// (pass filterwidth(x)). The same as filteredstep.
float aastep(float edge, x, w)
{
    return filteredstep(edge, x, w);
}

// The box-filtered pulse: the mean of pulse(a, b, .) over [x - w/2, x + w/2]. By linearity it is
// filteredstep(a, x, w) - filteredstep(b, x, w); each ramp is computed relative to its own edge, so
// that a narrow filter far from the origin loses no precision (the Advanced RenderMan form
// (min(x1, b) - max(x0, a)) / w cancels when w is below the spacing of floats at x).
// pulse(a, b, x) for w <= 0; tends to 0 as w grows.
float filteredpulse(float a, b, x, w)
{
    if (w <= 0)
        return pulse(a, b, x);
    return filteredstep(a, x, w) - filteredstep(b, x, w);
}

// The integral from 0 to t of Peachey's unit-period pulse train with margin e, for any t:
// floor(t) (1 - 2e) + min(1 - 2e, max(0, t - floor(t) - e)) (Peachey's sintegral, L2130-2137, with
// the upper clamp it lacks: errata §3.6 / catalogue §2.3; without it the integral jumps by -e at
// every integer).
float _patina_pulsetrain_integral(float e, t)
{
    float n = floor(t);
    return n * (1 - 2 * e) + min(1 - 2 * e, max(0, t - n - e));
}

// The box-filtered pulse train: the mean of pulsetrain(edge, period, .) over [x - w/2, x + w/2].
// In units of the period, with c the position of x within its period and h = w / (2 period):
// for h >= 1/2, (I(c + h) - I(c - h)) / 2h with I the integral above (Peachey L2137); for a
// narrower filter, which meets at most three pulses, the sum of the three filtered pulses
// (k + e, k + 1 - e) for k = -1, 0, 1, which stays exact as w -> 0 where the difference of
// integrals would cancel. pulsetrain(edge, period, x) for w <= 0; tends to the duty cycle
// 1 - 2e as w grows. Period 0 is pulsetrain's; where x / period or w / period overflows f32
// (1e30 over 1e-30), x is taken as the start of a period and the filter as infinitely wide.
float filteredpulsetrain(float edge, period, x, w)
{
    if (w <= 0 || period == 0)
        return pulsetrain(edge, period, x);
    float e = clamp(edge / period, 0, 0.5);
    float t = x / period;
    float c = abs(t) < 1e38 ? t - floor(t) : 0;
    float h = w / (2 * period);
    if (abs(h) >= 1e38)
        return 1 - 2 * e;
    if (h >= 0.5)
        return (_patina_pulsetrain_integral(e, c + h) - _patina_pulsetrain_integral(e, c - h)) / (2 * h);
    float fw = 2 * h;
    return filteredpulse(e - 1, -e, c, fw) + filteredpulse(e, 1 - e, c, fw)
           + filteredpulse(1 + e, 2 - e, c, fw);
}

// The box-filtered absolute value: the mean of |.| over [x - w/2, x + w/2]. With h = w/2: |x|
// when the box does not straddle 0 (|x| >= h), else (x^2 + h^2) / 2h, written (x (x / h) + h) / 2
// so that it cannot overflow (Advanced RenderMan's (F(x1) - F(x0)) / w with F(t) = t|t|/2, in a
// form without cancellation). |x| for w <= 0; grows as w/4 for a wide box, the mean of |.| there.
float filteredabs(float x, w)
{
    float h = w / 2;
    if (abs(x) >= h)
        return abs(x);
    return (x * (x / h) + h) / 2;
}

// sin(2 pi t) for any finite t, with the range reduction done here (DESIGN §7: WGSL specifies sin
// only on [-pi, pi]): r = t - floor(t + 1/2) is in [-1/2, 1/2] and exact for |t| < 2^22 in f32,
// so sin sees 2 pi r in [-pi, pi] on both backends, the same argument bit for bit.
// (2 pi as a literal, not 2 * PI: the WGSL backend's compute kernels read PI as 0, a compiler bug;
// the literal rounds to 2 * PI exactly in f32 and is 2 pi to the last bit in f64.)
float _patina_sin2pi(float t)
{
    float r = t - floor(t + 0.5);
    return sin(6.283185307179586 * r);
}

#ifndef PATINA_PATTERN_MAX_TERMS
#define PATINA_PATTERN_MAX_TERMS 30
#endif

// Peachey's spectral synthesis with sinusoids, antialiased by clamping (L1995-2027; catalogue
// §1.4 and §2.4): the sum over f = minfreq, 2 minfreq, 4 minfreq, ... while f < maxfreq of
// fade(f) sin(2 pi f x) / f, each term faded out as its frequency approaches the Nyquist limit
// 0.5 / w of the filter width w (in the units of x): fade(f) = clamp(2 (cutoff - f) / cutoff, 0, 1)
// with cutoff = 0.5 / w, i.e. clamp(2 - 4 f w, 0, 1): 1 below cutoff / 2, 0 from cutoff on, linear
// between (Peachey's fade, L2021). Departure: Peachey takes cutoff = clamp(0.5 / swidth, 0, MAXFREQ),
// which also fades the term in [MAXFREQ/2, MAXFREQ) when nothing is filtered; here maxfreq only
// bounds the terms, so w = 0 gives the plain sum (L2003) and the result is continuous in w.
// At most PATINA_PATTERN_MAX_TERMS (30) terms. Range reduction: x = floor(x) + frac(x) and
// sin(2 pi f x) = sin(2 pi (frac(f floor(x)) + f frac(x))), with frac(f floor(x)) carried from
// term to term by exact doubling, so an integer minfreq keeps full precision at any |x| (the phase
// of the integer part is then exactly 0). Guards: minfreq <= 0 gives 0 (no terms); minfreq is
// taken as at least 1e-30; a frequency that overflows is >= maxfreq and adds nothing. The loop
// always runs its 30 iterations, skipping the terms from maxfreq on. |result| < 2 / minfreq.
float sinesum(float x, w, minfreq, maxfreq)
{
    float on = minfreq > 0 ? 1 : 0;
    float f = max(minfreq, 1e-30);
    float xi = floor(x);
    float xf = x - xi;
    float t = f * xi;
    // Beyond 2^53 every float is an integer (in f32 and f64): the phase of the integer part is 0.
    float phase = abs(t) < 1e30 ? t - floor(t) : 0;
    float ww = max(w, 0);
    float value = 0;
    // A plain float counter, not `constant`: sinesum may then be called under a varying
    // condition (a constant declaration there is E0605).
    float i;
    for (i = 0; i < PATINA_PATTERN_MAX_TERMS; i += 1) {
        if (on != 0 && f < maxfreq) {
            float fade = clamp(2 - 4 * f * ww, 0, 1);
            value += fade * _patina_sin2pi(phase + f * xf) / f;
        }
        f *= 2;
        phase = 2 * phase;
        phase -= floor(phase);
    }
    return value;
}

// Peachey's brick (L1559-1620, with the printed listing's `th` read as `h`, L1612; catalogue
// §3.6): 1 in a brick, 0 in the mortar. The brick repeats every (brickwidth + mortar) in s and
// (brickheight + mortar) in t, with mortar / 2 on each side of a brick (MWF, MHF, L1576), and
// alternate rows shifted by half a brick (L1598: odd rows, mod(tt / 2, 1) > 0.5). Sizes are
// clamped to >= 0 and the periods to >= 1e-6.
float brick(float s, t, brickwidth, brickheight, mortar)
{
    float m = max(mortar, 0);
    float bmw = max(max(brickwidth, 0) + m, 1e-6), bmh = max(max(brickheight, 0) + m, 1e-6);
    float mwf = m * 0.5 / bmw, mhf = m * 0.5 / bmh;
    float ss = s / bmw, tt = t / bmh;
    if (mod(tt * 0.5, 1) > 0.5)
        ss += 0.5;
    ss -= floor(ss);
    tt -= floor(tt);
    float w = step(mwf, ss) - step(1 - mwf, ss);
    float h = step(mhf, tt) - step(1 - mhf, tt);
    return w * h;
}

// The box-filtered brick: the exact mean of brick(s, t, ...) over the box
// [s - swidth/2, s + swidth/2] x [t - twidth/2, t + twidth/2] (pass filterwidth(s),
// filterwidth(t)). Peachey antialiases the brick with the integrals of its pulse trains (L2120-
// 2141, the `sintegral` errata: the upper clamp, pattern.sl's filteredpulsetrain), but filters s
// with the row shift of the point's own row, which is wrong once the box spans two rows. Here the
// shift is exact: the brick is Weven(s) Heven(t) + Wodd(s) Hodd(t), with Heven, Hodd the
// indicators of the even and odd rows' bricks in t (pulse trains of period 2) and Weven, Wodd the
// s pulse trains unshifted and shifted by half a brick; the box mean of each product is the
// product of the box means, each a filteredpulsetrain. swidth, twidth <= 0 filter nothing in that
// direction (both <= 0 give brick(...) up to rounding at the mortar edges).
float filteredbrick(float s, t, swidth, twidth, brickwidth, brickheight, mortar)
{
    float m = max(mortar, 0);
    float bmw = max(max(brickwidth, 0) + m, 1e-6), bmh = max(max(brickheight, 0) + m, 1e-6);
    float mwf = m * 0.5 / bmw, mhf = m * 0.5 / bmh;
    float ss = s / bmw, tt = t / bmh;
    float sw = swidth / bmw, tw = twidth / bmh;
    float heven = filteredpulsetrain(0.5 + mhf, 2, tt + 0.5, tw);
    float hodd = filteredpulsetrain(0.5 + mhf, 2, tt - 0.5, tw);
    float weven = filteredpulsetrain(mwf, 1, ss, sw);
    float wodd = filteredpulsetrain(mwf, 1, ss + 0.5, sw);
    return weven * heven + wodd * hodd;
}

#endif
