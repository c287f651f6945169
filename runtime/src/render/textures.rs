//! The textures a scene's shaders read, by name: a PNG file (relative to the scene's directory)
//! or a generated table:
//!
//! - `checker` or `checker:N`: an N×N black-and-white board (default 8);
//! - `ramp:N`: a 1D table, N×1 texels, texel x is (x, x, x, N) / N (read with any t);
//! - `ramp3d:N`: an N³ volume whose texel (x, y, z) is (x, y, z, N) / N;
//! - `banks:N` or `banks:N:P`: the Banks / Heidrich-Seidel anisotropic BRDF table of the Stanford
//!   listings (W. R. Mark's chapter, `shared/seeds/002_a44091d2843c02ac.txt` L3281, L3320), N×N
//!   texels (default 64) for the specular exponent P (default 32). At texel (x, y), with the centres
//!   s = (x + ½) / N, t = (y + ½) / N read as a = 2s − 1 = T·V and b = 2t − 1 = T·L, the texel is
//!   (√(1 − b²), max(0, √(1 − b²) √(1 − a²) − ab)^P, 0, 1): the diffuse and the specular term,
//!   which a shader weights by its kd and ks. The same values as the standard library's
//!   `banks_table(s, t, 1, 0, P)` and `banks_table(s, t, 0, 1, P)` (compiler/stdlib/lighting.sl), computed
//!   here in f64 and rounded once;
//! - `blobs3d:N`: a synthetic density volume, N³ texels (default 32), for volume rendering. At the
//!   texel centre c = ((x, y, z) + ½) / N the density is the sum, clamped to [0, 1], of two soft
//!   spheres, w (1 − (d/r)²)² for distance d < r from their centres — (0.38, 0.42, 0.45) with
//!   r = 0.24, w = 1 and (0.64, 0.6, 0.56) with r = 0.17, w = 0.9 — and a spherical shell
//!   0.55 max(0, 1 − ((d − 0.36)/0.06)²) about (0.5, 0.5, 0.5); the texel is (ρ, ρ, ρ, 1). Every
//!   part is 0 within 0.08 of the unit cube's faces, so a lookup that wraps (`repeat`) at the
//!   border reads 0 there;
//! - `sky:N`: a lat-long environment map (the `environment` lookup's layout, compiler/src/opt/
//!   textures.rs), 2N × N texels (default 64). Texel (x, y) holds the direction D of its centre,
//!   φ = 2π ((x + ½) / 2N − ½), θ = π (y + ½) / N, D = (sin θ sin φ, cos θ, −sin θ cos φ). Above
//!   the horizon (D.y ≥ 0) a gradient from the horizon's (0.85, 0.9, 1) to the zenith's
//!   (0.15, 0.35, 0.8), horizon + (zenith − horizon) D.y, except the sun: where D · S ≥ cos 6°,
//!   S = (1, 1, −1) / √3, the texel is (4, 3.6, 3). Below, a ground of 16 × 8 checks in (s, t) =
//!   (φ / 2π + ½, θ / π): (0.45, 0.4, 0.32) where ⌊16 s⌋ + ⌊8 t⌋ is even, (0.12, 0.1, 0.08)
//!   where odd. Alpha 1. Computed in f64 and rounded once, then given its mip chain (below);
//! - `skycube:N`: the same sky as a cube map of N × N faces (default 32): an atlas 3N × 2N, faces
//!   +X, −X, +Y in the top row and −Y, +Z, −Z below, face texel (i, j) the sky along the
//!   direction of its centre (sc, tc) = (2 (i + ½) / N − 1, 2 (j + ½) / N − 1) in OpenGL's face
//!   axes (+X: (1, −tc, −sc), −X: (−1, −tc, sc), +Y: (sc, 1, tc), −Y: (sc, −1, −tc),
//!   +Z: (sc, −tc, 1), −Z: (−sc, −tc, −1)); for N a power of two with the atlas's mip chain
//!   stacked below it (levels of half the width and height, texels the means of 2 × 2, down to
//!   faces of one texel: a texture 3N × (4N − 2), rows padded with black), which an environment
//!   lookup reads trilinearly by its footprint;
//! - `cube:A,B,C,D,E,F`: a cube map from six square images of one size (files as below), in the
//!   order +X, −X, +Y, −Y, +Z, −Z, packed into that atlas (with its chain when the faces are a
//!   power of two wide).
//!
//! - `env:FILE`: the lat-long map FILE (2:1, a power of two tall) with its mip chain: levels of
//!   half the width and height, each texel the mean of 2 × 2 of the level above, down to 2 × 1,
//!   stacked below level 0 in one texture w × (w − 1), each level's rows padded with black to w.
//!   An environment lookup reads such a map trilinearly by its footprint; any other lat-long map
//!   at level 0.
//!
//! The empty name is no map: one black, transparent texel. Any other name is a file relative to
//! the scene's directory: PNG (8 or 16 bits), or Radiance HDR (`.hdr`, kept in linear floats). An
//! environment lookup reads a texture three texels wide for every two tall as a cube-map atlas,
//! one 3N wide and 4N − 2 tall as a cube-map atlas with its chain, one w wide and w − 1 tall as
//! a lat-long map with its mip chain, and any other one as a lat-long map (2:1) at level 0.

