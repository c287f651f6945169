//! Sampled textures: the caller's texels, their mip chain, and the wgpu texture and sampler.

use super::{Gpu, GpuError};

/// How many coordinates a texture has.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TextureDimension {
    /// `texture_1d`: `size` is `[width, 1, 1]`.
    D1,
    /// `texture_2d`: `size` is `[width, height, 1]`.
    D2,
    /// `texture_3d`: `size` is `[width, height, depth]`.
    D3,
}

/// Texel filtering, for magnification, minification and between mip levels alike.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Filter {
    /// The nearest texel (and the nearest mip level).
    Nearest,
    /// Linear interpolation between texels (and between mip levels).
    Linear,
}

/// What a coordinate outside [0, 1] reads, on every axis.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Address {
    /// Wrap around.
    Repeat,
    /// The edge texel.
    ClampToEdge,
    /// Wrap around, mirroring every other repetition.
    MirrorRepeat,
}

/// A texture to sample in a draw: RGBA float texels, x fastest, then y, then z.
#[derive(Debug, Clone, PartialEq)]
pub struct TextureData {
    /// 1D, 2D or 3D; must agree with the shader's texture type.
    pub dimension: TextureDimension,
    /// Width, height and depth in texels; unused axes are 1.
    pub size: [u32; 3],
    /// `size[0] * size[1] * size[2]` texels, row 0 first (row 0 is at v = 0).
    pub texels: Vec<[f32; 4]>,
    /// Filtering for the sampler bound beside the texture.
    pub filter: Filter,
    /// Addressing for the sampler bound beside the texture.
    pub address: Address,
    /// Whether to build a mip chain by 2x box filtering. Ignored for 1D textures, which WebGPU
    /// allows only one level.
    pub mipmaps: bool,
}

impl TextureData {
    pub(super) fn check(&self) -> Result<(), GpuError> {
        let [w, h, d] = self.size;
        let shape_ok = match self.dimension {
            TextureDimension::D1 => h == 1 && d == 1,
            TextureDimension::D2 => d == 1,
            TextureDimension::D3 => true,
        };
        if w == 0 || h == 0 || d == 0 || !shape_ok {
            return Err(GpuError::InvalidInput(format!(
                "texture size {:?} does not fit a {:?} texture",
                self.size, self.dimension
            )));
        }
        let count = u64::from(w) * u64::from(h) * u64::from(d);
        if count != self.texels.len() as u64 {
            return Err(GpuError::InvalidInput(format!(
                "texture of size {:?} needs {count} texels, got {}",
                self.size,
                self.texels.len()
            )));
        }
        Ok(())
    }

    /// Level 0 and, with `mipmaps`, every smaller level down to 1x1(x1), each with its size.
    fn levels(&self) -> Vec<([u32; 3], Vec<[f32; 4]>)> {
        let mut levels = vec![(self.size, self.texels.clone())];
        if !self.mipmaps || self.dimension == TextureDimension::D1 {
            return levels;
        }
        while let Some((size, texels)) = levels.last() {
            if size.iter().all(|&n| n == 1) {
                break;
            }
            let next = downsample(*size, texels);
            levels.push(next);
        }
        levels
    }
}

/// One 2x box-filter step. Level sizes halve rounding down (as WebGPU's do), so an odd axis leaves
/// its last texel out; an axis of length 1 stays 1 and is not averaged along.
fn downsample(size: [u32; 3], texels: &[[f32; 4]]) -> ([u32; 3], Vec<[f32; 4]>) {
    let half = size.map(|n| (n / 2).max(1));
    let index = |x: u32, y: u32, z: u32| ((z * size[1] + y) * size[0] + x) as usize;
    let mut out = Vec::with_capacity((half[0] * half[1] * half[2]) as usize);
    for z in 0..half[2] {
        for y in 0..half[1] {
            for x in 0..half[0] {
                let mut sum = [0.0f32; 4];
                let mut count = 0.0f32;
                for (dx, dy, dz) in (0..8).map(|i| (i & 1, (i >> 1) & 1, i >> 2)) {
                    if (dx == 1 && size[0] == 1) || (dy == 1 && size[1] == 1) || (dz == 1 && size[2] == 1) {
                        continue;
                    }
                    let t = texels[index(2 * x + dx, 2 * y + dy, 2 * z + dz)];
                    for c in 0..4 {
                        sum[c] += t[c];
                    }
                    count += 1.0;
                }
                out.push(sum.map(|s| s / count));
            }
        }
    }
    (half, out)
}

