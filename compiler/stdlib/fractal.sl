// Fractal sums of noise: Musgrave's fBm with a fractional last octave, Perlin's turbulence,
// Musgrave's ridged and hybrid multifractals, and an fBm that drops the octaves finer than a
// filter width. Every basis is snoise3 (compiler/stdlib/noise.sl: Perlin's improved noise, signed, in
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
// taken as 0 (weights never exceed 1); lacunarity is clamped to [1, 8]; the scaled points are
// clamped to +-1e30 (PATINA_FRACTAL_MAX_COORD), so that p lacunarity^i stays finite for every
// finite p; the multifractals' offsets are clamped to +-1e4 (PATINA_FRACTAL_MAX_OFFSET). Octave i
// samples the noise at p * lacunarity^i, so in f32 the finer octaves lose their fraction sooner
// than the first (compiler/stdlib/noise.sl: past 2^23 every f32 is an integer and the noise is 0; those
// octaves then add nothing, which is finite but not detail).
//
// Precision (measured by compiler/tests/stdlib_fractal.rs and runtime/tests/stdlib/fractal_gpu.rs):
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

// The bound on the coordinates of the scaled points p lacunarity^i: each octave's point is
// clamped to +-1e30, so that p lacunarity^i stays finite for any finite p (1e30 * 8 < the f32
// maximum). Beyond 2^53 (f64) or 2^23 (f32) every coordinate is an integer, so the clamp moves
// only coordinates whose fraction is already 0; it changes which lattice cell such a coordinate
// hashes to, not the fraction of the others.
#define PATINA_FRACTAL_MAX_COORD 1e30

// The largest |offset| the multifractals (ridged, hybrid, multifractal, hetero_terrain) use: a
// larger one is taken as +-PATINA_FRACTAL_MAX_OFFSET. Musgrave: the multifractal "approaches a flat plane
// as offset gets large (i.e., around 100 or so)" (T&M L10228), so nothing is lost at 1e4.
#ifndef PATINA_FRACTAL_MAX_OFFSET
#define PATINA_FRACTAL_MAX_OFFSET 1e4
#endif

// The bound on multifractal's running product (|value| is clamped to it after every octave) and
// on the hybrid multifractal's negative weights.
#define PATINA_FRACTAL_MAX_PRODUCT 1e30

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
        pp = clamp(pp * lac, -PATINA_FRACTAL_MAX_COORD, PATINA_FRACTAL_MAX_COORD);
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
        point pf = clamp(p * f, -PATINA_FRACTAL_MAX_COORD, PATINA_FRACTAL_MAX_COORD);
        value += clamp(oct - i, 0, 1) * abs(snoise3(pf)) / f;
        f *= 2;
    }
    return value;
}

