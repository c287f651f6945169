//! The conformance cases (`conformance/cases.rs`, which `conformance.rs` runs as compute
//! kernels) through the real vertex -> fragment path: each group of cases becomes surface
//! shaders rendered on a plane by `patina_runtime::render` on the GPU and by the CPU reference,
//! and the two rgba32float images are compared pixel by pixel with each case's tolerance.
//!
//! What the render path adds to the compute kernel: the split into host, vertex and fragment
//! stages (a call whose arguments are all uniform runs in the host stage, on the interpreter for
//! both renderers, and reaches the fragment stage through the uniform block; so do uniform
//! subexpressions of the other calls), the scene's parameter values in the uniform block, the
//! interpolated `s`, `t` (and `P` for the derivative cases), the fragment entry point with its
//! derivative seeds, bound light shaders, and the colour output with its blending.
//!
//! How a case runs:
//! - Its uniform arguments are surface parameters (`uniform float c3a1u`) whose values the scene
//!   sets, drawn from the case's domain as the compute harness draws them (`cases::sample_n`).
//! - Its varying arguments (`c3a1v`) are locals computed from the interpolated `s` and `t`. The
//!   plane exactly fills the image, so pixel (x, y) has s = (x + 0.5) / 32 and
//!   t = (y + 0.5) / 32, and `floor(s * 32)`, `floor(t * 32)` give back x and y however the two
//!   rasterizers round s and t (half a pixel is 2^-6; [`cells_come_from_the_interpolated_surface`]
//!   checks this and measures s and t on both). From the pixel's index, an integer hash (exact
//!   and wrapping on both) picks each component: a quarter of the time one of the domain's
//!   specials, otherwise a point of a fixed-point grid over the domain, `float(n) * 2^-p` with
//!   |n| < 2^24, which no rounding, fused multiply-add or reassociation can change. So both
//!   renderers compute each case on bit-identical arguments, and every family keeps the
//!   tolerance it has in the compute harness (`cases::tol`). Only the derivative cases, which read
//!   `s`, `t` and `P` and their screen derivatives themselves, get their own bound
//!   ([`DERIVATIVES`]).
//! - Its outputs are locals (`o3m5_0`: mix 5, output 0, as in the compute harness). A shader's
//!   outputs are flattened into scalars (an integer as its two 16-bit halves, exact as floats; a
//!   boolean as 0 or 1) and packed three to a colour; pixel (x, y) writes colour number
//!   `(32 y + x) mod colours` to `Ci`, so each output is seen at every colours-th pixel, with
//!   that pixel's varying arguments. `Oi` is not written, so alpha is 1 and the premultiplied
//!   blend over the black background passes `Ci` through on both (`c + 0 * 0`, which turns -0
//!   into +0 on both).
//! - Every mix of argument rates runs, as in the compute harness (`cases::mixes`).
//! - A group whose outputs need more than [`MAX_COLOURS`] colours is split into several shaders.
//! - [`BATCHES`] scenes per shader, each with new uniform values and a new hash seed for the
//!   varying ones (the shader text stays the same, so Mesa's shader cache compiles it once).
//!
//! Denormals: lavapipe's fragment shaders flush them (its compute shaders do not), so the
//! specials here leave out the denormals, the smallest normal float (half of it is denormal) and
//! the largest finite floats (their reciprocals are denormal); the grid's nonzero values are at
//! least 2^-23 from zero, so products of a few of them stay far from the denormals.
//!
//! The tests need a GPU adapter (lavapipe is enough) and panic without one, unless
//! `PATINA_GPU=off`. `PATINA_CONFORMANCE_REPORT=1` prints each output's largest difference and
//! the time each step took.

// The compute runner is not used here, only `Tol` and its comparison.
#[allow(dead_code)]
use crate::{cases, harness};
use std::fmt::Write as _;
use std::path::Path;
use std::time::Instant;

use crate::cases::{Case, Dom, declare, mixes};
use crate::harness::Tol;
use patina_compiler::backend::binding::LightBinding;
use patina_runtime::gpu::{self, Gpu};
use patina_runtime::image::Image;
use patina_runtime::render::{self, Backend, Options, Prepared};
use patina_runtime::scene::Scene;