/// A texture's view and sampler, kept alive for a bind group.
pub(super) struct Uploaded {
    pub view: wgpu::TextureView,
    pub sampler: wgpu::Sampler,
}

pub(super) fn view_dimension(d: TextureDimension) -> wgpu::TextureViewDimension {
    match d {
        TextureDimension::D1 => wgpu::TextureViewDimension::D1,
        TextureDimension::D2 => wgpu::TextureViewDimension::D2,
        TextureDimension::D3 => wgpu::TextureViewDimension::D3,
    }
}

impl Gpu {
    /// Creates the texture with every level uploaded, and its sampler. Call inside `scoped`.
    pub(super) fn upload_texture(&self, data: &TextureData) -> Result<Uploaded, GpuError> {
        data.check()?;
        let levels = data.levels();
        let format = self.texture_format;
        let texel_bytes = format.block_copy_size(None).unwrap_or(16);
        let texture = self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("patina texture"),
            size: extent(data.size),
            mip_level_count: levels.len() as u32,
            sample_count: 1,
            dimension: match data.dimension {
                TextureDimension::D1 => wgpu::TextureDimension::D1,
                TextureDimension::D2 => wgpu::TextureDimension::D2,
                TextureDimension::D3 => wgpu::TextureDimension::D3,
            },
            format,
            usage: wgpu::TextureUsages::TEXTURE_BINDING | wgpu::TextureUsages::COPY_DST,
            view_formats: &[],
        });
        for (level, (size, texels)) in levels.iter().enumerate() {
            let bytes = encode_texels(texels, format);
            self.queue.write_texture(
                wgpu::TexelCopyTextureInfo {
                    texture: &texture,
                    mip_level: level as u32,
                    origin: wgpu::Origin3d::ZERO,
                    aspect: wgpu::TextureAspect::All,
                },
                &bytes,
                wgpu::TexelCopyBufferLayout {
                    offset: 0,
                    bytes_per_row: Some(size[0] * texel_bytes),
                    rows_per_image: Some(size[1]),
                },
                extent(*size),
            );
        }
        let view = texture.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(view_dimension(data.dimension)),
            ..Default::default()
        });
        let address = match data.address {
            Address::Repeat => wgpu::AddressMode::Repeat,
            Address::ClampToEdge => wgpu::AddressMode::ClampToEdge,
            Address::MirrorRepeat => wgpu::AddressMode::MirrorRepeat,
        };
        let (filter, mipmap_filter) = match data.filter {
            Filter::Nearest => (wgpu::FilterMode::Nearest, wgpu::MipmapFilterMode::Nearest),
            Filter::Linear => (wgpu::FilterMode::Linear, wgpu::MipmapFilterMode::Linear),
        };
        let sampler = self.device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("patina sampler"),
            address_mode_u: address,
            address_mode_v: address,
            address_mode_w: address,
            mag_filter: filter,
            min_filter: filter,
            mipmap_filter,
            ..Default::default()
        });
        Ok(Uploaded { view, sampler })
    }
}

fn extent([width, height, depth_or_array_layers]: [u32; 3]) -> wgpu::Extent3d {
    wgpu::Extent3d { width, height, depth_or_array_layers }
}

fn encode_texels(texels: &[[f32; 4]], format: wgpu::TextureFormat) -> Vec<u8> {
    let channels = texels.iter().flatten();
    if format == wgpu::TextureFormat::Rgba16Float {
        channels.flat_map(|&c| f16_bits(c).to_le_bytes()).collect()
    } else {
        channels.flat_map(|&c| c.to_le_bytes()).collect()
    }
}

