//! Third-party shaders checked, compiled and rendered as a new user would try them: every `.sl`
//! file under a directory (Aqsis's standard set in `../shared/corpus/aqsis/`) is checked, and each
//! shader that checks is rendered small on both backends in a scene made for its kind, the GPU's
//! picture compared with the CPU reference's by the gallery's thresholds. `patina corpus` writes
//! the results as a table and a contact sheet; `runtime/tests/renderer/corpus.rs` asserts them.
//!
//! The scenes: a surface on a unit sphere under a point and an ambient light; a light on a
//! plastic sphere above a plastic floor (with a dim ambient light beside it, and a shadow map
//! made from the light when it has a `shadowname` parameter: orthographic for a distant light); a displacement on a plastic sphere
//! under the point and ambient lights; a volume shader as the scene's atmosphere and an imager
//! as its imager, over a plastic sphere under the point and ambient lights. Points and
//! directions a light declares (`from`, `to`) are set above and to the left of the camera, aimed
//! at the sphere, so that lights whose defaults sit at the origin (inside the sphere) still light
//! what is seen.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use patina_compiler::diag::Severity;
use patina_compiler::syntax::ast::ShaderKind;

use crate::gpu::Gpu;
use crate::image::{Comparison, Image, compare};
use crate::render::{self, Backend};
use crate::scene::{Scene, toml_string};

/// What a corpus run needs besides the directory.
#[derive(Clone, Debug)]
pub struct Options {
    /// Directories searched by `#include` after each file's own.
    pub include_dirs: Vec<PathBuf>,
    /// The test picture's width and height in pixels.
    pub size: (u32, u32),
}

impl Default for Options {
    fn default() -> Options {
        Options { include_dirs: Vec::new(), size: (64, 48) }
    }
}

/// The outcome of one step for one shader file.
#[derive(Clone, Debug, PartialEq)]
pub enum Outcome {
    /// It worked.
    Ok,
    /// It worked, with this many warnings.
    Warnings(usize),
    /// It did not: the first error, as `E0000: message`.
    Failed(String),
    /// Not tried, and why (a file of functions only; an earlier step failed).
    Skipped(String),
}

impl Outcome {
    /// Whether the step worked (with or without warnings).
    pub fn worked(&self) -> bool {
        matches!(self, Outcome::Ok | Outcome::Warnings(_))
    }

    /// A table cell: `ok`, `ok (2 warnings)`, `**E0503**: ...` or `–` with the reason.
    pub fn cell(&self) -> String {
        match self {
            Outcome::Ok => "ok".to_string(),
            Outcome::Warnings(n) => format!("ok ({n} warning{})", if *n == 1 { "" } else { "s" }),
            Outcome::Failed(e) => format!("**{}**", e.replace('|', "\\|")),
            Outcome::Skipped(why) => format!("– ({why})"),
        }
    }
}

/// One file's results.
#[derive(Clone, Debug)]
pub struct Entry {
    /// The file, relative to the corpus directory.
    pub file: PathBuf,
    /// The first shader's name and kind; `None` for a file with no shader (functions only).
    pub shader: Option<(String, ShaderKind)>,
    /// `patina check`.
    pub check: Outcome,
    /// The render on the CPU reference.
    pub cpu: Outcome,
    /// The render on the GPU.
    pub gpu: Outcome,
    /// GPU against CPU, when both rendered.
    pub comparison: Option<Comparison>,
    /// Whether the comparison passes the scene's thresholds.
    pub agrees: Option<bool>,
    /// The pictures, when rendered.
    pub cpu_image: Option<Image>,
    /// The GPU's picture.
    pub gpu_image: Option<Image>,
    /// Wall time of both renders, compilation included.
    pub time: Duration,
}

/// Every `.sl` file under `dir` (recursively, in path order).
pub fn files(dir: &Path) -> std::io::Result<Vec<PathBuf>> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d)? {
            let path = entry?.path();
            if path.is_dir() {
                stack.push(path);
            } else if path.extension().is_some_and(|e| e == "sl") {
                out.push(path);
            }
        }
    }
    out.sort();
    Ok(out)
}

/// Checks and renders every shader file under `dir`; `gpu` is `None` to render on the CPU only.
/// `each` is told about every entry as it is finished (for progress).
pub fn run(
    dir: &Path,
    options: &Options,
    gpu: Option<&Gpu>,
    mut each: impl FnMut(&Entry),
) -> std::io::Result<Vec<Entry>> {
    let mut entries = Vec::new();
    for path in files(dir)? {
        let entry = run_file(dir, &path, options, gpu);
        each(&entry);
        entries.push(entry);
    }
    Ok(entries)
}

