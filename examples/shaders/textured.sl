// Texture lookups in both styles: a RenderMan surface reading a 2D texture by name (a string
// parameter) with lighting, and a Stanford surface reading a 3D texture through a `texref`.
// sweep: repeats in [0, 1e4] (times an s of 1e30 it would overflow f32)
surface
textured(string map = "checker:8"; float Kd = 0.8; float repeats = 4)
{
    normal Nf = faceforward(normalize(N), I);
    color c = texture(map, s * repeats, t * repeats / 2);
    Oi = Os;
    Ci = Os * c * (0.15 + Kd * diffuse(Nf));
}

surface shader float4
solid(vertex float4 uv, primitive group texref density, primitive group float depth)
{
    float4 at = {uv[0], uv[1], depth, 1};
    return texture3d(density, at);
}