/// IEEE binary16 bits of `x`, rounded to nearest even (the fallback when f32 is not filterable).
fn f16_bits(x: f32) -> u16 {
    let bits = x.to_bits();
    let sign = ((bits >> 16) & 0x8000) as u16;
    let exponent = ((bits >> 23) & 0xff) as i32;
    let mantissa = bits & 0x7f_ffff;
    if exponent == 0xff {
        let nan = if mantissa != 0 { 0x200 } else { 0 };
        return sign | 0x7c00 | nan;
    }
    let e = exponent - 127 + 15;
    let magnitude = if e >= 0x1f {
        0x7c00
    } else if e > 0 {
        // A rounding carry out of the mantissa correctly bumps the exponent (up to infinity).
        ((e as u32) << 10) + round_shift(mantissa, 13)
    } else if e >= -10 {
        round_shift(mantissa | 0x80_0000, (14 - e) as u32)
    } else {
        0
    };
    sign | magnitude as u16
}

fn round_shift(value: u32, shift: u32) -> u32 {
    let kept = value >> shift;
    let rest = value & ((1 << shift) - 1);
    let half = 1 << (shift - 1);
    if rest > half || (rest == half && kept & 1 == 1) { kept + 1 } else { kept }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn data(dimension: TextureDimension, size: [u32; 3], texels: Vec<[f32; 4]>) -> TextureData {
        TextureData {
            dimension,
            size,
            texels,
            filter: Filter::Nearest,
            address: Address::ClampToEdge,
            mipmaps: true,
        }
    }

    #[test]
    fn mip_chain_of_2d_is_box_filtered_to_1x1() {
        let texels = (0..16).map(|i| [i as f32, 0.0, 0.0, 1.0]).collect();
        let levels = data(TextureDimension::D2, [4, 4, 1], texels).levels();
        let sizes: Vec<_> = levels.iter().map(|l| l.0).collect();
        assert_eq!(sizes, [[4, 4, 1], [2, 2, 1], [1, 1, 1]]);
        // Texels 0,1,4,5 average to 2.5; the 1x1 level is the mean of all sixteen.
        assert_eq!(levels[1].1.iter().map(|t| t[0]).collect::<Vec<_>>(), [2.5, 4.5, 10.5, 12.5]);
        assert_eq!(levels[2].1, [[7.5, 0.0, 0.0, 1.0]]);
    }

    #[test]
    fn mip_chain_handles_odd_and_flat_axes() {
        let texels = (0..6).map(|i| [i as f32; 4]).collect();
        let levels = data(TextureDimension::D3, [3, 1, 2], texels).levels();
        let sizes: Vec<_> = levels.iter().map(|l| l.0).collect();
        assert_eq!(sizes, [[3, 1, 2], [1, 1, 1]]);
        assert_eq!(levels[1].1[0][0], (0.0 + 1.0 + 3.0 + 4.0) / 4.0);
        let one_d = data(TextureDimension::D1, [4, 1, 1], vec![[0.0; 4]; 4]);
        assert_eq!(one_d.levels().len(), 1);
    }

    #[test]
    fn bad_sizes_are_errors() {
        assert!(data(TextureDimension::D2, [2, 2, 1], vec![[0.0; 4]; 3]).check().is_err());
        assert!(data(TextureDimension::D1, [2, 2, 1], vec![[0.0; 4]; 4]).check().is_err());
        assert!(data(TextureDimension::D2, [0, 2, 1], vec![]).check().is_err());
        assert!(data(TextureDimension::D3, [1, 2, 2], vec![[0.0; 4]; 4]).check().is_ok());
    }

    #[test]
    fn f16_conversion_rounds_to_nearest_even() {
        assert_eq!(f16_bits(1.0), 0x3c00);
        assert_eq!(f16_bits(-2.0), 0xc000);
        assert_eq!(f16_bits(0.5), 0x3800);
        assert_eq!(f16_bits(65504.0), 0x7bff);
        assert_eq!(f16_bits(65520.0), 0x7c00); // rounds up to infinity
        assert_eq!(f16_bits(f32::INFINITY), 0x7c00);
        assert_eq!(f16_bits(f32::NAN) & 0x7e00, 0x7e00);
        assert_eq!(f16_bits(2f32.powi(-24)), 0x0001); // smallest subnormal
        assert_eq!(f16_bits(2f32.powi(-14)), 0x0400); // smallest normal
        assert_eq!(f16_bits(1.0 + 2f32.powi(-11)), 0x3c00); // tie to even (down)
        assert_eq!(f16_bits(1.0 + 3.0 * 2f32.powi(-11)), 0x3c02); // tie to even (up)
        assert_eq!(f16_bits(2f32.powi(-26)), 0);
    }
}
