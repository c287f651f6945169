//! The imager pass: an imager shader run over the finished image, once per pixel, on the CPU by
//! the interpreter and on the GPU as a compute kernel over the same columns (so both backends run
//! the same program on the same inputs). An imager sees `P` (the pixel centre in raster space,
//! z = 0), `s` and `t` (the centre across the image, 0 to 1), `Ci` (the premultiplied colour),
//! `alpha` (the coverage: the scene is drawn over transparent black when it has an imager) and
//! `Oi` (alpha in each channel); its `Ci` and `alpha` are the pixel's, then put over the scene's
//! background.

use std::path::Path;

use patina_compiler::backend::binding::Binding;
use patina_compiler::backend::cpu::{CpuProgram, Evaluator, Texture};
use patina_compiler::syntax::ast::ShaderKind;

use super::RenderError;
use super::program::{LoadedShader, evaluate_params, set_spaces};
use crate::gpu::Gpu;
use crate::image::Image;

/// An imager shader compiled for both backends, with its parameter values.
#[derive(Clone)]
pub struct ImagerProgram {
    /// The imager shader (bound to the scene's values and differentiated).
    pub loaded: LoadedShader,
    /// The interpreter's program for it.
    pub cpu: CpuProgram,
    /// Its parameter values after defaults, by name.
    pub values: Vec<(String, Vec<f64>)>,
    /// The scene's background (premultiplied), put under the imager's result.
    pub background: [f32; 4],
    /// The named spaces at the output size (what `transform` and `option("Format")` read).
    pub spaces: Vec<(String, glam::Mat4)>,
    /// The textures it looks up, by name.
    pub textures: Vec<(String, Texture)>,
}

/// Compiles an imager shader, computes its parameter values and loads the textures it reads
/// (files relative to `base`, the scene's folder).
pub fn imager_program(
    loaded: LoadedShader,
    background: [f32; 4],
    spaces: Vec<(String, glam::Mat4)>,
    base: &Path,
) -> Result<ImagerProgram, RenderError> {
    if loaded.shader.kind != ShaderKind::Imager {
        return Err(RenderError::Input(format!("`{}` is not an imager shader", loaded.shader.name)));
    }
    let binding = Binding { lights: Vec::new(), strings: loaded.strings.clone() };
    let cpu = CpuProgram::compile(&loaded.shader, &binding).map_err(|d| loaded.error(d))?;
    let values = evaluate_params(&cpu, &loaded.params, &spaces, None, &[])?;
    let textures = cpu
        .textures()
        .iter()
        .map(|name| Ok((name.to_string(), super::textures::load(name, base)?)))
        .collect::<Result<_, RenderError>>()?;
    Ok(ImagerProgram { loaded, cpu, values, background, spaces, textures })
}

/// The per-pixel inputs the imager reads, by name, point-major.
fn columns(imager: &ImagerProgram, image: &Image) -> Vec<(String, Vec<f64>)> {
    let (w, h) = (image.width as usize, image.height as usize);
    let n = w * h;
    let mut all: Vec<(String, Vec<f64>)> = vec![
        ("P".into(), Vec::with_capacity(n * 3)),
        ("s".into(), Vec::with_capacity(n)),
        ("t".into(), Vec::with_capacity(n)),
        ("Ci".into(), Vec::with_capacity(n * 3)),
        ("Oi".into(), Vec::with_capacity(n * 3)),
        ("alpha".into(), Vec::with_capacity(n)),
    ];
    for (i, px) in image.pixels.iter().enumerate() {
        let (x, y) = ((i % w) as f64 + 0.5, (i / w) as f64 + 0.5);
        let a = f64::from(px[3]);
        all[0].1.extend([x, y, 0.0]);
        all[1].1.push(x / w as f64);
        all[2].1.push(y / h as f64);
        all[3].1.extend(px[..3].iter().map(|c| f64::from(*c)));
        all[4].1.extend([a, a, a]);
        all[5].1.push(a);
    }
    all.retain(|(name, _)| imager.cpu.slot(name).is_some());
    all
}

/// The outputs the imager can write, among `Ci` and `alpha`.
fn outputs(imager: &ImagerProgram) -> Vec<&'static str> {
    ["Ci", "alpha"].into_iter().filter(|name| imager.cpu.slot(name).is_some()).collect()
}

/// The image from the imager's outputs (a pixel keeps what the imager does not write), over the
/// background.
fn finish(imager: &ImagerProgram, image: &Image, names: &[&str], results: &[Vec<f64>]) -> Image {
    let result = |name: &str| names.iter().position(|n| *n == name).map(|k| &results[k]);
    let (ci, alpha) = (result("Ci"), result("alpha"));
    let bg = imager.background;
    let pixels = image
        .pixels
        .iter()
        .enumerate()
        .map(|(i, px)| {
            let mut out = *px;
            if let Some(ci) = ci {
                for c in 0..3 {
                    out[c] = ci[i * 3 + c] as f32;
                }
            }
            if let Some(alpha) = alpha {
                out[3] = alpha[i] as f32;
            }
            let under = 1.0 - out[3];
            [out[0] + under * bg[0], out[1] + under * bg[1], out[2] + under * bg[2], out[3] + under * bg[3]]
        })
        .collect();
    Image { width: image.width, height: image.height, pixels }
}

/// Runs the imager over `image` with the interpreter.
pub fn cpu(imager: &ImagerProgram, image: &Image) -> Result<Image, RenderError> {
    let columns = columns(imager, image);
    let mut e = Evaluator::<f32>::new(&imager.cpu);
    set_spaces(&mut e, &imager.cpu, &imager.spaces);
    for (name, value) in &imager.values {
        let _ = e.set(name, value);
    }
    for (name, texture) in &imager.textures {
        // The names are the program's own (`CpuProgram::textures`), so this cannot fail.
        let _ = e.set_texture(name, texture.clone());
    }
    let inputs: Vec<(&str, &[f64])> = columns.iter().map(|(n, c)| (n.as_str(), c.as_slice())).collect();
    let names = outputs(imager);
    let count = image.pixels.len();
    let results = e.eval_points(count, &inputs, &names).map_err(|e| RenderError::Run(e.to_string()))?;
    Ok(finish(imager, image, &names, &results))
}

/// Runs the imager over `image` on the GPU, as a compute kernel over the same inputs (the
/// parameters as columns of their values).
pub fn gpu(gpu: &Gpu, imager: &ImagerProgram, image: &Image) -> Result<Image, RenderError> {
    let count = image.pixels.len();
    let mut columns = columns(imager, image);
    for (name, value) in &imager.values {
        if imager.cpu.slot(name).is_some() {
            columns.push((name.clone(), (0..count).flat_map(|_| value.iter().copied()).collect()));
        }
    }
    let inputs: Vec<(&str, &[f64])> = columns.iter().map(|(n, c)| (n.as_str(), c.as_slice())).collect();
    let names = outputs(imager);
    let resources = crate::kernel::Resources {
        lights: &[],
        strings: &imager.loaded.strings,
        spaces: &imager.spaces,
        textures: &imager.textures,
        // An imager runs once per pixel of the finished image: its exact lowering costs little.
        lowering: patina_compiler::backend::wgsl::Lowering::Exact,
    };
    let results = crate::kernel::run_prepared(gpu, &imager.loaded.shader, &resources, count, &inputs, &names)
        .map_err(|e| RenderError::Gpu(format!("imager `{}`: {e}", imager.loaded.shader.name)))?;
    Ok(finish(imager, image, &names, &results))
}
