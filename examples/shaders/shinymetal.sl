// The standard shinymetal surface (RenderMan Interface Specification 3.2, Appendix A): metal with
// a mirror term read from an environment map along the reflected direction, in world space.
// `texturename` names a lat-long map, a cube-map atlas or a generated one (`sky:N`, `skycube:N`;
// runtime/src/render/textures.rs).
surface
shinymetal(float Ka = 1; float Ks = 1; float Kr = 1; float roughness = .1;
           string texturename = "sky:64")
{
    normal Nf = faceforward(normalize(N), I);
    vector V = -normalize(I);
    vector D = reflect(I, Nf);
    D = vtransform("world", D);
    Oi = Os;
    Ci = Os * Cs * (Ka * ambient() + Ks * specular(Nf, V, roughness)
                    + Kr * color environment(texturename, D));
}
