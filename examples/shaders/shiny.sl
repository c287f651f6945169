// A hand-written specular loop over the lights, with an `illuminance` cone, a ternary, a `while`
// with `break`, and RenderMan's cross and dot operators.
surface
shiny(float Ks = 1, roughness = 0.2; output varying float hits = 0)
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    color spec = 0;
    illuminance(P, Nf, PI / 2) {
        vector H = normalize(normalize(L) + V);
        float facing = Nf . H;
        spec += Cl * pow(facing > 0 ? facing : 0, 1 / roughness);
        hits += 1;
    }
    illuminance("specular", P) {
        spec += 0.1 * Cl;
    }
    vector T = normalize(dPdu ^ Nf);
    float k = 0;
    while (k < 4) {
        k += 1;
        if (abs(T . V) > 0.99)
            break;
        else
            continue;
    }
    Ci = Ks * spec;
    Oi = 1;
}
