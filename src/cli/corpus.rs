//! `patina corpus`: every shader file of a directory checked, compiled for its kind and rendered
//! small on both backends (`patina_runtime::corpus`), written as a Markdown table and a contact
//! sheet of the pictures (GPU left, CPU right, the file's name below).

use std::path::Path;
use std::process::ExitCode;

use patina_runtime::corpus::{self, Entry, Options, Totals};
use patina_runtime::image::Image;
use plotters::prelude::*;
use plotters::style::{FontStyle, register_font};

use super::CorpusArgs;
use super::render::open_gpu;

/// The font of the sheet's labels (the plots' embedded DejaVu Sans Mono).
static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSansMono.ttf");

/// How many tiles per row of the contact sheet.
const COLUMNS: u32 = 4;

/// Each picture's scale on the sheet.
const SCALE: u32 = 2;

/// The height of a tile's label.
const LABEL: u32 = 18;

pub fn run(args: CorpusArgs) -> Result<ExitCode, String> {
    // A missing directory is reported before a GPU is opened for nothing.
    corpus::files(&args.dir).map_err(|e| format!("{}: {e}", args.dir.display()))?;
    let gpu = if args.cpu_only { None } else { open_gpu() };
    let options = Options { include_dirs: args.include.clone(), size: (args.width, args.height) };
    let entries = corpus::run(&args.dir, &options, gpu.as_ref(), |e| {
        eprintln!(
            "{:<36} check {:<12} gpu {:<10} cpu {:<10} {}",
            e.file.display(),
            short(&e.check),
            short(&e.gpu),
            short(&e.cpu),
            match e.agrees {
                Some(true) => "agrees",
                Some(false) => "DIFFERS",
                None => "",
            }
        );
    })
    .map_err(|e| format!("{}: {e}", args.dir.display()))?;
    let table = corpus::markdown(&entries);
    match &args.markdown {
        Some(path) => std::fs::write(path, page(&args.dir, &table))
            .map_err(|e| format!("{}: cannot write: {e}", path.display()))?,
        None => print!("{table}"),
    }
    if let Some(path) = &args.sheet {
        contact_sheet(&entries, options.size, path)?;
    }
    let t = Totals::of(&entries);
    eprintln!(
        "{} files: {} check, {} render on the GPU, {} on the CPU, {} agree",
        t.files, t.checked, t.gpu, t.cpu, t.agree
    );
    Ok(ExitCode::SUCCESS)
}

/// An outcome in a word, for the progress lines.
fn short(o: &corpus::Outcome) -> String {
    match o {
        corpus::Outcome::Ok | corpus::Outcome::Warnings(_) => "ok".into(),
        corpus::Outcome::Failed(e) => e.split(':').next().unwrap_or("failed").to_string(),
        corpus::Outcome::Skipped(_) => "-".into(),
    }
}

/// The Markdown page around the table.
fn page(dir: &Path, table: &str) -> String {
    format!(
        "# Third-party shaders\n\n\
         Every shader file of `{}` checked, compiled for its kind and rendered at a small size on both \
         backends in a scene made for its kind (`runtime/src/corpus.rs` says which), the GPU's picture \
         compared with the CPU reference's by the gallery's thresholds. Regenerate with\n\n\
         ```sh\ncargo run --release -- corpus ../shared/corpus/aqsis -I ../shared/corpus/aqsis/include \\\n    \
         --markdown docs/corpus.md --sheet docs/corpus.png\n```\n\n\
         ![the pictures: GPU left, CPU right](corpus.png)\n\n{table}",
        dir.display()
    )
}

/// Writes the pictures as one PNG: a tile per shader file (GPU left, CPU right, grey where a
/// backend gave no picture), its name below.
fn contact_sheet(entries: &[Entry], size: (u32, u32), path: &Path) -> Result<(), String> {
    register_font("sans-serif", FontStyle::Normal, FONT)
        .map_err(|_| "the embedded font is invalid".to_string())?;
    let (w, h) = (size.0 * SCALE, size.1 * SCALE);
    let tile = (2 * w + 8, h + LABEL + 8);
    let rows = (entries.len() as u32).div_ceil(COLUMNS).max(1);
    let sheet = (COLUMNS * tile.0, rows * tile.1);
    let mut rgb = vec![24u8; (sheet.0 * sheet.1 * 3) as usize];
    let byte = |c: f32| (c.clamp(0.0, 1.0) * 255.0).round() as u8;
    for (i, entry) in entries.iter().enumerate() {
        let (x0, y0) = ((i as u32 % COLUMNS) * tile.0 + 4, (i as u32 / COLUMNS) * tile.1 + 4);
        for (k, image) in [&entry.gpu_image, &entry.cpu_image].into_iter().enumerate() {
            for y in 0..h {
                for x in 0..w {
                    let colour = match image {
                        Some(Image { width, pixels, .. }) => {
                            let [r, g, b, _] = pixels[((y / SCALE) * width + x / SCALE) as usize];
                            [byte(r), byte(g), byte(b)]
                        }
                        None => [64, 64, 64],
                    };
                    let at = (((y0 + y) * sheet.0 + x0 + k as u32 * w + x) * 3) as usize;
                    rgb[at..at + 3].copy_from_slice(&colour);
                }
            }
        }
    }
    {
        let root = BitMapBackend::with_buffer(&mut rgb, sheet).into_drawing_area();
        let style = ("sans-serif", 12).into_font().color(&WHITE);
        for (i, entry) in entries.iter().enumerate() {
            let (x0, y0) = ((i as u32 % COLUMNS) * tile.0 + 4, (i as u32 / COLUMNS) * tile.1 + 4);
            let mark = match entry.agrees {
                Some(true) => "",
                Some(false) => " (differs)",
                None if !entry.check.worked() => " (does not check)",
                None if entry.shader.is_none() => " (functions only)",
                None => " (not rendered)",
            };
            let label = format!("{}{mark}", entry.file.display());
            root.draw(&Text::new(label, (x0 as i32, (y0 + h + 3) as i32), style.clone()))
                .map_err(|e| format!("{}: {e}", path.display()))?;
        }
        root.present().map_err(|e| format!("{}: {e}", path.display()))?;
    }
    let image = Image {
        width: sheet.0,
        height: sheet.1,
        pixels: rgb
            .chunks_exact(3)
            .map(|p| [p[0], p[1], p[2]].map(|c| f32::from(c) / 255.0))
            .map(|[r, g, b]| [r, g, b, 1.0])
            .collect(),
    };
    image.write_png(path).map_err(|e| format!("{}: {e}", path.display()))
}
