//! Command-line arguments and the subcommands behind them.

mod bench;
mod check;
mod compile;
mod corpus;
mod eval;
mod explain;
mod explain_scene;
mod gallery;
mod live;
mod lsp;
mod plot;
mod progress;
mod render;
mod stability;
mod view;
mod watch;

use std::path::PathBuf;
use std::process::ExitCode;

use clap::{Parser, Subcommand, ValueEnum};

/// Patina: compile procedural shaders to WGSL and run them on the CPU reference.
#[derive(Parser, Debug)]
#[command(name = "patina", version, about)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Check shader sources and print their diagnostics.
    Check(CheckArgs),
    /// Print each shader's parameters and variables with their types, rates and stages; for a
    /// scene (.toml), what binding kept and left out of each object's shader, and why.
    Explain(ExplainArgs),
    /// Run a shader on the CPU interpreter at given points and print its outputs.
    Eval(EvalArgs),
    /// Compile a surface shader (with its lights) to WGSL and a JSON description of its interface.
    Compile(CompileArgs),
    /// Render a scene to a PNG, on the GPU (the CPU reference when there is none, or when asked).
    Render(RenderArgs),
    /// Render scenes on the GPU and the CPU reference, compare them, and write their pictures and
    /// a Markdown page with their timings.
    Gallery(GalleryArgs),
    /// Error against run time: render a scene at each setting of its quality knobs on the GPU and
    /// the CPU, time them and measure them against the reference; write CSV, Markdown and a plot.
    Bench(BenchArgs),
    /// The extreme-input sweep of the standard library's functions (--stdlib) or of a file's
    /// functions and surface shaders: non-finite results per backend and the backends' errors;
    /// exit 1 when a finite input gave a non-finite output.
    Stability(StabilityArgs),
    /// Render a scene, then render it again whenever the scene or a shader it uses (or a file
    /// included) changes, printing each outcome; an error keeps the last good image.
    Watch(watch::WatchArgs),
    /// A window showing a scene: drag to orbit, scroll to zoom; it renders again when the scene
    /// or a shader it uses (or a file included) changes, keeping the last good picture on an
    /// error; D toggles the difference between the GPU and the CPU reference.
    View(view::ViewArgs),
    /// Check, compile and render every shader file of a directory (third-party shaders) on both
    /// backends, in a scene made for each shader's kind; write a results table and a contact sheet.
    Corpus(CorpusArgs),
    /// A Language Server Protocol server over stdin and stdout, for editors: diagnostics as you
    /// type, hover with types and rates, go to definition, completion, inlay hints, semantic tokens.
    Lsp(LspArgs),
}

/// Arguments of `patina lsp`.
#[derive(clap::Args, Debug)]
pub struct LspArgs {
    /// Add an `#include` search directory (after each file's own; repeat for more). Clients may
    /// add more with the initialization option `includeDirs`.
    #[arg(short = 'I', value_name = "DIR")]
    include: Vec<PathBuf>,
}

/// Arguments of `patina corpus`.
#[derive(clap::Args, Debug)]
pub struct CorpusArgs {
    /// The directory of shader files (searched recursively for `.sl`).
    dir: PathBuf,
    /// Add an `#include` search directory (after each file's own; repeat for more).
    #[arg(short = 'I', value_name = "DIR")]
    include: Vec<PathBuf>,
    /// Write the results as a Markdown page (printed as a table otherwise).
    #[arg(long, value_name = "FILE")]
    markdown: Option<PathBuf>,
    /// Write the pictures as one PNG: GPU left, CPU right, per shader file.
    #[arg(long, value_name = "FILE")]
    sheet: Option<PathBuf>,
    /// Render on the CPU reference only.
    #[arg(long)]
    cpu_only: bool,
    /// The test picture's width in pixels.
    #[arg(long, default_value_t = 64, value_parser = clap::value_parser!(u32).range(1..=4096))]
    width: u32,
    /// The test picture's height in pixels.
    #[arg(long, default_value_t = 48, value_parser = clap::value_parser!(u32).range(1..=4096))]
    height: u32,
}

