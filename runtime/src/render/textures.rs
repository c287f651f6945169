//! The textures a scene's shaders read, by name: a PNG file (relative to the scene's directory)
//! or a generated table — `checker` or `checker:N` (an N×N black-and-white board, default 8),
//! `ramp:N` (a 1D table: N×1 texels, texel x is (x, x, x, N) / N, read with any t) and
//! `ramp3d:N` (an N³ volume whose texel (x, y, z) is (x, y, z, N) / N).

use std::path::Path;
use std::sync::Arc;

use patina_compiler::backend::cpu::Texture;

use super::RenderError;
use crate::gpu::{Address, Filter, TextureData, TextureDimension};

/// Loads or generates the texture `name`.
pub fn load(name: &str, base: &Path) -> Result<Texture, RenderError> {
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
        _ => {
            let path = base.join(name);
            let image = crate::image::Image::read_png(&path)
                .map_err(|e| RenderError::Input(format!("texture `{name}`: {e}")))?;
            Ok(Texture { size: [image.width, image.height, 1], texels: Arc::from(image.pixels) })
        }
    }
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
        assert!(load("missing.png", base).is_err());
    }
}
