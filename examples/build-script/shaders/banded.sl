// Stripes along t, from an included helper.
#include "bands.sl"

surface banded(float count = 8; color bright = color(0.9, 0.8, 0.6); color dark = color(0.3, 0.2, 0.1);
               float Kd = 0.8)
{
    normal Nf = faceforward(normalize(N), I);
    color c = mix(dark, bright, band(t, count));
    Oi = Os;
    Ci = Os * c * (Kd * diffuse(Nf) + 0.1);
}
