// Imager shaders: run over the finished image, once per pixel, after every object is drawn. Bind
// one with a scene's `[imager]` table. An imager sees P (the pixel centre in raster space), s and
// t (its position across the image, 0 to 1), Ci (the premultiplied colour), alpha (the coverage)
// and Oi; what it leaves in Ci and alpha is the pixel.

// A background colour under whatever the objects left uncovered.
imager
background(color bgcolor = color(1, 1, 1))
{
    Ci += (1 - alpha) * bgcolor;
    Oi = 1;
    alpha = 1;
}

// Exposure and gamma: each channel scaled by `gain`, then raised to 1 / `gamma`.
imager
exposure(float gain = 1; float gamma = 1)
{
    float e = 1 / gamma;
    Ci = color(pow(gain * comp(Ci, 0), e), pow(gain * comp(Ci, 1), e), pow(gain * comp(Ci, 2), e));
}

// A vignette: the colour darkened towards the corners of the image by `amount`.
imager
vignette(float amount = 0.5)
{
    float r = 2 * sqrt((s - 0.5) * (s - 0.5) + (t - 0.5) * (t - 0.5)) / sqrt(2);
    Ci *= 1 - amount * r * r;
}
