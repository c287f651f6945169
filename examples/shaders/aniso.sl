// Stanford style: a light shader, a surface shader with perlight values and integrate(), a
// context-prefixed function, explicit rates, braced constructors and indexing.
light shader float4
falloff_light(float4 lightcolor, float constant_term, float linear_term)
{
    return lightcolor * (1.0 / (linear_term * Sdist + constant_term));
}

surface float3 to_object(float3 v)
{
    return invert(affine(__modelview)) * v;
}

surface shader float4
aniso(texref base, texref table, primitive group float4 ambient_color)
{
    vertex float4 base_uv = {0.5 * Pobj[2] + 0.5, 0.5 * Pobj[0] + 0.5, 0, 1};
    fragment float4 surface_color = texture(base, base_uv);
    perlight float4 table_uv = {0.5 * dot(B, E) + 0.5, 0.5 * dot(B, L) + 0.5, 0, 1};
    perlight float4 lit = Cl * max(dot(N, L), 0) * texture(table, table_uv);
    constant float4 ka = {0.1, 0.1, 0.1, 1.0};
    float3 color = rgb(ambient_color);
    return surface_color * (ka * {color, 1} + integrate(lit));
}
