// The standard lights, RenderMan style: `illuminate` for local lights, `solar` for distant ones.
light
pointlight(float intensity = 1;
           color lightcolor = 1;
           point from = point "shader" (0, 0, 0))
{
    illuminate(from)
        Cl = intensity * lightcolor / (L . L);
}

light
distantlight(float intensity = 1;
             color lightcolor = 1;
             point from = point "shader" (0, 0, 0);
             point to = point "shader" (0, 0, 1))
{
    solar(to - from, 0.0)
        Cl = intensity * lightcolor;
}

light
spotlight(float intensity = 1;
          color lightcolor = 1;
          point from = point "shader" (0, 0, 0);
          point to = point "shader" (0, 0, 1);
          float coneangle = radians(30);
          float conedeltaangle = radians(5);
          float beamdistribution = 2)
{
    uniform vector A = (to - from) / length(to - from);
    illuminate(from, A, coneangle) {
        float cosangle = (L . A) / length(L);
        float atten = pow(cosangle, beamdistribution) / (L . L);
        atten *= smoothstep(cos(coneangle), cos(coneangle - conedeltaangle), cosangle);
        Cl = atten * intensity * lightcolor;
    }
}

light
ambientlight(float intensity = 1; color lightcolor = 1)
{
    Cl = intensity * lightcolor;
    L = 0;
}
