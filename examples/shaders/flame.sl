// Stanford style procedural flame: plain functions, select(), clamp01, integer bit operations and
// shifts (hash), wrapping arithmetic, bool, and `constant` values folded at compile time.
uint hash(uint x)
{
    x = (x ^ (x >> 16u)) * 0x45d9f3bu;
    x = (x ^ (x >> 16u)) * 0x45d9f3bu;
    return x ^ (x >> 16u);
}

float rand01(uint seed)
{
    return float(hash(seed) & 0xffffffu) / 16777216.0;
}

// A cubic spline on [0, 1] (the caller clamps x into it).
// sweep: x in [0, 1]
float fastspline(float x)
{
    float t0 = x * 2;
    float r0 = 0.8 + t0 * (-0.45 + t0 * (-0.8 + t0 * 0.55));
    float t1 = (x - 0.5) * 2;
    float r1 = 0.1 + t1 * (-0.4 + t1 * (0.55 + t1 * -0.25));
    return select(x < 0.5, r0, r1);
}

surface shader float4
flame(vertex float4 uv, primitive group float time)
{
    constant float rate = 6.0;
    fragment float u = uv[0];
    fragment float v = uv[1];
    bool lower_half = v < 0.5 && !(u > 1.0);
    int frame = int(time * rate);
    float jitter = rand01(uint(frame) << 3u | 1u);
    float x = (1.0 / sqrt(v)) * (abs(2.0 * u - 1.0) + 0.1 * jitter);
    float density = clamp01(12.5 * fastspline(clamp(x, 0, 1)));
    float3 hot = {1.0, 0.6, 0.4};
    float4 result = {hot * density, select(lower_half, density, density * 0.5)};
    return result;
}
