// A planet after Musgrave (Texturing & Modeling ch. 14-16: multifractal terrain as a height
// field over the sphere): the height is stdlib's hybrid multifractal of the object-space point
// on the unit sphere, and the colour follows the height: deep to shallow ocean below `sealevel`,
// a beach just above it, green lowlands to brown highlands and snow on the peaks, and polar caps
// where the latitude (object z, the sphere's axis) plus a little of the height passes `icecap`.
// The ocean is shiny, the land matte. The cost knob is `octaves`.
#include <fractal.sl>

surface planet(float Ka = 1; float Kd = 0.9; float Ks = 0.3; float roughness = 0.05;
               float octaves = 8; float frequency = 1.7; float H = 0.25; float offset = 0.7;
               float sealevel = 1.75; float icecap = 0.78)
{
    point Po = transform("object", P);
    point pn = normalize(Po);
    float h = hybrid_multifractal(frequency * pn + point(3.1, -7.3, 1.7), H, 2, octaves, offset);
    float e = h - sealevel;
    color c;
    float wet = 0;
    if (e < 0) {
        c = mix(color(0.01, 0.05, 0.25), color(0.08, 0.3, 0.55), smoothstep(-1, 0, e));
        wet = 1;
    } else if (e < 0.04) {
        c = color(0.76, 0.7, 0.5);
    } else {
        c = mix(color(0.16, 0.42, 0.12), color(0.42, 0.33, 0.2), smoothstep(0.04, 0.9, e));
        c = mix(c, color(0.92, 0.92, 0.95), smoothstep(1, 1.3, e));
    }
    float ice = smoothstep(icecap - 0.03, icecap + 0.03, abs(pn[2]) + 0.08 * e);
    c = mix(c, color(0.93, 0.95, 0.97), ice);
    wet *= 1 - ice;
    // Not faceforward: on a closed ball N faces the eye wherever it is seen, and at the
    // silhouette, where N . I is 0 to rounding, the two backends would flip it on different pixels.
    normal Nf = normalize(N);
    vector V = -normalize(I);
    Oi = Os;
    Ci = c * (Ka * ambient() + Kd * diffuse(Nf)) + wet * Ks * specular(Nf, V, roughness);
}