/// The image is `SIDE × SIDE` pixels, one shading point each.
const SIDE: u32 = 32;
/// The most colours one shader packs its outputs into: at least 8 pixels (points) per colour
/// and scene.
const MAX_COLOURS: usize = (SIDE * SIDE / 8) as usize;
/// Scenes per shader, each with its own uniform values and varying seed.
const BATCHES: usize = 3;

/// The derivative built-ins on the real path: the GPU differentiates the interpolated seeds
/// (`s`, `t`, `u`, `v`, `P`) across the 2x2 pixel quad, the CPU reference takes the rasterizer's
/// analytic derivatives, and the seeds' values are each rasterizer's interpolation. On this
/// plane, parallel to the image, the seeds are affine in screen space, so all of these agree up
/// to rounding: a quad difference of two interpolated values below 1 in magnitude, each rounded
/// by up to 2^-24, over their step of at least 1/32 (s, t step 1/32 per pixel, P 2/32 at z = 1)
/// is off by at most 2^-23 * 32 = 4e-6 relative; `Du` and `area` divide and multiply two or three
/// such differences (about 1.2e-5), `calculatenormal` crosses two. 1e-4 relative keeps a factor
/// of 8 over that; the absolute part covers results
/// that cancel towards zero and `filterstep`, whose value moves by its slope (at most
/// 1 / filterwidth = 32 here) times the error of its inputs (a few ulp of values below 1).
/// Lavapipe measured 0: its interpolation and quad differences give the CPU reference's bits on
/// this plane, but nothing in WGSL promises that.
const DERIVATIVES: Tol = Tol::rel(1e-4, 1e-5);

// -------------------------------------------------------------------------------------------------
// The shaders.

/// The scalar kind of a type's components.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Kind {
    Float,
    Int,
    Uint,
    Bool,
}

/// A type's scalar kind and the accessors of its components (`""`, `"[2]"`, `"[1][3]"`,
/// `"[4][0]"` for element 4 of an array of triples).
fn components(ty: &str) -> (Kind, Vec<String>) {
    if let Some((base, n)) = ty.split_once('[') {
        let n: usize = n.trim_end_matches(']').parse().expect("array size");
        let (kind, inner) = components(base);
        let all = (0..n).flat_map(|e| inner.iter().map(move |c| format!("[{e}]{c}"))).collect();
        return (kind, all);
    }
    let index = |n: usize| (0..n).map(|c| format!("[{c}]")).collect();
    let rows = |n: usize| (0..n).flat_map(|r| (0..n).map(move |c| format!("[{r}][{c}]"))).collect();
    match ty {
        "float" => (Kind::Float, vec![String::new()]),
        "color" | "point" | "vector" | "normal" | "float3" => (Kind::Float, index(3)),
        "float4" => (Kind::Float, index(4)),
        "matrix" => (Kind::Float, rows(4)),
        "matrix3" => (Kind::Float, rows(3)),
        "int" => (Kind::Int, vec![String::new()]),
        "uint" => (Kind::Uint, vec![String::new()]),
        "bool" => (Kind::Bool, vec![String::new()]),
        other => panic!("no render packing for `{other}`"),
    }
}

/// How many scalars an output of type `ty` packs into (integers take two 16-bit halves).
fn packed(ty: &str) -> usize {
    let (kind, comps) = components(ty);
    comps.len() * if matches!(kind, Kind::Int | Kind::Uint) { 2 } else { 1 }
}

/// The specials of a domain that lavapipe's fragment shaders keep: no denormals, and nothing
/// whose halves or reciprocals are denormal.
fn render_specials(dom: &Dom) -> Vec<f64> {
    dom.specials
        .iter()
        .copied()
        .filter(|x| !x.is_finite() || *x == 0.0 || (1e-30..=1e30).contains(&x.abs()))
        .collect()
}

/// A domain with [`render_specials`].
fn render_dom(dom: Dom) -> Dom {
    Dom { specials: Box::leak(render_specials(&dom).into_boxed_slice()), ..dom }
}

