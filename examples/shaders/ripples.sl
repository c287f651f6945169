// A displacement shader and a volume shader: `P` and `N` are written, `calculatenormal`,
// `for` loops with declarations, arrays, `break 1`, and `++`.
displacement
ripples(float Km = 0.02, frequency = 8;
        float phases[3] = {0, 2.1, 4.2})
{
    float height = 0;
    for (int i = 0; i < 3; i++) {
        height += sin(frequency * s + phases[i]) / 3;
        if (height > 10)
            break 1;
    }
    P += Km * height * normalize(N);
    N = calculatenormal(P);
}

volume
fog(float distance = 10; color background = color "hsv" (0.6, 0.2, 0.9))
{
    float d = 1 - exp(-length(I) / distance);
    Ci = mix(Ci, background, d);
    Oi = mix(Oi, color (1, 1, 1), d);
}