use std::path::Path;
use std::sync::Arc;

use patina_compiler::backend::cpu::Texture;

use super::RenderError;
use crate::gpu::{Address, Filter, TextureData, TextureDimension};

/// Loads or generates the texture `name`. The empty name is no texture: a single black,
/// transparent texel, so that every lookup reads 0, as RenderMan renderers answer a lookup of a
/// missing map (shaders default their map names to `""` and often look up unguarded).
pub fn load(name: &str, base: &Path) -> Result<Texture, RenderError> {
    if name.is_empty() {
        return Ok(Texture { size: [1, 1, 1], texels: Arc::from(vec![[0.0; 4]]) });
    }
    let count =
        |spec: Option<&str>, default: u32| -> Result<u32, RenderError> {
            match spec {
                None => Ok(default),
                Some(n) => n.parse::<u32>().ok().filter(|n| (1..=1024).contains(n)).ok_or_else(|| {
                    RenderError::Input(format!("texture `{name}`: the size must be 1 to 1024"))
                }),
            }
        };
    let (kind, spec) = match name.split_once(':') {
        Some((k, n)) => (k, Some(n)),
        None => (name, None),
    };
    match kind {
        "checker" => {
            let n = count(spec, 8)?;
            let texels = (0..n * n)
                .map(|i| if (i % n + i / n) % 2 == 0 { [1.0; 4] } else { [0.0, 0.0, 0.0, 1.0] })
                .collect::<Vec<_>>();
            Ok(Texture { size: [n, n, 1], texels: Arc::from(texels) })
        }
        "ramp" => {
            let n = count(spec, 16)?;
            let texels = (0..n)
                .map(|x| [x as f32 / n as f32, x as f32 / n as f32, x as f32 / n as f32, 1.0])
                .collect::<Vec<_>>();
            Ok(Texture { size: [n, 1, 1], texels: Arc::from(texels) })
        }
        "ramp3d" => {
            let n = count(spec, 16)?;
            let f = n as f32;
            let texels = (0..n * n * n)
                .map(|i| [(i % n) as f32 / f, (i / n % n) as f32 / f, (i / (n * n)) as f32 / f, 1.0])
                .collect::<Vec<_>>();
            Ok(Texture { size: [n, n, n], texels: Arc::from(texels) })
        }
        "banks" => {
            let (size, exponent) = match spec.map(|s| s.split_once(':').unwrap_or((s, ""))) {
                None => (None, 32.0),
                Some((n, "")) => (Some(n), 32.0),
                Some((n, p)) => (
                    Some(n),
                    p.parse::<f64>().ok().filter(|p| p.is_finite() && (0.0..=1e4).contains(p)).ok_or_else(
                        || RenderError::Input(format!("texture `{name}`: the exponent must be 0 to 10000")),
                    )?,
                ),
            };
            let n = count(size, 64)?;
            let texels = (0..n * n)
                .map(|i| {
                    let [diffuse, specular] = banks_texel(i % n, i / n, n, exponent);
                    [diffuse as f32, specular as f32, 0.0, 1.0]
                })
                .collect::<Vec<_>>();
            Ok(Texture { size: [n, n, 1], texels: Arc::from(texels) })
        }
        "blobs3d" => {
            let n = count(spec, 32)?;
            let centre = |i: u32| (f64::from(i) + 0.5) / f64::from(n);
            let texels = (0..n * n * n)
                .map(|i| {
                    let rho = blobs_density([centre(i % n), centre(i / n % n), centre(i / (n * n))]) as f32;
                    [rho, rho, rho, 1.0]
                })
                .collect::<Vec<_>>();
            Ok(Texture { size: [n, n, n], texels: Arc::from(texels) })
        }
        "sky" => {
            let n = count(spec, 64)?;
            let texels = (0..2 * n * n)
                .map(|i| {
                    let (x, y) = (i % (2 * n), i / (2 * n));
                    let phi = std::f64::consts::TAU * ((f64::from(x) + 0.5) / f64::from(2 * n) - 0.5);
                    let theta = std::f64::consts::PI * (f64::from(y) + 0.5) / f64::from(n);
                    let d = [theta.sin() * phi.sin(), theta.cos(), -theta.sin() * phi.cos()];
                    sky_texel(d).map(|c| c as f32)
                })
                .collect::<Vec<_>>();
            Ok(with_chain(2 * n, n, texels))
        }
        "env" => {
            let file = spec.unwrap_or("");
            let level0 = read_file(file, base)?;
            let [w, h, _] = level0.size;
            if w != 2 * h || !h.is_power_of_two() {
                return Err(RenderError::Input(format!(
                    "texture `{name}`: a lat-long map with a mip chain must be twice as wide as tall, \
                     a power of two (`{file}` is {w}x{h})"
                )));
            }
            Ok(with_chain(w, h, level0.texels.to_vec()))
        }
        "skycube" => {
            let n = count(spec, 32)?;
            let faces: Vec<Vec<[f32; 4]>> = (0..6)
                .map(|face| {
                    (0..n * n)
                        .map(|i| {
                            let centre = |k: u32| 2.0 * (f64::from(k) + 0.5) / f64::from(n) - 1.0;
                            sky_texel(face_direction(face, centre(i % n), centre(i / n))).map(|c| c as f32)
                        })
                        .collect()
                })
                .collect();
            Ok(atlas(n, &faces))
        }
        "cube" => {
            let files: Vec<&str> = spec.unwrap_or("").split(',').map(str::trim).collect();
            if files.len() != 6 || files.iter().any(|f| f.is_empty()) {
                return Err(RenderError::Input(format!(
                    "texture `{name}`: a cube map names six images, +X, -X, +Y, -Y, +Z, -Z, separated by commas"
                )));
            }
            let mut faces = Vec::new();
            let mut size = None;
            for file in files {
                let face = read_file(file, base)?;
                let [w, h, _] = face.size;
                if w != h || size.is_some_and(|s| s != w) {
                    return Err(RenderError::Input(format!(
                        "texture `{name}`: the faces must be square and of one size (`{file}` is {w}x{h})"
                    )));
                }
                size = Some(w);
                faces.push(face.texels.to_vec());
            }
            Ok(atlas(size.unwrap_or(1), &faces))
        }
        _ => read_file(name, base),
    }
}

