// The teacup of the steam_cup scene: a glazed ceramic (RenderMan's plastic) for the cup's wall,
// saucer and handle, and the tea, a disk of radius `radius` in the unit plane's (s, t) square
// (transparent outside it) with a dark, glossy surface.

// The ceramic is drawn on closed meshes (sphere, torus), whose visible faces face the eye, so the
// normal is not flipped toward the eye: faceforward flips where N . I changes sign, on the
// silhouettes, and there the two backends' roundings of N . I would choose different sides (whole
// pixels lit on one backend and in shadow on the other).
surface ceramic(float Ka = 1, Kd = 0.75, Ks = 0.6, roughness = 0.06)
{
    normal Nf = normalize(N);
    vector V = -normalize(I);
    Oi = Os;
    Ci = Os * (Cs * (Ka * ambient() + Kd * diffuse(Nf)) + Ks * specular(Nf, V, roughness));
}

surface tea(float radius = 0.5; float Ka = 1, Kd = 0.4, Ks = 0.8, roughness = 0.03;
            color tint = color(0.23, 0.1, 0.035))
{
    float r = length(vector(s - 0.5, t - 0.5, 0));
    float inside = 1 - smoothstep(radius - 0.01, radius, r);
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    Oi = inside;
    Ci = inside * (tint * (Ka * ambient() + Kd * diffuse(Nf)) + Ks * specular(Nf, V, roughness));
}
