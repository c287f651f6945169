// Shaping and pattern functions from Peachey's chapter of Texturing & Modeling
// (shared/seeds/002_a44091d2843c02ac.txt, lines 1160-1560) and Perlin & Hoffert's bias and gain.
// Issue 7 extends this module; the argument orders follow the book's listings.

#ifndef PATINA_PATTERN_SL
#define PATINA_PATTERN_SL

// 1 on [a, b), 0 elsewhere.
float pulse(float a, b, x)
{
    return step(a, x) - step(b, x);
}

// A linear ramp from 0 at a to 1 at b, clamped.
float boxstep(float a, b, x)
{
    return clamp((x - a) / (b - a), 0, 1);
}

float gammacorrect(float gamma, x)
{
    return pow(x, 1 / gamma);
}

// bias(b, 0.5) = b.
float bias(float b, x)
{
    return pow(x, log(b) / log(0.5));
}

// gain(g, 0.5) = 0.5; an S curve for g < 0.5, an inverted one for g > 0.5.
float gain(float g, x)
{
    if (x < 0.5)
        return bias(1 - g, 2 * x) / 2;
    else
        return 1 - bias(1 - g, 2 - 2 * x) / 2;
}

#endif