/// A texture file relative to `base`: Radiance HDR by its `.hdr` extension (linear floats), else
/// PNG.
fn read_file(name: &str, base: &Path) -> Result<Texture, RenderError> {
    let path = base.join(name);
    if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("hdr")) {
        let error = |e: String| RenderError::Input(format!("texture `{name}`: {}: {e}", path.display()));
        let decoded = image::ImageReader::open(&path)
            .map_err(|e| error(e.to_string()))?
            .with_guessed_format()
            .map_err(|e| error(e.to_string()))?
            .decode()
            .map_err(|e| error(e.to_string()))?;
        let (w, h) = (decoded.width(), decoded.height());
        let texels: Vec<[f32; 4]> = decoded.to_rgba32f().pixels().map(|p| p.0).collect();
        return Ok(Texture { size: [w, h, 1], texels: Arc::from(texels) });
    }
    let image = crate::image::Image::read_png(&path)
        .map_err(|e| RenderError::Input(format!("texture `{name}`: {e}")))?;
    Ok(Texture { size: [image.width, image.height, 1], texels: Arc::from(image.pixels) })
}

/// A lat-long map's level 0 (w × h, w = 2h, h a power of two) with its mip chain below it: each
/// level the mean of 2 × 2 texels of the previous one, down to 2 × 1, stacked in one texture
/// w × (w − 1) (the layout `environment` lookups read, compiler/src/opt/textures.rs).
fn with_chain(w: u32, h: u32, level0: Vec<[f32; 4]>) -> Texture {
    stacked_chain(w, h, level0, 1)
}

