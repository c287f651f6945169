// Swatches for docs/stdlib/lighting.md: Kajiya-Kay hair lighting and the Banks/Heidrich model on a
// sphere, the fibres running along the sphere's u direction (dPdu).
#include <lighting.sl>

surface lighting_kajiya_kay_swatch(float kd = 0.6, ks = 0.4, p = 40)
{
    vector V = -normalize(I);
    Oi = Os;
    Ci = Os * (0.05 + Cs * kajiya_kay(dPdu, V, kd, ks, p));
}

surface lighting_banks_swatch(float kd = 0.6, ks = 0.4, n = 40)
{
    vector V = -normalize(I);
    normal Nf = faceforward(normalize(N), I);
    Oi = Os;
    Ci = Os * (0.05 + Cs * banks(dPdu, Nf, V, kd, ks, n));
}
