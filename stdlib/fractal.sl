// Fractal sums of noise: Musgrave's fBm with a fractional last octave, Perlin's turbulence,
// Musgrave's ridged and hybrid multifractals, and an fBm that drops the octaves finer than a
// filter width. Every basis is snoise3 (stdlib/noise.sl: Perlin's improved noise, signed, in
// [-1, 1]); this file includes noise.sl itself.
//
// Sources: Texturing & Modeling, 3rd ed. (shared/seeds/002_a44091d2843c02ac.txt): Musgrave ch. 14
// fBm L10148-10179, ch. 16 HybridMultifractal L11665-11745 and RidgedMultifractal L11760-11845;
// Perlin's turbulence L8960-8990 (and Peachey's L2722-2781). The printed listings' defects
// (fBm without `return`, stray blocks in the multifractals L11691-11699 and L11792-11803, the
// exponent array computed once for all parameters, H-R5) are not reproduced: the spectral
// weights lacunarity^(-H i) are computed per octave, from this call's parameters.
//
// Octave loops: every function here runs its loop up to ceil(octaves) (floor(octaves) where only
// whole octaves count), and weights octave i by clamp(octaves - i, 0, 1) (1 for whole octaves, the
// remainder for the fractional one). The loop counter is an ordinary (varying) variable, so every
// parameter may be varying; snoise3's permutation table is a `constant` local initialised at its
// declaration, which stays constant under the varying loop (the rate checker's rule since issue 7).
// The octave count is clamped to PATINA_FRACTAL_MAX_OCTAVES (default 30); define it to a smaller
// count before the first #include <fractal.sl> to cap the cost.
//
// Guards shared by every function here, so that any finite input gives a finite result on both
// backends: the octave count is clamped to [0, 30] (PATINA_FRACTAL_MAX_OCTAVES); H below 0 is
// taken as 0 (weights never exceed 1); lacunarity is clamped to [1, 8] (8^30 * 1e6 stays below
// the f32 maximum). Octave i samples the noise at p * lacunarity^i, so in f32 the finer octaves
// lose their fraction sooner than the first (stdlib/noise.sl: past 2^23 every f32 is an integer
// and the noise is 0; those octaves then add nothing, which is finite but not detail).
//
// Precision (measured by compiler/tests/stdlib_fractal.rs and runtime/tests/stdlib_fractal_gpu.rs):
// the f64 interpreter agrees with an independent Rust port to the last bit (tested within
// 1e-12); the f32 interpreter is within 2.7e-6 of the port at the same f32 inputs and f32-rounded
// scaled points (tested within 1e-5); the GPU is within 1.4e-6 of the f32 interpreter (tested
// within 1e-5; the noise is bit-exact, pow and log are not). In f32, with a lacunarity other than
// 2, the scaled points p lacunarity^i round: the finer octaves at large |p| lose accuracy first.

#ifndef PATINA_FRACTAL_SL
#define PATINA_FRACTAL_SL

#include <noise.sl>

#ifndef PATINA_FRACTAL_MAX_OCTAVES
#define PATINA_FRACTAL_MAX_OCTAVES 30
#endif

// Musgrave's fBm (T&M L10148-10170): sum over i < floor(octaves) of
// snoise3(p * lacunarity^i) * lacunarity^(-H i), plus the fractional remainder
// (octaves - floor(octaves)) times the next octave, so the result is continuous in `octaves`
// (L10177). H: 1 smooth, 0 close to white noise (L10181); lacunarity usually 2 (L10092).
// Octaves are clamped to [0, 30], H to >= 0, lacunarity to [1, 8]; octaves 0 gives 0.
// The weights are pow(lacunarity, -H i) per octave (L10179's exponent array, without its
// computed-once cache).
float fbm(point p; float H, lacunarity, octaves)
{
    float h = max(H, 0);
    float lac = clamp(lacunarity, 1, 8);
    float oct = clamp(octaves, 0, PATINA_FRACTAL_MAX_OCTAVES);
    float value = 0;
    point pp = p;
    float i;
    for (i = 0; i < oct; i += 1) {
        // 1 for whole octaves, the remainder for the fractional last one, 0 beyond.
        value += clamp(oct - i, 0, 1) * snoise3(pp) * pow(lac, -h * i);
        pp = pp * lac;
    }
    return value;
}