/// Level 0 (w × h) and each level below it, half as wide and tall, its texels the means of 2 × 2
/// of the level above, down to `last` rows, stacked in one texture w wide (each level's rows
/// padded with black to w).
fn stacked_chain(w: u32, h: u32, level0: Vec<[f32; 4]>, last: u32) -> Texture {
    let mut texels = level0.clone();
    let (mut level, mut lw, mut lh) = (level0, w, h);
    let mut height = h;
    while lh > last {
        let (nw, nh) = (lw / 2, lh / 2);
        let next: Vec<[f32; 4]> = (0..nw * nh)
            .map(|i| {
                let (x, y) = ((i % nw) * 2, (i / nw) * 2);
                let at = |dx: u32, dy: u32| level[((y + dy) * lw + x + dx) as usize];
                let (a, b, c, d) = (at(0, 0), at(1, 0), at(0, 1), at(1, 1));
                [0, 1, 2, 3].map(|k| (a[k] + b[k] + c[k] + d[k]) * 0.25)
            })
            .collect();
        for row in next.chunks(nw as usize) {
            texels.extend_from_slice(row);
            texels.extend(std::iter::repeat_n([0.0f32, 0.0, 0.0, 1.0], (w - nw) as usize));
        }
        height += nh;
        (level, lw, lh) = (next, nw, nh);
    }
    Texture { size: [w, height, 1], texels: Arc::from(texels) }
}

/// Six n × n faces (+X, −X, +Y, −Y, +Z, −Z) packed into the 3n × 2n cube-map atlas; when n is a
/// power of two, with the atlas's mip chain below it down to faces of one texel (a texture
/// 3n × (4n − 2): a 2 × 2 block of a level never straddles two faces).
fn atlas(n: u32, faces: &[Vec<[f32; 4]>]) -> Texture {
    let (w, h) = (3 * n, 2 * n);
    let texels = (0..w * h)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            let face = (y / n * 3 + x / n) as usize;
            faces[face][((y % n) * n + x % n) as usize]
        })
        .collect::<Vec<_>>();
    if n.is_power_of_two() {
        return stacked_chain(w, h, texels, 2);
    }
    Texture { size: [w, h, 1], texels: Arc::from(texels) }
}

/// The direction of face coordinates (sc, tc) on cube face `face` (+X, −X, +Y, −Y, +Z, −Z), in
/// OpenGL's face axes.
fn face_direction(face: u32, sc: f64, tc: f64) -> [f64; 3] {
    match face {
        0 => [1.0, -tc, -sc],
        1 => [-1.0, -tc, sc],
        2 => [sc, 1.0, tc],
        3 => [sc, -1.0, -tc],
        4 => [sc, -tc, 1.0],
        _ => [-sc, -tc, -1.0],
    }
}

