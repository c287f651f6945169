// A distant light whose shadows come from an orthographic shadow map (a `[[shadow]]` table with
// `projection = "orthographic"`): lights.sl's distantlight, attenuated by the fraction of the
// map's percentage-closer taps that see the point unoccluded.
light
shadowdistant(float intensity = 1;
              color lightcolor = 1;
              point from = point "shader" (0, 0, 0);
              point to = point "shader" (0, 0, 1);
              string shadowname = "";
              float samples = 16;
              float blur = 0)
{
    solar(to - from, 0.0) {
        float lit = 1;
        if (shadowname != "")
            lit = 1 - shadow(shadowname, Ps, "samples", samples, "blur", blur);
        Cl = lit * intensity * lightcolor;
    }
}
