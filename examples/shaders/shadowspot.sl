// A spot light whose shadows come from a shadow map (RenderMan's `shadow()`): the cone and
// falloff of lights.sl's spotlight, attenuated by the fraction of the map's percentage-closer
// taps that see the point unoccluded. `shadowname` names a `[[shadow]]` map of the scene;
// `samples` (taps), `blur` (a fraction of the map) and `bias` (negative: the map's own bias) go
// to the lookup as its options.
light
shadowspot(float intensity = 1;
           color lightcolor = 1;
           point from = point "shader" (0, 0, 0);
           point to = point "shader" (0, 0, 1);
           float coneangle = radians(30);
           float conedeltaangle = radians(5);
           float beamdistribution = 2;
           string shadowname = "";
           float samples = 16;
           float blur = 0;
           float bias = -1)
{
    uniform vector axis = normalize(to - from);
    illuminate(from, axis, coneangle) {
        float cosangle = (L . axis) / length(L);
        float falloff = pow(cosangle, beamdistribution) / (L . L);
        falloff *= smoothstep(cos(coneangle), cos(coneangle - conedeltaangle), cosangle);
        float lit = 1;
        if (shadowname != "") {
            if (bias < 0)
                lit = 1 - shadow(shadowname, Ps, "samples", samples, "blur", blur);
            else
                lit = 1 - shadow(shadowname, Ps, "samples", samples, "blur", blur, "bias", bias);
        }
        Cl = falloff * lit * intensity * lightcolor;
    }
}