/// The `sky` environment along `d` (any length; the module documentation gives the formula).
pub(crate) fn sky_texel(d: [f64; 3]) -> [f64; 4] {
    let length = (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt().max(1e-300);
    let d = d.map(|c| c / length);
    if d[1] >= 0.0 {
        let sun = (d[0] - d[2] + d[1]) / 3f64.sqrt();
        if sun >= 6f64.to_radians().cos() {
            return [4.0, 3.6, 3.0, 1.0];
        }
        let (horizon, zenith) = ([0.85, 0.9, 1.0], [0.15, 0.35, 0.8]);
        let c = |k: usize| horizon[k] + (zenith[k] - horizon[k]) * d[1];
        [c(0), c(1), c(2), 1.0]
    } else {
        let s = d[0].atan2(-d[2]) / std::f64::consts::TAU + 0.5;
        let t = (d[0].hypot(d[2])).atan2(d[1]) / std::f64::consts::PI;
        let check = ((16.0 * s).floor() as i64 + (8.0 * t).floor() as i64).rem_euclid(2);
        if check == 0 { [0.45, 0.4, 0.32, 1.0] } else { [0.12, 0.1, 0.08, 1.0] }
    }
}

/// The `banks:N:P` table's diffuse and specular terms at texel (x, y) of an N×N table.
fn banks_texel(x: u32, y: u32, n: u32, exponent: f64) -> [f64; 2] {
    let a = 2.0 * (f64::from(x) + 0.5) / f64::from(n) - 1.0;
    let b = 2.0 * (f64::from(y) + 0.5) / f64::from(n) - 1.0;
    let (sa, sb) = ((1.0 - a * a).max(0.0).sqrt(), (1.0 - b * b).max(0.0).sqrt());
    let cosine = (sb * sa - a * b).clamp(0.0, 1.0);
    // x^0 = 1, also at x = 0 (as the standard library's lighting_pow01).
    [sb, if exponent == 0.0 { 1.0 } else { cosine.powf(exponent) }]
}

/// The `blobs3d` density at a point of the unit cube (the module documentation gives the formula).
fn blobs_density(p: [f64; 3]) -> f64 {
    let distance =
        |c: [f64; 3]| ((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2) + (p[2] - c[2]).powi(2)).sqrt();
    let soft = |c: [f64; 3], r: f64, w: f64| {
        let q = distance(c) / r;
        if q < 1.0 { w * (1.0 - q * q).powi(2) } else { 0.0 }
    };
    let shell = {
        let q = (distance([0.5; 3]) - 0.36) / 0.06;
        0.55 * (1.0 - q * q).max(0.0)
    };
    (soft([0.38, 0.42, 0.45], 0.24, 1.0) + soft([0.64, 0.6, 0.56], 0.17, 0.9) + shell).clamp(0.0, 1.0)
}

/// The GPU form of a texture (the shaders fetch texels; the sampler is never used).
pub fn gpu_data(texture: &Texture, dimensions: u32) -> TextureData {
    TextureData {
        dimension: if dimensions == 3 { TextureDimension::D3 } else { TextureDimension::D2 },
        size: texture.size,
        texels: texture.texels.to_vec(),
        filter: Filter::Nearest,
        address: Address::Repeat,
        mipmaps: false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn generated_tables_have_their_sizes_and_values() {
        let base = Path::new(".");
        let checker = load("checker:4", base).unwrap();
        assert_eq!(checker.size, [4, 4, 1]);
        assert_eq!((checker.texels[0][0], checker.texels[1][0], checker.texels[4][0]), (1.0, 0.0, 0.0));
        let ramp = load("ramp:8", base).unwrap();
        assert_eq!(ramp.size, [8, 1, 1]);
        assert_eq!(ramp.texels[4], [0.5, 0.5, 0.5, 1.0]);
        let volume = load("ramp3d:2", base).unwrap();
        assert_eq!(volume.texels[7], [0.5, 0.5, 0.5, 1.0]);
        assert!(load("checker:0", base).is_err());
        assert!(load("banks:8:-1", base).is_err());
        assert!(load("banks:8:x", base).is_err());
        assert!(load("missing.png", base).is_err());
        assert!(load("missing.hdr", base).is_err());
        assert!(load("sky:0", base).is_err());
        assert!(load("env:missing.png", base).is_err());
        assert_eq!(load("", base).unwrap(), Texture::default());
        assert!(load("cube:a.png,b.png", base).is_err());
        assert!(load("cube:a.png,b.png,c.png,d.png,e.png,f.png", base).is_err());
    }

    #[test]
    fn hdr_files_cube_faces_and_chains_load_from_files() {
        let dir = std::env::temp_dir().join(format!("patina-textures-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        // A 4 x 2 Radiance HDR file with values above 1 (powers of two survive RGBE exactly).
        let values = [8.0f32, 0.5, 2.0, 1.0, 0.25, 4.0, 16.0, 0.125];
        let rgb: Vec<image::Rgb<f32>> = values.iter().map(|&v| image::Rgb([v, v / 2.0, v / 4.0])).collect();
        let file = std::fs::File::create(dir.join("map.hdr")).unwrap();
        image::codecs::hdr::HdrEncoder::new(std::io::BufWriter::new(file)).encode(&rgb, 4, 2).unwrap();
        let hdr = load("map.hdr", &dir).unwrap();
        assert_eq!(hdr.size, [4, 2, 1]);
        assert_eq!(hdr.texels[0], [8.0, 4.0, 2.0, 1.0]);
        assert_eq!(hdr.texels[6], [16.0, 8.0, 4.0, 1.0]);
        // With its chain: 4 x 3, level 1 (2 x 1) the means of the 2 x 2 blocks, padded to 4.
        let chained = load("env:map.hdr", &dir).unwrap();
        assert_eq!(chained.size, [4, 3, 1]);
        assert_eq!(chained.texels[8][0], (8.0 + 0.5 + 0.25 + 4.0) / 4.0);
        assert_eq!(chained.texels[9][0], (2.0 + 1.0 + 16.0 + 0.125) / 4.0);
        assert_eq!(chained.texels[10], [0.0, 0.0, 0.0, 1.0]);
        // Six 2 x 2 faces, face k's texels k/8 in red: the atlas puts +X, -X, +Y on top.
        let names: Vec<String> = (0..6).map(|k| format!("face{k}.png")).collect();
        for (k, name) in names.iter().enumerate() {
            let v = k as f32 / 8.0;
            let face = crate::image::Image { width: 2, height: 2, pixels: vec![[v, 0.0, 0.0, 1.0]; 4] };
            face.write_png(dir.join(name)).unwrap();
        }
        let cube = load(&format!("cube:{}", names.join(",")), &dir).unwrap();
        // The atlas, 6 x 4, and its chain (faces of one texel, 3 x 2) below it.
        assert_eq!(cube.size, [6, 6, 1]);
        let red = |x: u32, y: u32| (cube.texels[(y * 6 + x) as usize][0] * 8.0).round() as u32;
        assert_eq!([red(0, 0), red(3, 1), red(5, 0), red(0, 2), red(2, 3), red(5, 3)], [0, 1, 2, 3, 4, 5]);
        assert_eq!([red(0, 4), red(1, 4), red(2, 4), red(0, 5), red(1, 5), red(2, 5)], [0, 1, 2, 3, 4, 5]);
        // Faces three texels wide have no chain.
        for (k, name) in names.iter().enumerate() {
            let v = k as f32 / 8.0;
            let face = crate::image::Image { width: 3, height: 3, pixels: vec![[v, 0.0, 0.0, 1.0]; 9] };
            face.write_png(dir.join(format!("odd{name}"))).unwrap();
        }
        let odd: Vec<String> = names.iter().map(|n| format!("odd{n}")).collect();
        assert_eq!(load(&format!("cube:{}", odd.join(",")), &dir).unwrap().size, [9, 6, 1]);
        // Faces of different sizes, or not square, are one error naming the face.
        let wide = crate::image::Image { width: 4, height: 2, pixels: vec![[0.0; 4]; 8] };
        wide.write_png(dir.join("wide.png")).unwrap();
        let bad = names[..5].join(",") + ",wide.png";
        let message = load(&format!("cube:{bad}"), &dir).unwrap_err().to_string();
        assert!(message.contains("wide.png") && message.contains("square"), "{message}");
        // A chain needs a 2:1 map a power of two tall.
        assert!(load("env:wide.png", &dir).is_ok());
        assert!(load("env:face0.png", &dir).unwrap_err().to_string().contains("twice as wide"));
        std::fs::remove_dir_all(&dir).ok();
    }

    #[test]
    fn sky_maps_hold_the_sky_along_their_texel_centres() {
        let base = Path::new(".");
        let sky = load("sky:16", base).unwrap();
        // Level 0, 32 × 16, with its chain below: 16 + 8 + 4 + 2 + 1 rows.
        assert_eq!(sky.size, [32, 31, 1]);
        // Level 1's texel (3, 2), at row 16 + 2, is the mean of level 0's (6..8, 4..6).
        let level0 = |x: u32, y: u32| sky.texels[(y * 32 + x) as usize];
        let mean = [0, 1, 2, 3]
            .map(|k| (level0(6, 4)[k] + level0(7, 4)[k] + level0(6, 5)[k] + level0(7, 5)[k]) * 0.25);
        assert_eq!(sky.texels[(18 * 32 + 3) as usize], mean);
        // The last level, 2 × 1 at row 30, holds the means of the two halves of the map.
        let half = |x0: u32| {
            let sum: f64 = (0..16)
                .flat_map(|y| (x0..x0 + 16).map(move |x| (x, y)))
                .map(|(x, y)| f64::from(level0(x, y)[2]))
                .sum();
            sum / 256.0
        };
        assert!((f64::from(sky.texels[30 * 32][2]) - half(0)).abs() < 1e-5);
        assert!((f64::from(sky.texels[30 * 32 + 1][2]) - half(16)).abs() < 1e-5);
        assert_eq!(sky.texels[30 * 32 + 2], [0.0, 0.0, 0.0, 1.0]);
        // The top rows are sky near the zenith, the bottom ones ground checks.
        let top = sky.texels[0];
        assert!(top[2] < 0.81 && top[2] > 0.79 && top[0] < 0.2, "{top:?}");
        let bottom = sky.texels[(15 * 32) as usize];
        assert!(bottom == [0.45, 0.4, 0.32, 1.0] || bottom == [0.12, 0.1, 0.08, 1.0], "{bottom:?}");
        // The sun, S = (1, 1, -1)/√3: s = atan(1, 1)/2π + ½ = 0.625, t = acos(1/√3)/π = 0.304:
        // texel (80, 19) of sky:64, whose centre is 1.1° from S.
        let large = load("sky:64", base).unwrap();
        assert_eq!(large.size, [128, 127, 1]);
        assert_eq!(large.texels[(19 * 128 + 80) as usize], [4.0, 3.6, 3.0, 1.0]);
        assert_ne!(large.texels[(19 * 128 + 90) as usize], [4.0, 3.6, 3.0, 1.0]);
        // The cube map's face texels agree with the formula along their own directions.
        let cube = load("skycube:4", base).unwrap();
        // The atlas (12 x 8) and its chain below it: 6 x 4 and 3 x 2, in 4 * 4 - 2 = 14 rows.
        assert_eq!(cube.size, [12, 14, 1]);
        // Level 1's first texel is the mean of +X's top-left 2 x 2 block; level 2's +Z texel
        // (the second of its bottom row) the mean of the +Z face.
        let mean = |texels: &[[f32; 4]]| {
            [0, 1, 2, 3].map(|k| texels.iter().map(|t| t[k]).sum::<f32>() / texels.len() as f32)
        };
        let at = |x: u32, y: u32| cube.texels[(y * 12 + x) as usize];
        let block = [at(0, 0), at(1, 0), at(0, 1), at(1, 1)];
        assert_eq!(
            cube.texels[(8 * 12) as usize],
            [0, 1, 2, 3].map(|k| (block[0][k] + block[1][k] + block[2][k] + block[3][k]) * 0.25)
        );
        let face: Vec<[f32; 4]> =
            (4..8).flat_map(|y| (4..8).map(move |x| (x, y))).map(|(x, y)| at(x, y)).collect();
        let level2 = at(1, 13);
        assert!((0..4).all(|k| (level2[k] - mean(&face)[k]).abs() < 1e-6), "{level2:?} {:?}", mean(&face));
        // Past each level's width, the rows are black padding.
        assert_eq!(at(6, 8), [0.0, 0.0, 0.0, 1.0]);
        // +Y face (top row, third), texel (1, 2): sc = -0.25, tc = 0.25, D = (-0.25, 1, 0.25).
        let texel = cube.texels[(2 * 12 + 8 + 1) as usize];
        assert_eq!(texel, sky_texel([-0.25, 1.0, 0.25]).map(|c| c as f32));
        // -Z face (bottom row, third), texel (0, 3): sc = -0.75, tc = 0.75, D = (0.75, -0.75, -1):
        // below the horizon.
        let texel = cube.texels[(7 * 12 + 8) as usize];
        assert!(texel == [0.45, 0.4, 0.32, 1.0] || texel == [0.12, 0.1, 0.08, 1.0], "{texel:?}");
    }

    #[test]
    fn banks_table_holds_the_diffuse_and_specular_terms() {
        let base = Path::new(".");
        let table = load("banks:16:8", base).unwrap();
        assert_eq!(table.size, [16, 16, 1]);
        assert_eq!(load("banks", base).unwrap().size, [64, 64, 1]);
        for y in 0..16u32 {
            for x in 0..16u32 {
                // T·V and T·L at the texel centre, and the angles they are cosines of.
                let a = (f64::from(x) + 0.5) / 8.0 - 1.0;
                let b = (f64::from(y) + 0.5) / 8.0 - 1.0;
                let (theta_v, theta_l) = (a.acos(), b.acos());
                let texel = table.texels[(y * 16 + x) as usize];
                // Diffuse: sin of the angle between the fibre and the light.
                assert!((f64::from(texel[0]) - theta_l.sin()).abs() < 1e-6, "diffuse at ({x}, {y})");
                // Specular: V·R for R on the mirror cone of -L about T is cos(π - θl - θv), to
                // the 8th where positive.
                let specular = (std::f64::consts::PI - theta_l - theta_v).cos().max(0.0).powi(8);
                assert!((f64::from(texel[1]) - specular).abs() < 1e-6, "specular at ({x}, {y})");
                assert_eq!((texel[2], texel[3]), (0.0, 1.0));
            }
        }
        // The peak is where T·V = -T·L: on the anti-diagonal x + y = 15 the specular term is 1.
        assert!(table.texels[(3 * 16 + 12) as usize][1] > 0.999_99);
        assert!(table.texels[(3 * 16 + 3) as usize][1] < 0.5);
    }

    #[test]
    fn blobs_volume_is_a_density_in_the_unit_range() {
        let base = Path::new(".");
        let n = 32u32;
        let volume = load("blobs3d:32", base).unwrap();
        assert_eq!(volume.size, [n, n, n]);
        let at = |x: u32, y: u32, z: u32| volume.texels[(x + n * (y + n * z)) as usize];
        let mut max = 0.0f32;
        for (i, t) in volume.texels.iter().enumerate() {
            assert!(
                (0.0..=1.0).contains(&t[0]) && t[0] == t[1] && t[1] == t[2] && t[3] == 1.0,
                "texel {i}: {t:?}"
            );
            max = max.max(t[0]);
        }
        // The densest texel is the one nearest the first blob's centre.
        assert!(max > 0.995 && max <= 1.0, "{max}");
        // Every texel of the outer two layers of each face is empty (the lookup wraps there).
        for a in 0..n {
            for b in 0..n {
                for c in [0, 1, n - 2, n - 1] {
                    assert_eq!(
                        [at(c, a, b)[0], at(a, c, b)[0], at(a, b, c)[0]],
                        [0.0; 3],
                        "border ({a}, {b}, {c})"
                    );
                }
            }
        }
        // Texel (12, 13, 14) has centre (0.390625, 0.421875, 0.453125): 0.011233 from the first
        // blob's centre, so (1 - (0.011233/0.24)^2)^2 = 0.995624; 0.325 from the second's and
        // 0.142 from the shell's centre (both outside).
        assert!((at(12, 13, 14)[0] - 0.995_624).abs() < 1e-6, "{:?}", at(12, 13, 14));
        // On the shell, far from both blobs: texel (16, 16, 27), centre (0.515625, 0.515625,
        // 0.859375), 0.360054 from the centre: 0.55 (1 - (0.000054/0.06)^2) = 0.5499996.
        assert!((at(16, 16, 27)[0] - 0.549_999_6).abs() < 1e-6, "{:?}", at(16, 16, 27));
        // Between the shell and the blobs: empty (centre (0.48, 0.48, 0.77), 0.27 from the centre).
        assert_eq!(at(15, 15, 24)[0], 0.0);
    }
}