// Musgrave's ridged multifractal (T&M L11760-11845; suggested H 1, offset 1, gain 2, L11766):
// signal_0 = (offset - |snoise3(p)|)^2, result = signal_0; for 0 < i < floor(octaves):
// weight = clamp(signal_{i-1} * gain, 0, 1), signal_i = (offset - |snoise3(p lacunarity^i)|)^2
// * weight, result += signal_i * lacunarity^(-H i). Whole octaves only, as printed (a fractional
// part of octaves is dropped); octaves clamped to [0, 30] (0 gives 0), H >= 0, lacunarity in
// [1, 8], offset to +-PATINA_FRACTAL_MAX_OFFSET (so that signal^2 stays finite). With offset 1,
// gain 2, H 1 the result stays in [0, 2] (catalogue: max about 1.95).
float ridged_multifractal(point p; float H, lacunarity, octaves, offset, gain)
{
    float h = max(H, 0);
    float lac = clamp(lacunarity, 1, 8);
    float n = floor(clamp(octaves, 0, PATINA_FRACTAL_MAX_OCTAVES));
    float o = clamp(offset, -PATINA_FRACTAL_MAX_OFFSET, PATINA_FRACTAL_MAX_OFFSET);
    float result = 0, weight = 1, signal;
    point pp = p;
    float i;
    for (i = 0; i < n; i += 1) {
        signal = o - abs(snoise3(pp));
        signal = signal * signal * weight;
        result += clamp(n - i, 0, 1) * signal * pow(lac, -h * i);
        weight = clamp(signal * gain, 0, 1);
        pp = clamp(pp * lac, -PATINA_FRACTAL_MAX_COORD, PATINA_FRACTAL_MAX_COORD);
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
// [0, 30] (0 gives 0), H >= 0, lacunarity in [1, 8], offset to +-PATINA_FRACTAL_MAX_OFFSET, and
// the weight to >= -PATINA_FRACTAL_MAX_PRODUCT as well as <= 1 (a negative weight grows by up to
// 1 + |offset| per octave): then every term is below 1e34 and the sum finite.
float hybrid_multifractal(point p; float H, lacunarity, octaves, offset)
{
    float h = max(H, 0);
    float lac = clamp(lacunarity, 1, 8);
    float oct = clamp(octaves, 0, PATINA_FRACTAL_MAX_OCTAVES);
    float o = clamp(offset, -PATINA_FRACTAL_MAX_OFFSET, PATINA_FRACTAL_MAX_OFFSET);
    float result = 0, weight = 1, signal;
    point pp = p;
    float i;
    for (i = 0; i < oct; i += 1) {
        weight = clamp(weight, -PATINA_FRACTAL_MAX_PRODUCT, 1);
        signal = (snoise3(pp) + o) * pow(lac, -h * i);
        result += clamp(oct - i, 0, 1) * weight * signal;
        weight *= signal;
        pp = clamp(pp * lac, -PATINA_FRACTAL_MAX_COORD, PATINA_FRACTAL_MAX_COORD);
    }
    return result;
}

// The octave count a filter width allows: min(octaves, k), k = log(1 / width) / log(lacunarity)
// with lacunarity clamped to [1, 8] and |width| to >= 1e-30 (fbm_filtered's rule, below). Pass it
// as `octaves` to filter any sum here; the functions with a fractional last octave (fbm,
// turbulence, hybrid_multifractal, hetero_terrain, distfbm) are then continuous in the width,
// the whole-octave ones (ridged_multifractal, multifractal) change in steps.
float fractal_filter_octaves(float octaves, lacunarity, width)
{
    float lac = clamp(lacunarity, 1, 8);
    float w = max(abs(width), 1e-30);
    return min(octaves, -log(w) / max(log(lac), 1e-6));
}

// fBm clamped to a filter width: fbm(p, H, lacunarity, min(octaves, k)) with
// k = log(1 / width) / log(lacunarity), the number of octaves whose feature size
// lacunarity^-i is still above `width` (log2(1 / width) for lacunarity 2; compare Musgrave's
// log2(resolution) - 2, L10173, and vfBm's cutoff at fw >= 1, L10524). k is fractional, so the
// last octave kept fades in with the remainder (continuous in width). `width` is the filter
// width of p (e.g. the sum of filterwidth over its coordinates); |width| below 1e-30 counts as
// 1e-30 (k = 99.7 at lacunarity 2, so octaves limit), width >= 1 gives 0 (the average).
// Lacunarity 1 means no frequency increase: k is unbounded and `octaves` alone limits. Same
// guards as fbm.
float fbm_filtered(point p; float H, lacunarity, octaves, width)
{
    return fbm(p, H, clamp(lacunarity, 1, 8), fractal_filter_octaves(octaves, lacunarity, width));
}

// Perlin's turbulence clamped to a filter width: turbulence(p, min(octaves, log2(1 / width))),
// fbm_filtered's rule at lacunarity 2 (compare Perlin's own loop, which stops at the pixel's
// frequency, L8960-8990). Continuous in width; width >= 1 gives 0.
float turbulence_filtered(point p; float octaves, width)
{
    return turbulence(p, fractal_filter_octaves(octaves, 2, width));
}

// Musgrave's multiplicative-cascade multifractal (T&M ch. 14, L10211-10232): the product over
// i < floor(octaves) of (snoise3(p lacunarity^i) + offset) * lacunarity^(-H i); 1 for octaves 0
// (the empty product). offset 0 is "heterogeneous in the extreme", about 0.8 gives "a very nice,
// heterogeneous terrain" (Fig. 14.3). Whole octaves only, as printed ("octaves is not real-valued,
// as this function would behave badly in LOD schemes"). Musgrave warns that the range "varies
// widely ... by many orders of magnitude" and that with more octaves it "will either converge to
// zero or diverge to infinity": rescale the result (he divides by its maximum over a patch).
// Guards: octaves clamped to [0, 30], H >= 0, lacunarity in [1, 8], offset to
// +-PATINA_FRACTAL_MAX_OFFSET, and the running product to +-PATINA_FRACTAL_MAX_PRODUCT (1e30)
// after each octave, so that no octave overflows (each factor is at most 1e4 + 1 in magnitude:
// 1e34 < the f32 maximum); a product that converges to 0 underflows to 0, which is finite.
float multifractal(point p; float H, lacunarity, octaves, offset)
{
    float h = max(H, 0);
    float lac = clamp(lacunarity, 1, 8);
    float n = floor(clamp(octaves, 0, PATINA_FRACTAL_MAX_OCTAVES));
    float o = clamp(offset, -PATINA_FRACTAL_MAX_OFFSET, PATINA_FRACTAL_MAX_OFFSET);
    float value = 1;
    point pp = p;
    float i;
    for (i = 0; i < n; i += 1) {
        value = clamp(value * ((snoise3(pp) + o) * pow(lac, -h * i)),
                      -PATINA_FRACTAL_MAX_PRODUCT, PATINA_FRACTAL_MAX_PRODUCT);
        pp = clamp(pp * lac, -PATINA_FRACTAL_MAX_COORD, PATINA_FRACTAL_MAX_COORD);
    }
    return value;
}

// Musgrave's heterogeneous terrain, "statistics by altitude" (T&M ch. 16, Hetero_Terrain,
// L11590-11655): value = offset + snoise3(p); then for each further octave i,
// increment = (snoise3(p lacunarity^i) + offset) * lacunarity^(-H i) * clamp(value, -1, 1),
// value += increment; the fractional remainder of octaves scales the next octave's increment
// (L11640-11647). Low areas ("sea level", value near 0) damp the finer octaves and stay smooth;
// high areas grow jagged. Errata and decisions: the printed loop header `for (l=1; i<octaves; l++)`
// (L11623) is the loop over i = 1 .. octaves - 1; the exponent array computed once for all
// parameters (H-R5) is pow(lacunarity, -H i) per octave; the altitude that weights each increment
// is clamped to [-1, 1], as the text suggests ("we may need to clamp the highest value of the
// weighting variable to 1.0, to prevent the sum from diverging", L11657; unclamped, the maximum
// grows from 2.6 to 24 between 2 and 12 octaves at offset 0.5, catalogue H-R2), and below -1 as
// well, so that negative altitudes cannot grow either. Departure: the first octave is weighted by
// clamp(octaves, 0, 1) like the others, so octaves 0 gives 0 and the result is continuous in
// `octaves` (the listing always adds the first octave). Guards: octaves clamped to [0, 30], H >= 0,
// lacunarity in [1, 8], offset to +-PATINA_FRACTAL_MAX_OFFSET; then
// |value| <= 31 (|offset| + 1) whatever the octaves.
float hetero_terrain(point p; float H, lacunarity, octaves, offset)
{
    float h = max(H, 0);
    float lac = clamp(lacunarity, 1, 8);
    float oct = clamp(octaves, 0, PATINA_FRACTAL_MAX_OCTAVES);
    float o = clamp(offset, -PATINA_FRACTAL_MAX_OFFSET, PATINA_FRACTAL_MAX_OFFSET);
    float value = clamp(oct, 0, 1) * (o + snoise3(p));
    point pp = clamp(p * lac, -PATINA_FRACTAL_MAX_COORD, PATINA_FRACTAL_MAX_COORD);
    float i;
    for (i = 1; i < oct; i += 1) {
        float increment = (snoise3(pp) + o) * pow(lac, -h * i) * clamp(value, -1, 1);
        value += clamp(oct - i, 0, 1) * increment;
        pp = clamp(pp * lac, -PATINA_FRACTAL_MAX_COORD, PATINA_FRACTAL_MAX_COORD);
    }
    return value;
}

// Musgrave's vector-valued noise VecNoise (T&M ch. 15, L10370-10380): three signed noises at p,
// p + 3.33 and p + 7.77 (each component displaced). Each component is in [-1, 1]. Named with the
// prefix so as not to collide with the vector noises of compiler/stdlib/noise.sl.
vector musgrave_vecnoise(point p)
{
    return vector(snoise3(p), snoise3(p + 3.33), snoise3(p + 7.77));
}

// Musgrave's distorted noise DistNoise (T&M ch. 15, L10350-10412): the noise of a domain
// displaced by a random vector, snoise3(p + distortion * musgrave_vecnoise(p + 0.5)); the 0.5
// "misregisters" the lattices (gradient noise is 0 at lattice points, L10386). In [-1, 1];
// distortion 0 gives snoise3(p). "About four times as expensive" as the noise (L10388).
// Erratum: the RenderMan version (L10413-10434) writes `point offset = snoise(Pt + ...)`, a float
// noise promoted to a point (the same displacement in x, y and z); this is the C++ version's
// vector noise. Guard: |distortion| is clamped to 1e30, so p + distortion * (a vector in
// [-1, 1]^3) stays finite for |p| below 3e38.
float distnoise(point p; float distortion)
{
    float d = clamp(distortion, -1e30, 1e30);
    return snoise3(p + d * musgrave_vecnoise(p + 0.5));
}

// Musgrave's DistfBm (named at T&M L10388, "fBm constructed using DistNoise() ... as the basis
// function"): fbm's sum with distnoise(p lacunarity^i, distortion) in place of snoise3, the same
// fractional last octave and guards. Four noise evaluations per octave.
float distfbm(point p; float H, lacunarity, octaves, distortion)
{
    float h = max(H, 0);
    float lac = clamp(lacunarity, 1, 8);
    float oct = clamp(octaves, 0, PATINA_FRACTAL_MAX_OCTAVES);
    float value = 0;
    point pp = p;
    float i;
    for (i = 0; i < oct; i += 1) {
        value += clamp(oct - i, 0, 1) * distnoise(pp, distortion) * pow(lac, -h * i);
        pp = clamp(pp * lac, -PATINA_FRACTAL_MAX_COORD, PATINA_FRACTAL_MAX_COORD);
    }
    return value;
}

#endif
