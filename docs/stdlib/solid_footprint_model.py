#!/usr/bin/env python3
"""A model of the clouds bench plane (examples/scenes/bench/hart_clouds.toml) for choosing how
hart_solid_footprint (compiler/stdlib/solid.sl) estimates a noise term's pixel average.

The clouds map is linear and never clamps here, so the image's error is the error of
f = sum_i a_i (0.5 + 0.5 S n(k_i p)) alone: this script renders f's pixel averages by k x k
supersampling (16 x 16 is the reference) and by the estimators docs/stdlib/solid.md compares,
and prints each one's RMS error over the image and its noise evaluations per pixel.
Needs NumPy; runs in about a minute. Usage: python3 docs/stdlib/solid_footprint_model.py
"""
import numpy as np

# Perlin's improved noise (compiler/stdlib/noise.sl, perlin_improved_noise).
P = np.array([
    151, 160, 137, 91, 90, 15, 131, 13, 201, 95, 96, 53, 194, 233, 7, 225, 140, 36, 103, 30, 69,
    142, 8, 99, 37, 240, 21, 10, 23, 190, 6, 148, 247, 120, 234, 75, 0, 26, 197, 62, 94, 252, 219,
    203, 117, 35, 11, 32, 57, 177, 33, 88, 237, 149, 56, 87, 174, 20, 125, 136, 171, 168, 68, 175,
    74, 165, 71, 134, 139, 48, 27, 166, 77, 146, 158, 231, 83, 111, 229, 122, 60, 211, 133, 230,
    220, 105, 92, 41, 55, 46, 245, 40, 244, 102, 143, 54, 65, 25, 63, 161, 1, 216, 80, 73, 209, 76,
    132, 187, 208, 89, 18, 169, 200, 196, 135, 130, 116, 188, 159, 86, 164, 100, 109, 198, 173, 186,
    3, 64, 52, 217, 226, 250, 124, 123, 5, 202, 38, 147, 118, 126, 255, 82, 85, 212, 207, 206, 59,
    227, 47, 16, 58, 17, 182, 189, 28, 42, 223, 183, 170, 213, 119, 248, 152, 2, 44, 154, 163, 70,
    221, 153, 101, 155, 167, 43, 172, 9, 129, 22, 39, 253, 19, 98, 108, 110, 79, 113, 224, 232, 178,
    185, 112, 104, 218, 246, 97, 228, 251, 34, 242, 193, 238, 210, 144, 12, 191, 179, 162, 241, 81,
    51, 145, 235, 249, 14, 239, 107, 49, 192, 214, 31, 181, 199, 106, 157, 184, 84, 204, 176, 115,
    121, 50, 45, 127, 4, 150, 254, 138, 236, 205, 93, 222, 114, 67, 29, 24, 72, 243, 141, 128, 195,
    78, 66, 215, 61, 156, 180])
PP = np.concatenate([P, P])


def fade(t):
    return t * t * t * (t * (t * 6 - 15) + 10)


def grad(h, x, y, z):
    h = h & 15
    u = np.where(h < 8, x, y)
    v = np.where(h < 4, y, np.where((h == 12) | (h == 14), x, z))
    return np.where(h & 1, -u, u) + np.where(h & 2, -v, v)


def noise(p):
    x, y, z = p[..., 0], p[..., 1], p[..., 2]
    X, Y, Z = (np.floor(c).astype(np.int64) & 255 for c in (x, y, z))
    x, y, z = x - np.floor(x), y - np.floor(y), z - np.floor(z)
    u, v, w = fade(x), fade(y), fade(z)
    A = PP[X] + Y
    AA, AB = PP[A] + Z, PP[A + 1] + Z
    B = PP[X + 1] + Y
    BA, BB = PP[B] + Z, PP[B + 1] + Z

    def lerp(t, a, b):
        return a + t * (b - a)

    return lerp(w,
                lerp(v, lerp(u, grad(PP[AA], x, y, z), grad(PP[BA], x - 1, y, z)),
                     lerp(u, grad(PP[AB], x, y - 1, z), grad(PP[BB], x - 1, y - 1, z))),
                lerp(v, lerp(u, grad(PP[AA + 1], x, y, z - 1), grad(PP[BA + 1], x - 1, y, z - 1)),
                     lerp(u, grad(PP[AB + 1], x, y - 1, z - 1), grad(PP[BB + 1], x - 1, y - 1, z - 1))))


# The scene: 192 x 96, vertical field of view 40 degrees, the ground y = 0, p = (x, 0, z);
# clouds: T = 2 I, lacunarity 2, amp and gain 1/2, 4 terms, snoise scaled by S.
W, H = 192, 96
EYE, TO = np.array([0.0, 1.2, -2.0]), np.array([0.0, 0.0, 1.0])
FWD = (TO - EYE) / np.linalg.norm(TO - EYE)
RIGHT = np.cross([0.0, 1.0, 0.0], FWD)
RIGHT /= np.linalg.norm(RIGHT)
UP = np.cross(FWD, RIGHT)
TAN = np.tan(np.radians(20.0))
S = 0.9649
AMPS, KS = [0.5, 0.25, 0.125, 0.0625], [2.0, 4.0, 8.0, 16.0]
ROWS, COLS = np.meshgrid(np.arange(H), np.arange(W), indexing="ij")


