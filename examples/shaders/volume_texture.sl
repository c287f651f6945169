// Volume rendering of a 3D texture, after the volume shader of W. R. Mark's Stanford RTSL chapter
// (Texturing & Modeling ch. 3, shared/seeds/002_a44091d2843c02ac.txt L3567-3654), which
// classifies texture3d samples through a transfer function into colour and opacity. That shader
// runs on slices the application draws through the volume; this one draws the volume's bounding
// cube and marches each fragment's eye ray through it in `steps` equal steps, front to back
// (stdlib volume_composite), reading the density with texture3d (trilinear).
#include <volume.sl>

// The transfer function's colour: blue for thin matter, orange in the middle, near white for the
// densest (the opacity is proportional to the density: `opacity` per unit of object space).
float3 transfer(float rho)
{
    float3 thin = {0.15, 0.3, 1.0};
    float3 middle = {1.0, 0.45, 0.1};
    float3 dense = {1.0, 0.95, 0.8};
    return mix(mix(thin, middle, smoothstep(0.1, 0.5, rho)), dense, smoothstep(0.5, 0.95, rho));
}

surface shader float4
volume_texture(primitive group texref density,
               primitive group float steps,
               primitive group float opacity)
{
    // The eye in object space (the cube is [-1, 1]^3 there, the texture [0, 1]^3), by RenderMan's
    // transform: the runtime gives no value to Stanford's __modelview yet.
    float3 eye = transform("object", point "camera" (0, 0, 0));
    // (P, not Pobj, through that transform: the CPU reference gives Pobj no value yet.)
    fragment float3 entry = transform("object", point "camera" (P[0], P[1], P[2]));
    float3 dir = normalize(entry - eye);
    // Where the ray leaves the cube (a fragment of a back face leaves at once: length 0).
    float far = 1e30;
    for (int k = 0; k < 3; k += 1) {
        if (abs(dir[k]) > 1e-6)
            far = min(far, max((-1 - entry[k]) / dir[k], (1 - entry[k]) / dir[k]));
    }
    float h = max(far, 0) / max(steps, 1);
    float4 acc = {0, 0, 0, 0};
    for (float i = 0; i < steps; i += 1) {
        float3 q = entry + dir * ((i + 0.5) * h);
        float4 uvw = {0.5 * q[0] + 0.5, 0.5 * q[1] + 0.5, 0.5 * q[2] + 0.5, 1};
        float rho = texture3d(density, uvw)[0];
        acc = volume_composite(acc, opacity * rho, transfer(rho), h);
    }
    return acc;
}