/// A value as a literal of the language (`pinf`, `qnan` are parameters the scene sets).
fn literal(x: f64, kind: Kind) -> String {
    match kind {
        Kind::Int if x == -2_147_483_648.0 => "(-2147483647 - 1)".into(),
        Kind::Int => format!("{}", x as i64),
        Kind::Uint => format!("{}u", x as u64),
        _ if x.is_nan() => "qnan".into(),
        _ if x.is_infinite() => {
            if x > 0.0 {
                "pinf".into()
            } else {
                "-pinf".into()
            }
        }
        _ => {
            let s = format!("{:?}", x as f32);
            if s.contains(['.', 'e']) { s } else { format!("{s}.0") }
        }
    }
}

/// The fixed-point grid a varying argument's values lie on: `(lo + n) * 2^-p` for n in
/// [0, span). For floats p is chosen so that every |lo + n| < 2^24 (exact as f32) and
/// span <= 2^24 (drawn from 24 bits of the hash); integers use p = 0 and the whole hash.
#[derive(Clone, Copy, Debug)]
struct Grid {
    lo: i64,
    span: u64,
    p: i32,
}

fn grid(dom: &Dom, kind: Kind) -> Grid {
    let p = if dom.integer || kind != Kind::Float {
        0
    } else {
        let m = dom.lo.abs().max(dom.hi.abs()).max(dom.hi - dom.lo);
        23 - m.log2().ceil() as i32
    };
    let scale = 2f64.powi(p);
    let lo = (dom.lo * scale).ceil() as i64;
    let hi = (dom.hi * scale).floor() as i64;
    Grid { lo, span: (hi - lo + 1) as u64, p }
}

/// murmur3's finalizer, as the shader computes it.
fn mix32(mut h: u32) -> u32 {
    h ^= h >> 16;
    h = h.wrapping_mul(2_246_822_507);
    h ^= h >> 13;
    h = h.wrapping_mul(3_266_489_909);
    h ^ (h >> 16)
}

/// The same in the language, on `h`.
const MIX32: &str = "h ^= h >> 16u; h *= 2246822507u; h ^= h >> 13u; h *= 3266489909u; h ^= h >> 16u;";

/// The multiplier that spreads pixel indices before hashing.
const SPREAD: u32 = 2_654_435_761;

/// One varying argument: its local, its components' hash salts, its grid and specials.
struct Varying {
    name: String,
    kind: Kind,
    salts: Vec<u32>,
    grid: Grid,
    specials: Vec<f64>,
}

impl Varying {
    /// A component's value at a pixel, as the shader computes it.
    fn value(&self, component: usize, cell: u32, seed: u32) -> f64 {
        let h = mix32(cell.wrapping_mul(SPREAD).wrapping_add(self.salts[component] ^ seed));
        if !self.specials.is_empty() && (h & 255) < 64 {
            return self.specials[((h & 255) % self.specials.len() as u32) as usize];
        }
        let bits = if self.grid.span > 1 << 24 { u64::from(h) } else { u64::from(h >> 8) };
        let n = self.grid.lo + (bits % self.grid.span) as i64;
        match self.kind {
            Kind::Int => f64::from(n as i32),
            Kind::Uint => f64::from(n as u32),
            _ => n as f64 * 2f64.powi(-self.grid.p),
        }
    }

    /// The statement that computes component `c` (`access`) in the shader.
    fn statement(&self, c: usize, access: &str) -> String {
        let g = self.grid;
        let bits = if g.span > 1 << 24 { "h" } else { "(h >> 8u)" };
        let n = format!("{bits} % {}u", g.span);
        let mut value = match self.kind {
            Kind::Uint => format!("{}u + {n}", g.lo),
            Kind::Int => format!("{} + int({n})", g.lo),
            _ => {
                let x = format!("float({} + int({n}))", g.lo);
                if g.p == 0 { x } else { format!("{x} * {:e}", 2f64.powi(-g.p)) }
            }
        };
        let mut pick = String::new();
        if !self.specials.is_empty() {
            // A chain of selections, not an indexed array: llvmpipe compiles a dynamically
            // indexed private array slowly (20 s for one shader, against 0.7 s).
            let count = self.specials.len();
            let mut chain = literal(self.specials[count - 1], self.kind);
            for (k, x) in self.specials.iter().enumerate().rev().skip(1) {
                chain = format!("j == {k}u ? {} : {chain}", literal(*x, self.kind));
            }
            pick = format!(" uint j = (h & 255u) % {count}u;");
            value = format!("(h & 255u) < 64u ? ({chain}) : {value}");
        }
        format!(
            "{{ uint h = base + ({}u ^ seed); {MIX32}{pick} {}{access} = {value}; }}",
            self.salts[c], self.name
        )
    }
}