def ground(px, py):
    """The ground point under raster position (px, py), y down."""
    d = FWD + ((2 * px / W - 1) * TAN * W / H)[..., None] * RIGHT + ((1 - 2 * py / H) * TAN)[..., None] * UP
    return EYE + (-EYE[1] / d[..., 1])[..., None] * d


def supersampled(n):
    """Each term's n x n box average per pixel."""
    acc = np.zeros((4, H, W))
    for a in range(n):
        for b in range(n):
            p = ground(COLS + (b + 0.5) / n, ROWS + (a + 0.5) / n)
            for i in range(4):
                acc[i] += noise(KS[i] * p)
    return acc / (n * n)


def smoothstep(a, b, x):
    t = np.clip((x - a) / (b - a), 0, 1)
    return t * t * (3 - 2 * t)


def f_of(terms):
    return sum(AMPS[i] * (0.5 + 0.5 * S * terms[i]) for i in range(4))


REF = supersampled(16)
F_REF = f_of(REF)
P0 = ground(COLS + 0.5, ROWS + 0.5)
DX = ground(COLS + 1.0, ROWS + 0.5) - ground(COLS + 0.0, ROWS + 0.5)
DY = ground(COLS + 0.5, ROWS + 1.0) - ground(COLS + 0.5, ROWS + 0.0)
CENTRE = np.stack([noise(k * P0) for k in KS])
LX, LY = np.linalg.norm(DX, axis=-1), np.linalg.norm(DY, axis=-1)
MAJOR = np.where((LX >= LY)[..., None], DX, DY)
LMAJOR, LMINOR = np.maximum(LX, LY), np.minimum(LX, LY)


def rms(terms):
    return np.sqrt(np.mean((f_of(terms) - F_REF) ** 2))


def faded(a, b):
    """One sample per term, faded by 1 - smoothstep(a, b, k tf) (tf: hart_term_footprint)."""
    tf = np.sqrt(0.5 * (LX ** 2 + LY ** 2))
    return np.stack([(1 - smoothstep(a, b, KS[i] * tf)) * CENTRE[i] for i in range(4)])


def best_weight(keys):
    """The least-squares weight of the centre sample per bin of `keys`, fitted to the reference."""
    w = np.zeros_like(CENTRE)
    for key in np.unique(keys):
        m = keys == key
        w[m] = (CENTRE[m] * REF[m]).sum() / max((CENTRE[m] ** 2).sum(), 1e-12)
    return w * CENTRE


def probed(per_feature, most, rows=1):
    """hart_solid_footprint's rule: ceil(per_feature k |M|) probes (at most `most`) along the
    major axis (and `rows` rows along the minor), each faded by the footprint it covers."""
    out, evaluations = np.zeros_like(CENTRE), 0.0
    minor = np.where((LX >= LY)[..., None], DY, DX)
    for i, k in enumerate(KS):
        n = np.clip(np.ceil(per_feature * k * LMAJOR), 1, most)
        m = np.clip(np.ceil(per_feature * k * LMINOR), 1, rows)
        acc = np.zeros_like(LMAJOR)
        for a in range(int(most)):
            for b in range(rows):
                t = (a + 0.5) / n - 0.5
                s = (b + 0.5) / m - 0.5
                value = noise(k * (P0 + t[..., None] * MAJOR + s[..., None] * minor))
                acc += np.where((a < n) & (b < m), value, 0.0)
        width = np.sqrt(0.5 * ((LMINOR / m) ** 2 + (LMAJOR / n) ** 2))
        out[i] = (1 - smoothstep(0.4, 1.6, k * width)) * acc / (n * m)
        evaluations += (n * m).mean()
    return out, evaluations


def main():
    four = rms(supersampled(4))
    print(f"4 x 4 supersampling: RMS {four:.3e} (64 noise evaluations a pixel)")
    for name, terms in [("point", CENTRE), ("2 x 2", supersampled(2))]:
        print(f"{name}: RMS {rms(terms):.3e}, {rms(terms) / four:.2f} of 4 x 4")
    for a, b in [(0.2, 0.6), (0.4, 1.6), (0.6, 3.0)]:
        e = rms(faded(a, b))
        print(f"one faded sample, range ({a}, {b}): RMS {e:.3e}, {e / four:.2f} of 4 x 4")
    tf = np.stack([k * np.sqrt(0.5 * (LX ** 2 + LY ** 2)) for k in KS])
    bins = np.geomspace(1e-3, 1e3, 61)
    e = rms(best_weight(np.digitize(tf, bins)))
    print(f"best weight per term footprint: RMS {e:.3e}, {e / four:.2f} of 4 x 4")
    sides = [np.stack([k * l for k in KS]) for l in (LX, LY)]
    bins = np.geomspace(1e-3, 1e3, 41)
    e = rms(best_weight(np.digitize(sides[0], bins) * 100 + np.digitize(sides[1], bins)))
    print(f"best weight per pair of footprint sides: RMS {e:.3e}, {e / four:.2f} of 4 x 4")
    for per_feature, most, rows in [(2, 8, 1), (4, 8, 1), (2, 4, 1), (2, 16, 1), (2, 8, 2)]:
        terms, evaluations = probed(per_feature, most, rows)
        e = rms(terms)
        print(f"probes: {per_feature} a feature, at most {most}, {rows} row(s): RMS {e:.3e}, "
              f"{e / four:.2f} of 4 x 4, {evaluations:.1f} noise evaluations a pixel")


if __name__ == "__main__":
    main()