/// Arguments of `patina stability`.
#[derive(clap::Args, Debug)]
pub struct StabilityArgs {
    /// The shader files whose functions and surface shaders to sweep.
    #[arg(value_name = "FILE", required_unless_present = "stdlib", conflicts_with = "stdlib")]
    files: Vec<PathBuf>,
    /// Sweep every function of every standard-library module.
    #[arg(long)]
    stdlib: bool,
    /// Only this standard-library module (`volume` or `volume.sl`; repeat for more).
    #[arg(long, value_name = "NAME", requires = "stdlib")]
    module: Vec<String>,
    /// Only the functions or shaders of this name (repeat for more).
    #[arg(long, value_name = "NAME")]
    function: Vec<String>,
    /// Random combinations of extremes per function, after the systematic points.
    #[arg(long, value_name = "N", default_value_t = 64)]
    random: usize,
    /// Where to run besides the interpreter: `cpu` skips the GPU.
    #[arg(long, value_enum, default_value_t = BackendChoice::Gpu)]
    backend: BackendChoice,
    /// Also write the table as Markdown.
    #[arg(long, value_name = "FILE")]
    markdown: Option<PathBuf>,
    /// Also write the table as CSV.
    #[arg(long, value_name = "FILE")]
    csv: Option<PathBuf>,
    /// A directory to search for `#include` files.
    #[arg(short = 'I', value_name = "DIR")]
    include: Vec<PathBuf>,
}

/// Which renderers `patina bench` times.
#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub enum Renderers {
    /// The GPU (when there is one) and the CPU reference.
    Both,
    /// The GPU only.
    Gpu,
    /// The CPU reference only.
    Cpu,
}

/// Arguments of `patina bench`.
#[derive(clap::Args, Debug)]
pub struct BenchArgs {
    /// The scene file (TOML), with its `[[knob]]` tables.
    scene: PathBuf,
    /// A knob to sweep: `NAME` (its listed settings) or `NAME=V,V,..` (those settings: labels, or
    /// any numbers for a one-parameter knob). Repeat for more; default: every knob of the scene.
    #[arg(long, value_name = "NAME[=V,..]")]
    knob: Vec<String>,
    /// Timed runs per setting and renderer, after one untimed warm-up; the median is reported.
    #[arg(long, default_value_t = 5, value_parser = clap::value_parser!(u32).range(1..=1000))]
    runs: u32,
    /// The renderers to time.
    #[arg(long, value_enum, default_value_t = Renderers::Both)]
    backend: Renderers,
    /// Render at WIDTHxHEIGHT instead of the scene's size (the reference too).
    #[arg(long, value_name = "WxH")]
    size: Option<String>,
    /// Where to write SCENE_KNOB.csv, .md, .svg and .png.
    #[arg(short, long, value_name = "DIR", default_value = "bench")]
    output: PathBuf,
}

/// Arguments of `patina gallery`.
#[derive(clap::Args, Debug)]
pub struct GalleryArgs {
    /// The scene files (TOML).
    #[arg(required = true)]
    scenes: Vec<PathBuf>,
    /// Where to write each scene's picture, as NAME.png (the GPU's when there is a GPU).
    #[arg(long, value_name = "DIR", default_value = "gallery")]
    images: PathBuf,
    /// A Markdown page to write, showing every picture with its command and timings.
    #[arg(long, value_name = "FILE")]
    markdown: Option<PathBuf>,
    /// How the GPU module writes the built-ins: `exact` (the CPU reference's bits, what the
    /// comparison is for) or `fast` (WGSL's own).
    #[arg(long, value_enum, default_value_t = LoweringChoice::Exact)]
    lowering: LoweringChoice,
}

