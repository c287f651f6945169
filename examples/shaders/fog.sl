// Atmosphere (volume) shaders: what the light from a surface meets on its way to the eye. Bind one
// to an object with `atmosphere = { shader = "fog.sl" }` (or to every object with a scene's
// `[atmosphere]` table); it runs after the surface at each fragment, on its Ci and Oi.

// Exponential fog: the colour goes towards `background`, and the opacity towards 1, by the
// fraction 1 - exp(-distance / falloff) of the light scattered over the distance to the eye.
volume
fog(float falloff = 1; color background = color(0.5, 0.6, 0.7))
{
    float d = 1 - exp(-length(I) / falloff);
    Ci = mix(Ci, background, d);
    Oi = mix(Oi, color(1, 1, 1), d);
}

// Depth cueing: a linear blend towards `background` between the depths `mindistance` (none) and
// `maxdistance` (all of it), by camera-space depth.
volume
depthcue(float mindistance = 0; float maxdistance = 10; color background = 0)
{
    float z = zcomp(P);
    float d = clamp((z - mindistance) / (maxdistance - mindistance), 0, 1);
    Ci = mix(Ci, background, d);
    Oi = mix(Oi, color(1, 1, 1), d);
}
