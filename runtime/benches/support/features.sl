// The benchmark's shader (runtime/benches/binding.rs), also rendered by runtime/tests/renderer/bind.rs: five
// feature flags, each behind its own branch: a texture, a noise-perturbed colour, an fBm bump of the
// normal, a specular lobe per light and a rim term.
#include <fractal.sl>
surface features(float use_tex = 0; string map = "checker:8"; float detail = 0; float bump = 0;
                 float specular = 1; float rim = 0; float Kd = 0.7; float Ks = 0.4; float roughness = 0.2)
{
    color c = Cs;
    normal Nf = normalize(N);
    if (use_tex > 0.5) { c *= color texture(map, s, t); }
    if (detail > 0.5) { c *= 0.6 + 0.4 * fbm(transform("object", P) * 4, 1, 2, 6); }
    if (bump > 0.5) {
        float h = fbm(transform("object", P) * 8, 1, 2, 5);
        Nf = normalize(calculatenormal(P + 0.02 * h * Nf));
    }
    vector V = -normalize(I);
    color d = 0, sp = 0;
    illuminance(P, Nf, PI / 2) {
        vector Ln = normalize(L);
        d += Cl * max(Ln . Nf, 0);
        if (specular > 0.5) {
            vector H = normalize(Ln + V);
            sp += Cl * pow(max(Nf . H, 0), 1 / roughness);
        }
    }
    color r = 0;
    if (rim > 0.5) { r = color(0.3, 0.4, 0.6) * pow(1 - abs(Nf . V), 3); }
    Ci = c * Kd * (0.05 + d) + Ks * sp + r;
    Oi = 1;
}