// Perlin's turbulence (T&M L8960-8990; Peachey L2722-2747): sum over i < floor(octaves) of
// |snoise3(p * 2^i)| / 2^i, plus the fractional remainder of the next octave (continuous in
// `octaves`). Without the book's -0.3 shift: the result is >= 0. Octaves are clamped to
// [0, 30]; octaves 0 gives 0. Not differentiable where an octave's noise crosses 0 (L2743).
float turbulence(point p; float octaves)
{
    float oct = clamp(octaves, 0, PATINA_FRACTAL_MAX_OCTAVES);
    float value = 0, f = 1;
    float i;
    for (i = 0; i < oct; i += 1) {
        value += clamp(oct - i, 0, 1) * abs(snoise3(p * f)) / f;
        f *= 2;
    }
    return value;
}

// Musgrave's ridged multifractal (T&M L11760-11845; suggested H 1, offset 1, gain 2, L11766):
// signal_0 = (offset - |snoise3(p)|)^2, result = signal_0; for 0 < i < floor(octaves):
// weight = clamp(signal_{i-1} * gain, 0, 1), signal_i = (offset - |snoise3(p lacunarity^i)|)^2
// * weight, result += signal_i * lacunarity^(-H i). Whole octaves only, as printed (a fractional
// part of octaves is dropped); octaves clamped to [0, 30] (0 gives 0), H >= 0, lacunarity in
// [1, 8]. With offset 1, gain 2, H 1 the result stays in [0, 2] (catalogue: max about 1.95).
float ridged_multifractal(point p; float H, lacunarity, octaves, offset, gain)
{
    float h = max(H, 0);
    float lac = clamp(lacunarity, 1, 8);
    float n = floor(clamp(octaves, 0, PATINA_FRACTAL_MAX_OCTAVES));
    float result = 0, weight = 1, signal;
    point pp = p;
    float i;
    for (i = 0; i < n; i += 1) {
        signal = offset - abs(snoise3(pp));
        signal = signal * signal * weight;
        result += clamp(n - i, 0, 1) * signal * pow(lac, -h * i);
        weight = clamp(signal * gain, 0, 1);
        pp = pp * lac;
    }
    return result;
}

// Musgrave's hybrid multifractal (T&M L11665-11745; suggested H 0.25, offset 0.7, L11672):
// result = signal_0 = (snoise3(p) + offset), weight = result; for 0 < i < floor(octaves):
// weight = min(weight, 1), signal_i = (snoise3(p lacunarity^i) + offset) * lacunarity^(-H i),
// result += weight * signal_i, weight *= signal_i. The fractional remainder adds
// (octaves - floor(octaves)) * weight * signal of the next octave. Departure: the printed
// remainder term, remainder * Noise3(point) * exponent_array[i], drops both the offset and the
// weight, which makes the result jump as octaves passes a whole number; this one is the next
// whole octave's term scaled, so the result is continuous in `octaves`. Octaves clamped to
// [0, 30] (0 gives 0), H >= 0, lacunarity in [1, 8]; finite for |offset| up to about 10 (the
// weight of a negative run grows by at most 1 + |offset| per octave).
float hybrid_multifractal(point p; float H, lacunarity, octaves, offset)
{
    float h = max(H, 0);
    float lac = clamp(lacunarity, 1, 8);
    float oct = clamp(octaves, 0, PATINA_FRACTAL_MAX_OCTAVES);
    float result = 0, weight = 1, signal;
    point pp = p;
    float i;
    for (i = 0; i < oct; i += 1) {
        weight = min(weight, 1);
        signal = (snoise3(pp) + offset) * pow(lac, -h * i);
        result += clamp(oct - i, 0, 1) * weight * signal;
        weight *= signal;
        pp = pp * lac;
    }
    return result;
}

// fBm clamped to a filter width: fbm(p, H, lacunarity, min(octaves, k)) with
// k = log(1 / width) / log(lacunarity), the number of octaves whose feature size
// lacunarity^-i is still above `width` (log2(1 / width) for lacunarity 2; compare Musgrave's
// log2(resolution) - 2, L10173, and vfBm's cutoff at fw >= 1, L10524). k is fractional, so the
// last octave kept fades in with the remainder (continuous in width). `width` is the filter
// width of p (e.g. filterwidthp(P)); |width| below 1e-30 counts as 1e-30 (k = 99.7 at
// lacunarity 2, so octaves limit), width >= 1 gives 0 (the average). Lacunarity 1 means no
// frequency increase: k is unbounded and `octaves` alone limits. Same guards as fbm.
float fbm_filtered(point p; float H, lacunarity, octaves, width)
{
    float lac = clamp(lacunarity, 1, 8);
    float w = max(abs(width), 1e-30);
    return fbm(p, H, lac, min(octaves, -log(w) / max(log(lac), 1e-6)));
}

#endif