/// One file of [`run`].
pub fn run_file(dir: &Path, path: &Path, options: &Options, gpu: Option<&Gpu>) -> Entry {
    let file = path.strip_prefix(dir).unwrap_or(path).to_path_buf();
    let mut entry = Entry {
        file,
        shader: None,
        check: Outcome::Skipped(String::new()),
        cpu: Outcome::Skipped("did not check".into()),
        gpu: Outcome::Skipped("did not check".into()),
        comparison: None,
        agrees: None,
        cpu_image: None,
        gpu_image: None,
        time: Duration::ZERO,
    };
    let checked = match patina_compiler::check_file(path, &options.include_dirs) {
        Ok(checked) => checked,
        Err(e) => {
            entry.check = Outcome::Failed(e.reason);
            return entry;
        }
    };
    let first_error = checked.diagnostics.iter().find(|d| d.severity == Severity::Error);
    if let Some(e) = first_error {
        entry.check = Outcome::Failed(format!("{}: {}", e.code, e.message));
        return entry;
    }
    let warnings = checked.diagnostics.iter().filter(|d| d.severity == Severity::Warning).count();
    entry.check = if warnings == 0 { Outcome::Ok } else { Outcome::Warnings(warnings) };
    let Some(shader) = checked.program.shaders.first() else {
        let why = "functions only".to_string();
        (entry.cpu, entry.gpu) = (Outcome::Skipped(why.clone()), Outcome::Skipped(why));
        return entry;
    };
    let params: Vec<&str> = shader.params.iter().map(|p| shader.local(*p).name.as_str()).collect();
    entry.shader = Some((shader.name.to_string(), shader.kind));
    let scene = match scene_for(path, shader.kind, &shader.name, &params, options) {
        Ok(scene) => scene,
        Err(why) => {
            (entry.cpu, entry.gpu) = (Outcome::Skipped(why.clone()), Outcome::Skipped(why));
            return entry;
        }
    };
    let start = Instant::now();
    render_both(&scene, gpu, &mut entry);
    entry.time = start.elapsed();
    entry
}

/// Renders `scene` on both backends into `entry`, and compares the pictures.
fn render_both(scene: &Scene, gpu: Option<&Gpu>, entry: &mut Entry) {
    let prepared = match render::prepare(scene) {
        Ok(p) => p,
        Err(e) => {
            let e = first_line(&e.to_string());
            (entry.cpu, entry.gpu) = (Outcome::Failed(e.clone()), Outcome::Failed(e));
            return;
        }
    };
    let picture = |backend: Backend, gpu: Option<&Gpu>| match render::render(&prepared, backend, gpu) {
        Ok(image) if image.pixels.iter().flatten().all(|c| c.is_finite()) => (Outcome::Ok, Some(image)),
        Ok(image) => {
            let bad = image.pixels.iter().filter(|p| p.iter().any(|c| !c.is_finite())).count();
            (Outcome::Failed(format!("{bad} non-finite pixels")), Some(image))
        }
        Err(e) => (Outcome::Failed(first_line(&e.to_string())), None),
    };
    (entry.cpu, entry.cpu_image) = picture(Backend::Cpu, None);
    (entry.gpu, entry.gpu_image) = match gpu {
        Some(gpu) => picture(Backend::Gpu, Some(gpu)),
        None => (Outcome::Skipped("no GPU".into()), None),
    };
    if let (Some(cpu), Some(gpu)) = (&entry.cpu_image, &entry.gpu_image) {
        let thresholds = scene.thresholds();
        if let Ok(c) = compare(gpu, cpu, &thresholds) {
            entry.agrees = Some(c.passes(&thresholds) && c.nan_pixels == 0);
            entry.comparison = Some(c);
        }
    }
}

/// The first line of an error that may be a rendered diagnostic, without its `error[...]` frame.
fn first_line(text: &str) -> String {
    text.lines().find(|l| !l.trim().is_empty()).unwrap_or("").trim().to_string()
}