/// Arguments of `patina compile`.
#[derive(clap::Args, Debug)]
pub struct CompileArgs {
    /// The shader file.
    file: PathBuf,
    /// The shader of FILE to compile (its first surface shader by default, or, in a file without
    /// one, its first shader).
    #[arg(long)]
    shader: Option<String>,
    /// For a light, displacement or volume shader compiled on its own: the surface to bind it to,
    /// `PATH` (its first surface shader) or `PATH:NAME` (default: the standard library's `plastic`).
    #[arg(long, value_name = "FILE[:NAME]")]
    surface: Option<String>,
    /// A light to bind: `NAME` (a light shader of FILE), `PATH` or `PATH:NAME` (repeat for more).
    #[arg(long, value_name = "LIGHT")]
    light: Vec<String>,
    /// A parameter value to compile in (`NAME=V`, `NAME=V,V,V` or `NAME="TEXT"`; repeat for more):
    /// the branches it decides and the code only they need are left out (the others stay
    /// uniforms). Points, vectors and normals depend on the view and cannot be fixed.
    #[arg(long, value_name = "NAME=V")]
    fix: Vec<String>,
    /// Fold the host part into the WGSL, so that the uniform block holds only values a program
    /// without Patina can fill (parameters, predefined variables, spaces, geometry).
    #[arg(long)]
    fold_host: bool,
    /// How the WGSL writes the built-ins: `fast` (WGSL's own) or `exact` (the CPU reference's bits).
    #[arg(long, value_enum, default_value_t = LoweringChoice::Fast)]
    lowering: LoweringChoice,
    /// Where to write NAME.wgsl and NAME.json.
    #[arg(short, long, value_name = "DIR", default_value = ".")]
    output: PathBuf,
    /// A directory to search for `#include` files.
    #[arg(short = 'I', value_name = "DIR")]
    include: Vec<PathBuf>,
}

/// How the GPU module writes the built-ins (`--lowering`).
#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub enum LoweringChoice {
    /// The CPU reference's operations in its order: bit-exact against it where WGSL is exact.
    Exact,
    /// WGSL's own built-ins (dot, normalize, inverseSqrt, matrix products), as hand-written WGSL.
    Fast,
}

impl From<LoweringChoice> for patina_compiler::backend::wgsl::Lowering {
    fn from(choice: LoweringChoice) -> Self {
        match choice {
            LoweringChoice::Exact => Self::Exact,
            LoweringChoice::Fast => Self::Fast,
        }
    }
}

/// Which renderer `patina render` uses.
#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub enum BackendChoice {
    /// wgpu on any adapter (lavapipe without a GPU); the CPU when no adapter exists.
    Gpu,
    /// The CPU reference renderer.
    Cpu,
}

/// Arguments of `patina render`.
#[derive(clap::Args, Debug)]
pub struct RenderArgs {
    /// The scene file (TOML).
    scene: PathBuf,
    /// The PNG to write.
    #[arg(short, long, value_name = "PNG", default_value = "out.png")]
    output: PathBuf,
    /// The renderer.
    #[arg(long, value_enum, default_value_t = BackendChoice::Gpu)]
    backend: BackendChoice,
    /// Compile every parameter dynamic (as uniforms) instead of binding the scene's values.
    #[arg(long)]
    dynamic: bool,
    /// How the GPU module writes the built-ins: `fast` (WGSL's own) or `exact` (the CPU
    /// reference's bits).
    #[arg(long, value_enum, default_value_t = LoweringChoice::Fast)]
    lowering: LoweringChoice,
    /// A directory to search for the shaders' `#include` files (after each shader's own folder
    /// and the scene's `include` list; repeat for more).
    #[arg(short = 'I', value_name = "DIR")]
    include: Vec<PathBuf>,
}

