// A box-filtered brick wall: macros, uniform parameters, `if`, compound assignment and the
// filtered pulse train of the antialiasing chapter.
#include "pattern.sl"

#define BRICK_WIDTH 0.25
#define BRICK_HEIGHT 0.08
#define MORTAR 0.01
#define BM_WIDTH (BRICK_WIDTH + MORTAR)
#define BM_HEIGHT (BRICK_HEIGHT + MORTAR)
#define MWF (MORTAR * 0.5 / BM_WIDTH)
#define MHF (MORTAR * 0.5 / BM_HEIGHT)

// The box-filtered brick (1) or mortar (0) across one axis: the mean over [x - width/2,
// x + width/2] of a pulse train of period 1 that is 1 on [edge, 1 - edge]. Peachey averages his
// integral `sintegral` (L2126), which lacks the upper clamp at 1 - edge; pattern.sl's
// filteredpulsetrain has it, and gives the pulse itself where the footprint has no width (no
// derivatives, or s constant across the pixel), where the difference quotient would be 0/0.
float filtered_pulse_train(float edge, x, width)
{
    return filteredpulsetrain(edge, 1, x, width);
}

surface
bricks(uniform float Ka = 1, Kd = 1;
       uniform color brick_color = color "rgb" (0.5, 0.15, 0.14);
       uniform color mortar_color = color (0.5, 0.5, 0.5);
       uniform float antialias = 1)
{
    varying float ss = s / BM_WIDTH;
    varying float tt = t / BM_HEIGHT;
    float w, h;

    if (mod(tt * 0.5, 1) > 0.5)
        ss += 0.5; /* shift alternate rows */
    else {
        ss -= 0;
    }
    ss -= floor(ss);
    tt -= floor(tt);
    if (antialias != 0) {
        float sw = filterwidth(ss), tw = filterwidth(tt);
        w = filtered_pulse_train(MWF, ss, sw);
        h = filtered_pulse_train(MHF, tt, tw);
    } else {
        w = pulse(MWF, 1 - MWF, ss);
        h = pulse(MHF, 1 - MHF, tt);
    }
    color Ct = mix(mortar_color, brick_color, w * h);
    normal Nf = faceforward(normalize(N), I);
    Oi = Os;
    Ci = Os * Ct * (Ka * ambient() + Kd * diffuse(Nf));
}