/// One output of one mix of one case.
struct Output {
    name: String,
    tol: Tol,
    /// The case, within its shader.
    case: usize,
}

/// A shader and where each of its outputs lands.
struct Layout {
    src: String,
    outputs: Vec<Output>,
    /// The colours: up to three (output, scalar) pairs each.
    colours: Vec<[Option<(usize, usize)>; 3]>,
    /// Uniform parameters: name, type, domain.
    uniforms: Vec<(String, &'static str, Dom)>,
    varyings: Vec<Varying>,
}

/// Builds the shader of a list of cases (see the module's documentation).
fn layout(cases: &[Case], tolerance: fn(Tol) -> Tol) -> Layout {
    let mut params = vec![
        "uniform uint seed = 0u".to_string(),
        "uniform float pinf = 0".into(),
        "uniform float qnan = 0".into(),
    ];
    let mut uniforms = Vec::new();
    let mut varyings = Vec::new();
    let mut body = String::new();
    let mut lines = String::new();
    let mut outputs = Vec::new();
    // (output, its scalar's index within the output, expression)
    let mut scalars: Vec<(usize, usize, String)> = Vec::new();
    for (i, c) in cases.iter().enumerate() {
        for (k, (ty, dom)) in c.args.iter().enumerate() {
            let dom = render_dom(*dom);
            params.push(format!("uniform {}", declare(ty, &format!("c{i}a{k}u"))));
            uniforms.push((format!("c{i}a{k}u"), *ty, dom));
            let (kind, comps) = components(ty);
            let salts = (0..comps.len())
                .map(|n| mix32(((i as u32) << 16) ^ ((k as u32) << 10) ^ n as u32 ^ 0x5bd1_e995))
                .collect();
            let v = Varying {
                name: format!("c{i}a{k}v"),
                kind,
                salts,
                grid: grid(&dom, kind),
                specials: dom.specials.to_vec(),
            };
            writeln!(body, "    varying {};", declare(ty, &v.name)).unwrap();
            for (n, access) in comps.iter().enumerate() {
                writeln!(body, "    {}", v.statement(n, access)).unwrap();
            }
            varyings.push(v);
        }
        for m in mixes(c.args.len()) {
            let mut line = c.body.to_string();
            for (j, (ty, t)) in c.outs.iter().enumerate() {
                let name = format!("o{i}m{m}_{j}");
                writeln!(body, "    varying {};", declare(ty, &name)).unwrap();
                let (kind, comps) = components(ty);
                let t = if kind == Kind::Float { tolerance(*t) } else { Tol::Int };
                let o = outputs.len();
                outputs.push(Output { name: name.clone(), tol: t, case: i });
                let mut push = |x: String| {
                    let within = scalars.iter().filter(|s| s.0 == o).count();
                    scalars.push((o, within, x));
                };
                for access in comps {
                    let x = format!("{name}{access}");
                    match kind {
                        Kind::Float => push(x),
                        Kind::Bool => push(format!("({x} ? 1.0 : 0.0)")),
                        Kind::Int => {
                            push(format!("float({x} & 65535)"));
                            push(format!("float(({x} >> 16) & 65535)"));
                        }
                        Kind::Uint => {
                            push(format!("float({x} & 65535u)"));
                            push(format!("float({x} >> 16u)"));
                        }
                    }
                }
                line = if c.outs.len() == 1 {
                    line.replace("$o", &name)
                } else {
                    line.replace(&format!("$o{j}"), &name)
                };
            }
            for k in (0..c.args.len()).rev() {
                let rate = if m & (1 << k) != 0 { 'v' } else { 'u' };
                line = line.replace(&format!("${k}"), &format!("c{i}a{k}{rate}"));
            }
            writeln!(lines, "    {line}").unwrap();
        }
    }
    let mut colours = Vec::new();
    let mut select = String::new();
    for (n, chunk) in scalars.chunks(3).enumerate() {
        let mut slot = [None; 3];
        let mut exprs = ["0", "0", "0"];
        for (ch, (o, within, x)) in chunk.iter().enumerate() {
            slot[ch] = Some((*o, *within));
            exprs[ch] = x;
        }
        colours.push(slot);
        writeln!(select, "    if (slot == {n}u) Ci = color({}, {}, {});", exprs[0], exprs[1], exprs[2])
            .unwrap();
    }
    let src = format!(
        "surface conformance_render(\n    {}\n) {{\n    \
         uint cell = uint(floor(t * {SIDE}) * {SIDE} + floor(s * {SIDE}));\n    \
         uint base = cell * {SPREAD}u;\n{body}{lines}    uint slot = cell % {}u;\n    Ci = 0;\n{select}}}\n",
        params.join(";\n    "),
        colours.len(),
    );
    Layout { src, outputs, colours, uniforms, varyings }
}

/// Splits a group into runs of consecutive cases that fit [`MAX_COLOURS`] colours each.
fn chunks(cases: Vec<Case>) -> Vec<Vec<Case>> {
    let mut out: Vec<Vec<Case>> = vec![Vec::new()];
    let mut used = 0;
    for c in cases {
        let per_mix: usize = c.outs.iter().map(|(ty, _)| packed(ty)).sum();
        let scalars = per_mix * mixes(c.args.len()).len();
        assert!(scalars <= 3 * MAX_COLOURS, "one case needs {scalars} scalars: `{}`", c.body);
        if used + scalars > 3 * MAX_COLOURS {
            out.push(Vec::new());
            used = 0;
        }
        used += scalars;
        out.last_mut().expect("a chunk").push(c);
    }
    out
}

// -------------------------------------------------------------------------------------------------
// Scenes and comparison.

/// A number as TOML writes it.
fn toml(x: f64) -> String {
    if x.is_nan() {
        "nan".into()
    } else if x.is_infinite() {
        if x > 0.0 { "inf".into() } else { "-inf".into() }
    } else {
        format!("{x:?}")
    }
}

/// The light shaders the light sums are bound to: distant lights (their `L` is the parameter
/// `dir`, whatever the surface point, so the interpolated `P` cannot reach it) and an ambient
/// one. (`solar(dir, 0.0)`: with an integer angle, `solar(dir, 0)`, the interpreter's lowering
/// panics and the WGSL module does not validate: the angle reaches the backends unconverted.)
const LIGHTS: &str = "light cdistant(uniform vector dir = vector(0, 0, 1); uniform color c = 1) {
    solar(dir, 0.0) {
        Cl = c;
    }
}