/// The scene a shader of `kind` is rendered in (see the module documentation); `Err` with the
/// scene error's first line.
pub fn scene_for(
    path: &Path,
    kind: ShaderKind,
    name: &str,
    params: &[&str],
    options: &Options,
) -> Result<Scene, String> {
    let file = toml_string(&path.display().to_string());
    let name = toml_string(name);
    let (width, height) = options.size;
    let include: Vec<String> =
        options.include_dirs.iter().map(|d| toml_string(&d.display().to_string())).collect();
    let mut text = format!(
        "include = [{}]\n\n[output]\nwidth = {width}\nheight = {height}\nbackground = [0.05, 0.05, 0.08, 1.0]\n\n\
         [camera]\nfrom = [0.0, 0.0, -4.0]\nto = [0.0, 0.0, 0.0]\nfov = 40\n\n",
        include.join(", ")
    );
    let point_light = "[[light]]\nshader = \"<shaders.sl>\"\nname = \"pointlight\"\n\
                       params = { intensity = 12.0, from = [-2.5, 3.0, -3.0] }\n\n";
    let ambient =
        "[[light]]\nshader = \"<shaders.sl>\"\nname = \"ambientlight\"\nparams = { intensity = 0.08 }\n\n";
    let sphere = |shader: &str, name: &str| {
        format!(
            "[[object]]\nmesh = \"sphere\"\ndetail = 32\nshader = {shader}\nname = {name}\ncolor = [0.9, 0.35, 0.2]\n"
        )
    };
    let plastic = sphere("\"<shaders.sl>\"", "\"plastic\"");
    match kind {
        ShaderKind::Surface => {
            text += point_light;
            text += ambient;
            text += &sphere(&file, &name);
        }
        ShaderKind::Light => {
            let mut set = Vec::new();
            if params.contains(&"from") {
                set.push("from = [-2.5, 3.0, -3.0]");
            }
            if params.contains(&"to") {
                set.push("to = [0.0, 0.0, 0.0]");
            }
            // A local light falls off as 1/d² in the standard lights; a distant one does not
            // (told by its name, as RenderMan's standard set names them).
            if params.contains(&"from") && params.contains(&"intensity") && !name.contains("distant") {
                set.push("intensity = 12.0");
            }
            // A light that names a shadow map gets one, made from the light (the floor shows it).
            let shadowed = params.contains(&"shadowname");
            if shadowed {
                set.push("shadowname = \"corpus.shad\"");
            }
            text +=
                &format!("[[light]]\nshader = {file}\nname = {name}\nparams = {{ {} }}\n\n", set.join(", "));
            if shadowed {
                let projection = if name.contains("distant") { "orthographic" } else { "perspective" };
                text += &format!(
                    "[[shadow]]\nname = \"corpus.shad\"\nlight = 0\nresolution = 256\nbias = 0.05\n\
                     projection = \"{projection}\"\n\n"
                );
            }
            if name != "\"ambientlight\"" {
                text += ambient;
            }
            text += &plastic;
            text += "\n[[object]]\nmesh = \"plane\"\ndetail = 4\nshader = \"<shaders.sl>\"\nname = \"plastic\"\n\
                     color = [0.8, 0.8, 0.75]\ntransform = [{ translate = [0.0, -1.0, 0.0] }, \
                     { rotate = { angle = 90, axis = [1.0, 0.0, 0.0] } }, { scale = [3.0, 3.0, 1.0] }]\n";
        }
        ShaderKind::Displacement => {
            text += point_light;
            text += ambient;
            text += &plastic;
            text += &format!("displacement = {{ shader = {file}, name = {name} }}\n");
        }
        ShaderKind::Volume | ShaderKind::Imager => {
            let table = if kind == ShaderKind::Volume { "atmosphere" } else { "imager" };
            // Fog's default 1-unit falloff would hide a sphere 3 units away entirely.
            let set = if params.contains(&"distance") { "distance = 8.0" } else { "" };
            text += &format!("[{table}]\nshader = {file}\nname = {name}\nparams = {{ {set} }}\n\n");
            text += point_light;
            text += ambient;
            text += &plastic;
        }
    }
    Scene::parse(&text, "corpus_scene.toml", ".").map_err(|e| first_line(&e.to_string()))
}

/// The results as a Markdown table, with the totals below it.
pub fn markdown(entries: &[Entry]) -> String {
    let mut out = String::from(
        "| shader | kind | check | GPU | CPU | agreement | time |\n|---|---|---|---|---|---|---|\n",
    );
    for e in entries {
        let kind = match (&e.shader, e.check.worked()) {
            (Some((_, k)), _) => k.keyword(),
            (None, true) => "functions",
            (None, false) => "?",
        };
        let agreement = match (&e.comparison, e.agrees) {
            (Some(c), Some(agrees)) => format!(
                "{} (max {:.3}, {} of {} px over)",
                if agrees { "agrees" } else { "**differs**" },
                c.max_error,
                c.failing_pixels,
                c.pixels
            ),
            _ => "–".to_string(),
        };
        let time = if e.time.is_zero() {
            "–".to_string()
        } else {
            format!("{:.0} ms", e.time.as_secs_f64() * 1e3)
        };
        out += &format!(
            "| `{}` | {kind} | {} | {} | {} | {agreement} | {time} |\n",
            e.file.display(),
            e.check.cell(),
            e.gpu.cell(),
            e.cpu.cell()
        );
    }
    let totals = Totals::of(entries);
    out += &format!(
        "\n**Totals**: {} files; {} check; {} render on the GPU, {} on the CPU; {} agree.\n",
        totals.files, totals.checked, totals.gpu, totals.cpu, totals.agree
    );
    out
}

/// Counts over a corpus run.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Totals {
    /// Files.
    pub files: usize,
    /// Files that check.
    pub checked: usize,
    /// Shaders rendered on the GPU with finite pixels.
    pub gpu: usize,
    /// Shaders rendered on the CPU with finite pixels.
    pub cpu: usize,
    /// Shaders whose pictures agree.
    pub agree: usize,
}

impl Totals {
    /// The counts of `entries`.
    pub fn of(entries: &[Entry]) -> Totals {
        Totals {
            files: entries.len(),
            checked: entries.iter().filter(|e| e.check.worked()).count(),
            gpu: entries.iter().filter(|e| e.gpu.worked()).count(),
            cpu: entries.iter().filter(|e| e.cpu.worked()).count(),
            agree: entries.iter().filter(|e| e.agrees == Some(true)).count(),
        }
    }
}