/// Arguments of `patina eval`.
#[derive(clap::Args, Debug)]
pub struct EvalArgs {
    /// The shader file.
    file: PathBuf,
    /// The shader to run (the file's first by default).
    #[arg(long)]
    shader: Option<String>,
    /// One point: its per-point inputs, e.g. `--at "P=0.5,1,2 s=0.25"` (repeat for more points).
    #[arg(long, value_name = "NAME=V,..")]
    at: Vec<String>,
    /// Inputs for every point: parameters, uniform variables, seeds (`dx(P)=1,0,0`), spaces
    /// (`space:world=` sixteen values, row by row).
    #[arg(long, value_name = "NAME=V,..")]
    set: Vec<String>,
    /// A bound light with its `L` and `Cl` at the surface (repeat for more lights).
    #[arg(long, value_name = "L=..  Cl=..")]
    light: Vec<String>,
    /// A bound ambient light with its `Cl`.
    #[arg(long, value_name = "Cl=..")]
    ambient_light: Vec<String>,
    /// The value of a `string` parameter (texture and space names are fixed at compile time).
    #[arg(long, value_name = "NAME=TEXT")]
    string: Vec<String>,
    /// What to print (default: what the shader kind produces, and its output parameters).
    #[arg(long, value_name = "NAME")]
    output: Vec<String>,
    /// Evaluate in double precision (the ground-truth mode) instead of f32.
    #[arg(long)]
    f64: bool,
    /// The most iterations any loop may run (the interpreter's default; docs/limits.md).
    #[arg(long, value_name = "N", default_value_t = patina_compiler::backend::MAX_LOOP_ITERATIONS)]
    budget: u64,
    /// A directory to search for `#include` files.
    #[arg(short = 'I', value_name = "DIR")]
    include: Vec<PathBuf>,
}

/// Arguments of `patina explain`.
#[derive(clap::Args, Debug)]
pub struct ExplainArgs {
    /// The shader file, or a scene (.toml).
    file: PathBuf,
    /// A directory to search for `#include` files.
    #[arg(short = 'I', value_name = "DIR")]
    include: Vec<PathBuf>,
}

/// How diagnostics are printed.
#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub enum OutputFormat {
    /// The compiler layout with source snippets (colour on a terminal).
    Human,
    /// One JSON object per diagnostic per line.
    Json,
}

/// Arguments of `patina check`.
#[derive(clap::Args, Debug)]
pub struct CheckArgs {
    /// The shader files to check.
    #[arg(required = true)]
    files: Vec<PathBuf>,
    /// A directory to search for `#include` files (after the including file's own directory).
    #[arg(short = 'I', value_name = "DIR")]
    include: Vec<PathBuf>,
    /// How to print diagnostics.
    #[arg(long, value_enum, default_value_t = OutputFormat::Human)]
    format: OutputFormat,
    /// When to colour the output.
    #[arg(long, value_enum, default_value_t = ColorChoice::Auto)]
    color: ColorChoice,
}

/// When to colour diagnostics.
#[derive(Copy, Clone, Debug, PartialEq, Eq, ValueEnum)]
pub enum ColorChoice {
    /// On a terminal only.
    Auto,
    /// Always.
    Always,
    /// Never.
    Never,
}

/// Runs a parsed command line. `Err` is a failure to even start (reported as one line, exit 2).
pub fn run(cli: Cli) -> Result<ExitCode, String> {
    match cli.command {
        Command::Check(args) => check::run(args),
        Command::Explain(args) => explain::run(args),
        Command::Eval(args) => eval::run(args),
        Command::Compile(args) => compile::run(args),
        Command::Render(args) => render::run(args),
        Command::Gallery(args) => gallery::run(args),
        Command::Bench(args) => bench::run(args),
        Command::Stability(args) => stability::run(args),
        Command::Watch(args) => watch::run(args),
        Command::View(args) => view::run(args),
        Command::Corpus(args) => corpus::run(args),
        Command::Lsp(args) => lsp::run(args),
    }
}