light cambient(uniform color c = 0.25) {
    Cl = c;
    L = 0;
}
";

/// The camera and the plane: the camera at the origin looking down +z (so world and camera space
/// are the same and the scene's points reach the shader unchanged), a plane of side 2 at z = 1
/// filling the 90° view exactly.
fn scene_head() -> String {
    format!(
        "[output]\nwidth = {SIDE}\nheight = {SIDE}\nbackground = [0.0, 0.0, 0.0, 1.0]\n\
         [camera]\nfrom = [0.0, 0.0, 0.0]\nto = [0.0, 0.0, 1.0]\nup = [0.0, 1.0, 0.0]\nfov = 90\n"
    )
}

fn scene_object(params: &str) -> String {
    format!(
        "[[object]]\nmesh = \"plane\"\ndetail = 2\nshader = \"s.sl\"\n\
         transform = [{{ translate = [0.0, 0.0, 1.0] }}]\n[object.params]\n{params}"
    )
}

/// The hash seed of a batch.
fn seed(batch: usize) -> u32 {
    mix32(batch as u32 + 1)
}

/// The scene of one batch of a shader: its lights, and its uniform values drawn under the name
/// `key/parameter`.
fn scene_text(layout: &Layout, lights: &[LightBinding], key: &str, batch: usize) -> String {
    let mut s = scene_head();
    for (k, light) in lights.iter().enumerate() {
        let c = cases::sample_n(cases::UNIT, "light colour", batch, k, 3);
        let c = format!("c = [{}, {}, {}]", c[0], c[1], c[2]);
        if light.ambient {
            writeln!(s, "[[light]]\nshader = \"lights.sl\"\nname = \"cambient\"\nparams = {{ {c} }}")
                .unwrap();
        } else {
            let d = cases::sample_n(cases::R1, "light direction", batch, k, 3);
            let d = format!("dir = [{}, {}, {}]", d[0], d[1], d[2]);
            writeln!(s, "[[light]]\nshader = \"lights.sl\"\nname = \"cdistant\"\nparams = {{ {d}, {c} }}")
                .unwrap();
        }
    }
    let mut params = format!("seed = {}\npinf = inf\nqnan = nan\n", seed(batch));
    for (name, ty, dom) in &layout.uniforms {
        let n = components(ty).1.len();
        let v: Vec<String> =
            cases::sample_n(*dom, &format!("{key}/{name}"), batch, 0, n).iter().map(|x| toml(*x)).collect();
        if n == 1 {
            writeln!(params, "{name} = {}", v[0]).unwrap();
        } else {
            writeln!(params, "{name} = [{}]", v.join(", ")).unwrap();
        }
    }
    s + &scene_object(&params)
}

fn report() -> bool {
    std::env::var_os("PATINA_CONFORMANCE_REPORT").is_some()
}

/// A temporary directory holding a scene's files.
struct TempDir(std::path::PathBuf);

impl TempDir {
    fn new(name: &str, shader: &str) -> TempDir {
        let dir =
            std::env::temp_dir().join(format!("patina-conformance-render-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(dir.join("s.sl"), shader).unwrap();
        std::fs::write(dir.join("lights.sl"), LIGHTS).unwrap();
        TempDir(dir)
    }
}

impl Drop for TempDir {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

/// Renders a scene on both backends.
fn render_both(gpu: &Gpu, dir: &Path, scene: &str) -> (Prepared, Image, Image) {
    let t0 = Instant::now();
    let scene = Scene::parse(scene, dir.join("s.toml"), dir).unwrap_or_else(|e| panic!("{e}\n{scene}"));
    // Compiled dynamic: the suite measures the backends' arithmetic on uniform arguments. Bound
    // to the scene, those become constants the GPU driver folds its own way (seen on lavapipe:
    // results 1 ulp apart in colour conversions, splines and matrix products, and mod(x, 0) giving
    // x where the reference computes x - 0 * floor(x / 0), NaN), so a specialized program matches
    // the reference within image tolerances, not bit for bit.
    let prepared = render::prepare_with(&scene, Options { specialize: false, ..Options::default() })
        .unwrap_or_else(|e| panic!("{e}"));
    let t1 = Instant::now();
    let cpu = render::render(&prepared, Backend::Cpu, None).unwrap_or_else(|e| panic!("{e}"));
    let t2 = Instant::now();
    let gpu = render::render(&prepared, Backend::Gpu, Some(gpu)).unwrap_or_else(|e| panic!("{e}"));
    if report() {
        let (a, b, c) = ((t1 - t0).as_secs_f64(), (t2 - t1).as_secs_f64(), t2.elapsed().as_secs_f64());
        eprintln!("prepare {a:.2} s, CPU render {b:.2} s, GPU render {c:.2} s");
    }
    assert_eq!((cpu.width, cpu.height, gpu.width, gpu.height), (SIDE, SIDE, SIDE, SIDE));
    (prepared, cpu, gpu)
}

/// The arguments of case `case` at pixel `cell`, for a report.
fn arguments(layout: &Layout, prepared: &Prepared, case: usize, cell: u32, seed: u32) -> String {
    let prefix = format!("c{case}a");
    let mut shown = Vec::new();
    for (name, _, _) in layout.uniforms.iter().filter(|(n, _, _)| n.starts_with(&prefix)) {
        // As the host computed it (the value the uniform block carries).
        shown.push(format!("{name} = {:?}", prepared.objects[0].param(name).unwrap_or_default()));
    }
    for v in layout.varyings.iter().filter(|v| v.name.starts_with(&prefix)) {
        let values: Vec<f64> = (0..v.salts.len()).map(|c| v.value(c, cell, seed)).collect();
        shown.push(format!("{} = {values:?}", v.name));
    }
    shown.join(", ")
}

/// Per output: values outside the tolerance, the first of them, the largest differences.
#[derive(Clone, Default)]
struct Tally {
    bad: usize,
    first: Option<String>,
    max_abs: f64,
    max_ulp: u64,
}

/// Renders one shader's batches and compares them. Returns the number of values compared and
/// one line per output outside its tolerance.
fn run_shader(gpu: &Gpu, name: &str, layout: &Layout, lights: &[LightBinding]) -> (usize, Vec<String>) {
    assert!(layout.colours.len() <= MAX_COLOURS);
    let dir = TempDir::new(name, &layout.src);
    let mut tally = vec![Tally::default(); layout.outputs.len()];
    let mut compared = 0;
    for batch in 0..BATCHES {
        let (prepared, cpu, gpu_image) = render_both(gpu, &dir.0, &scene_text(layout, lights, name, batch));
        for (p, (c, g)) in cpu.pixels.iter().zip(&gpu_image.pixels).enumerate() {
            assert!(c[3] == 1.0 && g[3] == 1.0, "{name}: pixel {p} is not covered: cpu {c:?}, gpu {g:?}");
            let cell = p as u32;
            let slot = layout.colours[p % layout.colours.len()];
            for ch in 0..3 {
                let Some((o, scalar)) = slot[ch] else {
                    assert!(c[ch] == 0.0 && g[ch] == 0.0, "{name}: padding at pixel {p}: {c:?} {g:?}");
                    continue;
                };
                let out = &layout.outputs[o];
                compared += 1;
                let (gv, cv) = (g[ch], c[ch]);
                let t = &mut tally[o];
                if gv.is_finite() && cv.is_finite() {
                    t.max_abs = t.max_abs.max((f64::from(gv) - f64::from(cv)).abs());
                    t.max_ulp = t.max_ulp.max(harness::ulps(gv, cv));
                }
                if !out.tol.accepts(gv, cv) {
                    t.bad += 1;
                    if t.first.is_none() {
                        t.first = Some(format!(
                            "first at batch {batch} pixel ({}, {}) scalar {scalar}: gpu {gv:e} ({:#010x}), \
                             cpu {cv:e} ({:#010x})\n    arguments: {}",
                            cell % SIDE,
                            cell / SIDE,
                            gv.to_bits(),
                            cv.to_bits(),
                            arguments(layout, &prepared, out.case, cell, seed(batch))
                        ));
                    }
                }
            }
        }
    }
    let mut failures = Vec::new();
    for (out, t) in layout.outputs.iter().zip(&tally) {
        if report() && out.tol != Tol::Int {
            eprintln!(
                "{name:>14} {:>10} {:?}: max |gpu - cpu| {:e}, max {} ulp",
                out.name, out.tol, t.max_abs, t.max_ulp
            );
        }
        if let Some(f) = &t.first {
            failures.push(format!("{name} `{}` ({:?}): {} values differ; {f}", out.name, out.tol, t.bad));
        }
    }
    if !failures.is_empty() {
        failures.push(format!("shader {name}:\n{}", layout.src));
    }
    (compared, failures)
}

/// Runs a group of cases through the render path and panics with a report of every output
/// outside its tolerance. `tolerance` maps a case's tolerance to the one it has here. Returns the
/// number of values compared.
fn run_group(group: &str, cases: Vec<Case>, lights: &[LightBinding], tolerance: fn(Tol) -> Tol) -> usize {
    let Some(gpu) = gpu::for_tests() else { return 0 };
    let mut compared = 0;
    let mut failures = Vec::new();
    let mut outputs = 0;
    for (k, chunk) in chunks(cases).iter().enumerate() {
        let layout = layout(chunk, tolerance);
        outputs += layout.outputs.len();
        let name = format!("{group}{k}");
        let (n, f) = run_shader(gpu, &name, &layout, lights);
        compared += n;
        failures.extend(f);
    }
    if report() {
        eprintln!("{group}: {outputs} outputs, {compared} values compared");
    }
    assert!(failures.is_empty(), "\n{group}: outputs disagree:\n{}", failures.join("\n"));
    assert!(compared > 0, "{group}: nothing compared");
    compared
}

/// The cases' own tolerances.
fn same(t: Tol) -> Tol {
    t
}

// -------------------------------------------------------------------------------------------------
// Tests.

/// The premise of the varying arguments: each pixel's `floor(s * 32)`, `floor(t * 32)` is its
/// column and row on both renderers, and `s`, `t` themselves agree closely (lavapipe measured:
/// bit for bit; allowed: 4 ulp, the rounding of two differently ordered interpolations).
#[test]
fn cells_come_from_the_interpolated_surface() {
    let Some(gpu) = gpu::for_tests() else { return };
    let src =
        format!("surface cells() {{ Ci = color(s, t, floor(t * {SIDE}) * {SIDE} + floor(s * {SIDE})); }}\n");
    let dir = TempDir::new("cells", &src);
    let (_, cpu, gpu_image) = render_both(gpu, &dir.0, &(scene_head() + &scene_object("")));
    let mut worst = 0;
    for (p, (c, g)) in cpu.pixels.iter().zip(&gpu_image.pixels).enumerate() {
        let (x, y) = ((p as u32 % SIDE) as f32, (p as u32 / SIDE) as f32);
        for image in [c, g] {
            assert_eq!(image[2], p as f32, "pixel ({x}, {y}): {image:?}");
            assert!((image[0] - (x + 0.5) / SIDE as f32).abs() < 1e-6, "pixel ({x}, {y}): s = {}", image[0]);
            assert!((image[1] - (y + 0.5) / SIDE as f32).abs() < 1e-6, "pixel ({x}, {y}): t = {}", image[1]);
        }
        worst = worst.max(harness::ulps(c[0], g[0])).max(harness::ulps(c[1], g[1]));
    }
    if report() {
        eprintln!("s, t: at most {worst} ulp apart");
    }
    assert!(worst <= 4, "s and t differ by {worst} ulp");
}

#[test]
fn trigonometry_and_exponentials() {
    run_group("trig", cases::trigonometry_and_exponentials(), &[], same);
}

#[test]
fn exact_math() {
    run_group("exact", cases::exact_math(), &[], same);
}

#[test]
fn integer_functions_and_operators() {
    run_group("integer", cases::integer_functions_and_operators(), &[], same);
}

#[test]
fn float_and_vector_operators() {
    run_group("operators", cases::float_and_vector_operators(), &[], same);
}

#[test]
fn geometric_functions() {
    run_group("geometric", cases::geometric_functions(), &[], same);
}

#[test]
fn transformations_and_matrices() {
    run_group("matrices", cases::transformations_and_matrices(), &[], same);
}

#[test]
fn matrix_division() {
    run_group("division", cases::matrix_division(), &[], same);
}

#[test]
fn colour_spaces() {
    run_group("colour", cases::colour_spaces(), &[], same);
}

#[test]
fn noise_float() {
    run_group("noise_float", cases::noise(cases::NoiseGroup::Float), &[], same);
}

#[test]
fn noise_colour() {
    run_group("noise_colour", cases::noise(cases::NoiseGroup::Colour), &[], same);
}

#[test]
fn noise_cell() {
    run_group("noise_cell", cases::noise(cases::NoiseGroup::Cell), &[], same);
}

#[test]
fn noise_periodic() {
    run_group("noise_periodic", cases::noise(cases::NoiseGroup::Periodic), &[], same);
}

#[test]
fn splines() {
    run_group("splines", cases::splines(), &[], same);
}

#[test]
fn light_sums() {
    run_group("lights", cases::light_sums(), &cases::light_sum_lights(), same);
}

#[test]
fn derivatives() {
    run_group("derivatives", cases::derivatives(), &[], |_| DERIVATIVES);
}

#[test]
fn stanford_vector_functions_and_select() {
    run_group("stanford", cases::stanford_vector_functions_and_select(), &[], same);
}

#[test]
fn array_reads() {
    run_group("arrays", cases::array_reads(), &[], same);
}

#[test]
fn strings_are_folded() {
    run_group("strings", cases::strings_are_folded(), &[], same);
}
