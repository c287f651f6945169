//! Drawing a prepared scene with the CPU reference: the vertex stage by the interpreter at every
//! vertex, the rasterizer, and the fragment stage by the interpreter over batches of fragments,
//! with the lights' programs run at each fragment and the rasterizer's analytic derivatives as
//! the seeds.

use glam::Vec3;
use patina_compiler::backend::POINT_INDEX;
use patina_compiler::backend::cpu::exec::LANES;
use patina_compiler::backend::cpu::{
    CpuProgram, Evaluator, lightsource_input, surface_flag_input, surface_input,
};
use patina_compiler::backend::wgsl::interface::Output;
use patina_compiler::sema::globals;
use patina_compiler::split::StageKind;
use patina_compiler::syntax::ast::ShaderKind;

use super::frame::{Frame, VertexGeometry};
use super::program::{LightProgram, SurfaceProgram, set_globals, set_spaces};
use super::{Object, Prepared, Progress, RenderError, Unit};
use crate::image::Image;
use std::sync::Mutex;

use rayon::prelude::*;

use crate::raster::{Blend, DrawOptions, Fragments, Framebuffer, Varyings, draw, rasterize};

/// Renders every object on the CPU into an image of `width × height`, telling `progress` how many
/// fragments there are to shade and how many are done.
pub fn render(
    prepared: &Prepared,
    width: u32,
    height: u32,
    progress: &dyn Progress,
) -> Result<Image, RenderError> {
    let shaded_vertices: Vec<Vertices> =
        prepared.objects.iter().map(vertex_stage).collect::<Result<_, _>>()?;
    // A dry run of the rasterizer, with the same depth tests in the same order, counts exactly the
    // fragments the fragment stage will shade; it costs little next to shading them.
    let mut dry = Framebuffer::new(width, height, prepared.background);
    let mut total = 0;
    for v in &shaded_vertices {
        let stats = draw(&mut dry, &v.clip, v.indices, &v.varyings(), &DRAW, |_, _| Ok::<_, RenderError>(()))
            .map_err(|e| RenderError::Run(e.to_string()))?;
        total += stats.fragments as u64;
    }
    progress.start(total, Unit::Fragments);
    let mut fb = Framebuffer::new(width, height, prepared.background);
    for (object, vertices) in prepared.objects.iter().zip(&shaded_vertices) {
        fragment_stage(&mut fb, prepared, object, vertices, progress)?;
    }
    Ok(Image { width, height, pixels: fb.color })
}

/// How every object is drawn: blended over what is there, with depth writes, in batches of the
/// interpreter's lane count.
const DRAW: DrawOptions = DrawOptions { blend: Blend::PremultipliedOver, depth_write: true, batch: LANES };

/// One object after its vertex stage: what the rasterizer needs to draw it.
struct Vertices<'a> {
    /// Where each varying comes from, its first component, its width and whether it is flat.
    carried: Vec<(Carried, usize, usize, bool)>,
    /// Components per vertex.
    components: usize,
    /// `components` values per vertex.
    data: Vec<f32>,
    /// Per component: not interpolated.
    flat: Vec<bool>,
    /// Clip-space positions.
    clip: Vec<[f32; 4]>,
    /// The mesh's triangles.
    indices: &'a [u32],
}

impl Vertices<'_> {
    fn varyings(&self) -> Varyings<'_> {
        Varyings { components: self.components, data: &self.data, flat: &self.flat }
    }
}

/// A varying's source, as the WGSL backend's entry point names it.
enum Carried {
    /// A predefined variable, and those that are equal to it on entry (the interface's `also`).
    Global(String, Vec<String>),
    Param(String),
    Transfer(String),
}

/// Runs the vertex stage of `object` at every vertex and lays out the varyings.
fn vertex_stage<'a>(object: &'a Object) -> Result<Vertices<'a>, RenderError> {
    let surface = &object.surface;
    let frame = &object.frame;
    let stanford = surface.stages.fragment.stanford;
    let geometry = frame.geometry(&object.mesh);
    let count = geometry.len();
    let interface = &surface.gpu.interface;

    // The vertex stage.
    let mut vertex = Evaluator::<f32>::new(&surface.vertex);
    bind_textures(&mut vertex, &surface.vertex, object);
    set_uniforms(&mut vertex, &surface.vertex, surface, frame);
    let mut columns: Vec<(String, Vec<f64>)> = Vec::new();
    for (_, slot) in surface.vertex.slots() {
        if slot.uniform {
            continue;
        }
        if let Some(c) = object_colour(frame, &slot.name) {
            columns.push((slot.name.clone(), (0..count).flat_map(|_| c.iter().copied()).collect()));
        } else if let Some(first) = geometry.first().and_then(|g| g.global(&slot.name, stanford)) {
            let width = first.len();
            let col: Vec<f64> = geometry
                .iter()
                .flat_map(|g| g.global(&slot.name, stanford).unwrap_or(vec![0.0; width]))
                .map(f64::from)
                .collect();
            columns.push((slot.name.clone(), col));
        } else if object.param(&slot.name).is_some() {
            let col = (0..count).flat_map(|i| object.vertex_param(&slot.name, i, slot.width)).collect();
            columns.push((slot.name.clone(), col));
        }
    }
    let transfers: Vec<String> = surface
        .stages
        .transfers
        .iter()
        .filter(|t| t.from == StageKind::Vertex && t.to_fragment)
        .map(|t| t.name.to_string())
        .collect();
    let inputs: Vec<(&str, &[f64])> = columns.iter().map(|(n, c)| (n.as_str(), c.as_slice())).collect();
    let refs: Vec<&str> = transfers.iter().map(String::as_str).collect();
    let outputs = vertex.eval_points(count, &inputs, &refs).map_err(|e| RenderError::Run(e.to_string()))?;

    // The varyings, in the interface's order and layout.
    let mut carried = Vec::new();
    let mut components = 0;
    for v in &interface.varyings {
        let what = if transfers.contains(&v.name) {
            Carried::Transfer(v.name.clone())
        } else {
            let name = v.name.trim_start_matches("in_").to_string();
            if object_colour(frame, &name).is_some()
                || geometry.first().and_then(|g| g.global(&name, stanford)).is_some()
            {
                Carried::Global(name, v.also.clone())
            } else {
                Carried::Param(name)
            }
        };
        carried.push((what, components, v.components as usize, v.flat));
        components += v.components as usize;
    }
    let mut data = vec![0f32; components * count];
    let mut flat = vec![false; components];
    for (what, offset, width, is_flat) in &carried {
        for c in 0..*width {
            flat[offset + c] = *is_flat;
        }
        for i in 0..count {
            let values: Vec<f32> = match what {
                Carried::Global(name, _) => match object_colour(frame, name) {
                    Some(c) => c.iter().map(|x| *x as f32).collect(),
                    None => geometry[i].global(name, stanford).unwrap_or_default(),
                },
                Carried::Param(name) => {
                    object.vertex_param(name, i, *width).iter().map(|x| *x as f32).collect()
                }
                Carried::Transfer(name) => {
                    let k = transfers.iter().position(|t| t == name).unwrap_or(0);
                    outputs[k][i * width..(i + 1) * width].iter().map(|x| *x as f32).collect()
                }
            };
            for c in 0..*width {
                data[i * components + offset + c] = values.get(c).copied().unwrap_or(0.0);
            }
        }
    }
    let clip: Vec<[f32; 4]> = geometry
        .iter()
        .map(|g: &VertexGeometry| (frame.camera_to_clip * g.p.extend(1.0)).to_array())
        .collect();
    Ok(Vertices { carried, components, data, flat, clip, indices: &object.mesh.indices })
}

/// Rasterizes `object` into `fb` and runs its fragment stage (with the lights' programs) over the
/// fragments, in batches shaded on every core of rayon's pool. The rasterizer runs ahead, depth
/// tests and all, collecting a window of batches; the window is shaded in parallel and blended in
/// the order the batches came, so the picture is the one-batch-at-a-time picture bit for bit (an
/// evaluator's result for a batch does not depend on what it evaluated before: `Evaluator::eval`
/// refills every register a program reads before writing it).
fn fragment_stage(
    fb: &mut Framebuffer,
    prepared: &Prepared,
    object: &Object,
    vertices: &Vertices,
    progress: &dyn Progress,
) -> Result<(), RenderError> {
    let shaders = Pool::new(|| Shaders::new(prepared, object));
    // Enough batches per thread that the threads finish a window at about the same time.
    let window_len = 32 * rayon::current_num_threads();
    let mut window: Vec<Fragments> = Vec::with_capacity(window_len);
    let shade_window = |fb: &mut Framebuffer, window: &mut Vec<Fragments>| -> Result<(), RenderError> {
        let colours: Vec<Result<Vec<[f32; 4]>, RenderError>> = window
            .par_iter()
            .map(|frags| {
                let mut colours = vec![[0.0f32; 4]; frags.count];
                shaders.with(|s| s.shade(frags, &mut colours, prepared, object, vertices))?;
                Ok(colours)
            })
            .collect();
        for (frags, colours) in window.iter().zip(colours) {
            fb.blend(&frags.pixels, &colours?, DRAW.blend);
            progress.advance(frags.count as u64);
        }
        window.clear();
        Ok(())
    };
    rasterize(fb, &vertices.clip, vertices.indices, &vertices.varyings(), &DRAW, |fb, frags| {
        window.push(frags.clone());
        if window.len() >= window_len {
            shade_window(fb, &mut window)?;
        }
        Ok(())
    })
    .map_err(|e| match e {
        crate::raster::DrawError::Shade(e) => e,
        other => RenderError::Run(other.to_string()),
    })?;
    shade_window(fb, &mut window)
}

/// The evaluators one thread shades an object's fragments with: the fragment stage's and each
/// light's, their inputs set for the object.
struct Shaders<'a> {
    fragment: Evaluator<'a, f32>,
    lights: Vec<Evaluator<'a, f32>>,
}

impl<'a> Shaders<'a> {
    fn new(prepared: &'a Prepared, object: &'a Object) -> Self {
        let surface = &object.surface;
        let frame = &object.frame;
        let mut fragment = Evaluator::<f32>::new(&surface.fragment);
        bind_textures(&mut fragment, &surface.fragment, object);
        set_uniforms(&mut fragment, &surface.fragment, surface, frame);
        let lights = prepared
            .lights
            .iter()
            .map(|l| {
                let mut e = Evaluator::<f32>::new(&l.cpu);
                // A light's lookups (shadow maps) read the textures loaded for the surface it lights.
                bind_textures(&mut e, &l.cpu, object);
                set_spaces(&mut e, &l.cpu, &frame.light_spaces);
                // A Stanford light's matrices are the object's, since it runs at its points.
                set_globals(&mut e, &l.cpu, frame);
                for (name, value) in &l.values {
                    let _ = e.set(name, value);
                }
                set_surface_flags(&mut e, &l.cpu, surface);
                e
            })
            .collect();
        Shaders { fragment, lights }
    }

    fn shade(
        &mut self,
        frags: &Fragments,
        colours: &mut [[f32; 4]],
        prepared: &Prepared,
        object: &Object,
        vertices: &Vertices,
    ) -> Result<(), RenderError> {
        let surface = &object.surface;
        let output = surface.gpu.interface.output;
        let (fragment, lights) = (&mut self.fragment, &mut self.lights);
        shade_batch(
            frags,
            colours,
            &vertices.carried,
            fragment,
            lights,
            prepared,
            surface,
            &object.frame,
            output,
        )
    }
}

/// Values made on demand and reused, one in use per thread at a time: rayon gives no thread-local
/// state, and making an evaluator per batch would cost more than some batches do.
struct Pool<T, M> {
    free: Mutex<Vec<T>>,
    make: M,
}

impl<T, M: Fn() -> T> Pool<T, M> {
    fn new(make: M) -> Self {
        Pool { free: Mutex::new(Vec::new()), make }
    }

    /// Runs `f` with a value of the pool (a new one when all are in use).
    fn with<R>(&self, f: impl FnOnce(&mut T) -> R) -> R {
        let free = self.free.lock().map(|mut v| v.pop()).unwrap_or_default();
        let mut value = free.unwrap_or_else(|| (self.make)());
        let result = f(&mut value);
        if let Ok(mut free) = self.free.lock() {
            free.push(value);
        }
        result
    }
}

/// Uniform inputs of a stage program: every uniform slot the interface or the host knows.
fn set_uniforms(eval: &mut Evaluator<f32>, program: &CpuProgram, surface: &SurfaceProgram, frame: &Frame) {
    set_spaces(eval, program, &frame.spaces);
    for (name, value) in &surface.uniforms {
        if program.slot(name).is_some_and(|id| program.slots().any(|(i, s)| i == id && s.uniform)) {
            let _ = eval.set(name, value);
        }
    }
    // Cs and Os are per-point inputs in RenderMan: a column of the object's colour is given at
    // evaluation; only uniform slots are set here.
    set_globals(eval, program, frame);
}

#[allow(clippy::too_many_arguments)]
fn shade_batch(
    frags: &Fragments,
    colors: &mut [[f32; 4]],
    carried: &[(Carried, usize, usize, bool)],
    fragment: &mut Evaluator<f32>,
    lights: &mut [Evaluator<f32>],
    prepared: &Prepared,
    surface: &SurfaceProgram,
    frame: &Frame,
    output: Output,
) -> Result<(), RenderError> {
    let n = frags.count;
    let stanford = surface.stages.fragment.stanford;
    let program = &surface.fragment;
    // Columns by slot name, point-major as the interpreter takes them.
    let mut columns: Vec<(String, Vec<f64>)> = Vec::new();
    // Component-major (the rasterizer's) to point-major (the interpreter's).
    let column = |offset: usize, width: usize, source: fn(&Fragments, usize) -> &[f32]| -> Vec<f64> {
        let mut col = vec![0f64; n * width];
        for c in 0..width {
            let values = source(frags, offset + c);
            for k in 0..n {
                col[k * width + c] = f64::from(values[k]);
            }
        }
        col
    };
    for (what, offset, width, _) in carried {
        let names = match what {
            Carried::Global(name, also) => std::iter::once(name).chain(also).collect(),
            Carried::Param(name) | Carried::Transfer(name) => vec![name],
        };
        for name in names {
            columns.push((name.clone(), column(*offset, *width, Fragments::values_of)));
            if !matches!(what, Carried::Transfer(_)) {
                // The derivative seeds: the rasterizer's analytic screen derivatives (seeds of a
                // float4 P are its xyz).
                let seed_width = if stanford && name == "P" { 3 } else { *width };
                columns.push((format!("dx({name})"), column(*offset, seed_width, Fragments::ddx_of)));
                columns.push((format!("dy({name})"), column(*offset, seed_width, Fragments::ddy_of)));
            }
        }
    }
    if program.slot(POINT_INDEX).is_some() {
        // What random() hashes: the pixel, as the GPU numbers it.
        let row = patina_compiler::backend::wgsl::RANDOM_ROW;
        let col = frags.pixels.iter().map(|(x, y)| f64::from(x + row * y)).collect();
        columns.push((POINT_INDEX.into(), col));
    }
    if program.slot("xyz_screen").is_some() {
        // The window position, as WGSL's fragment `position`: pixel centres, the depth, and
        // 1 / clip w, which the perspective depth d = a + b / w gives back as (d - a) / b.
        let (a, b) = (frame.camera_to_clip.z_axis.z, frame.camera_to_clip.w_axis.z);
        let col = (0..n)
            .flat_map(|k| {
                let (x, y) = frags.pixels[k];
                let d = frags.depth[k];
                [x as f32 + 0.5, y as f32 + 0.5, d, (d - a) / b].map(f64::from)
            })
            .collect();
        columns.push(("xyz_screen".into(), col));
    }
    for name in ["Cs", "Os"] {
        if let Some(c) = object_colour(frame, name)
            && !columns.iter().any(|(n, _)| n == name)
        {
            columns.push((name.into(), (0..n).flat_map(|_| c.iter().copied()).collect()));
        }
    }
    let get = |columns: &[(String, Vec<f64>)], name: &str| {
        columns.iter().find(|(n, _)| n == name).map(|(_, c)| c.clone())
    };
    if !stanford {
        // Ng from the screen derivatives of P, on the side of N; du, dv as |d/dx| + |d/dy|.
        if let (Some(dx), Some(dy), Some(nn)) =
            (get(&columns, "dx(P)"), get(&columns, "dy(P)"), get(&columns, "N"))
        {
            let mut ng = vec![0f64; n * 3];
            for k in 0..n {
                let v = |c: &[f64]| Vec3::new(c[k * 3] as f32, c[k * 3 + 1] as f32, c[k * 3 + 2] as f32);
                let c = v(&dy).cross(v(&dx));
                let c = c / c.length();
                let c = if c.dot(v(&nn)) >= 0.0 { c } else { -c };
                ng[k * 3..k * 3 + 3].copy_from_slice(&[f64::from(c.x), f64::from(c.y), f64::from(c.z)]);
            }
            columns.push(("Ng".into(), ng));
        }
        for (d, param) in [("du", "u"), ("dv", "v")] {
            if let (Some(dx), Some(dy)) =
                (get(&columns, &format!("dx({param})")), get(&columns, &format!("dy({param})")))
            {
                let col = (0..n).map(|k| f64::from((dx[k] as f32).abs() + (dy[k] as f32).abs())).collect();
                columns.push((d.into(), col));
            }
        }
    }
    // Displacement (bump mapping): the displacement program moves P and N for the surface.
    if let Some(d) = &surface.displacement {
        let mut e = Evaluator::<f32>::new(&d.cpu);
        set_spaces(&mut e, &d.cpu, &frame.spaces);
        for (name, value) in &d.values {
            let _ = e.set(name, value);
        }
        let inputs = varying_inputs(&d.cpu, &columns);
        let outputs: Vec<&str> = ["P", "N"].into_iter().filter(|name| d.cpu.slot(name).is_some()).collect();
        let moved = e.eval_points(n, &inputs, &outputs).map_err(|e| RenderError::Run(e.to_string()))?;
        for (name, value) in outputs.into_iter().zip(moved) {
            match columns.iter_mut().find(|(n, _)| n == name) {
                Some((_, c)) => *c = value,
                None => columns.push((name.into(), value)),
            }
        }
    }
    // The lights, at the surface point.
    let lit = light_columns(&columns, n, lights, prepared, surface)?;
    columns.extend(lit);
    let inputs = varying_inputs(program, &columns);
    let wanted: Vec<&str> = match output {
        Output::Result => vec!["result"],
        // With an atmosphere the interface's output is Ci and Oi whatever the surface writes.
        _ if surface.atmosphere.is_some() && program.slot("Oi").is_none() => vec!["Ci"],
        Output::CiOi => vec!["Ci", "Oi"],
        _ => vec!["Ci"],
    };
    // An atmosphere reads the surface's parameters with `surface` as the surface's body left them.
    let atmosphere_messages = match &surface.atmosphere {
        Some(a) => surface_messages(&a.cpu, surface),
        None => Vec::new(),
    };
    let shown = wanted.len();
    let mut wanted = wanted;
    wanted.extend(
        atmosphere_messages
            .iter()
            .filter(|(name, _, has)| *has && program.slot(name).is_some())
            .map(|(name, ..)| name.as_str()),
    );
    let mut outs = fragment.eval_points(n, &inputs, &wanted).map_err(|e| RenderError::Run(e.to_string()))?;
    let left: Vec<(String, Vec<f64>)> =
        wanted[shown..].iter().map(|name| surface_input(name)).zip(outs.split_off(shown)).collect();
    // The atmosphere, between the surface and the eye: on the surface's Ci and Oi (opaque when
    // the surface writes none), its own Ci and Oi are the fragment's.
    if let Some(a) = &surface.atmosphere {
        let oi = outs.get(1).cloned().unwrap_or_else(|| vec![1.0; n * 3]);
        let ci = outs[0].clone();
        let mut e = Evaluator::<f32>::new(&a.cpu);
        set_spaces(&mut e, &a.cpu, &frame.spaces);
        set_globals(&mut e, &a.cpu, frame);
        for (name, value) in &a.values {
            let _ = e.set(name, value);
        }
        set_surface_flags(&mut e, &a.cpu, surface);
        let mut messages: Vec<(String, Vec<f64>)> = atmosphere_messages
            .iter()
            .filter(|(name, ..)| !left.iter().any(|(input, _)| *input == surface_input(name)))
            .map(|(name, width, _)| (surface_input(name), uniform_column(surface, name, *width, n)))
            .collect();
        messages.extend(left);
        let varying =
            |name: &str| a.cpu.slot(name).is_some_and(|id| a.cpu.slots().any(|(i, s)| i == id && !s.uniform));
        let mut inputs: Vec<(&str, &[f64])> = columns
            .iter()
            .filter(|(name, _)| varying(name))
            .map(|(name, c)| (name.as_str(), c.as_slice()))
            .collect();
        for (name, c) in [("Ci", &ci), ("Oi", &oi)] {
            if varying(name) {
                inputs.push((name, c.as_slice()));
            }
        }
        inputs.extend(
            messages.iter().filter(|(name, _)| varying(name)).map(|(name, c)| (name.as_str(), c.as_slice())),
        );
        let names: Vec<&str> = ["Ci", "Oi"].into_iter().filter(|name| a.cpu.slot(name).is_some()).collect();
        let results = e.eval_points(n, &inputs, &names).map_err(|e| RenderError::Run(e.to_string()))?;
        let result = |name: &str| names.iter().position(|x| *x == name).map(|k| results[k].clone());
        outs = vec![result("Ci").unwrap_or(ci), result("Oi").unwrap_or(oi)];
    }
    for (k, color) in colors.iter_mut().enumerate() {
        *color = match output {
            Output::Result => {
                let r = &outs[0][k * 4..k * 4 + 4];
                [r[0] as f32, r[1] as f32, r[2] as f32, r[3] as f32]
            }
            _ => {
                let ci = &outs[0][k * 3..k * 3 + 3];
                let alpha = match outs.get(1) {
                    // The mean of Oi, as the GPU computes it: a dot product with 1/3.
                    Some(oi) => {
                        let third = 1.0f32 / 3.0;
                        oi[k * 3] as f32 * third + oi[k * 3 + 1] as f32 * third + oi[k * 3 + 2] as f32 * third
                    }
                    None => 1.0,
                };
                [ci[0] as f32, ci[1] as f32, ci[2] as f32, alpha]
            }
        };
    }
    Ok(())
}

/// The surface point the lights are evaluated at, one column per value, point-major: `P` as a
/// 3-vector in either style, the surface's own columns (`N`, `E`, Stanford's `Pobj`, ...).
struct SurfacePoint<'c> {
    n: usize,
    p: Vec<f64>,
    columns: &'c [(String, Vec<f64>)],
    stanford: bool,
}

impl<'c> SurfacePoint<'c> {
    /// The surface point of `n` points given by `columns`, of a surface of the given style.
    fn new(n: usize, columns: &'c [(String, Vec<f64>)], stanford: bool) -> Self {
        let mut point = SurfacePoint { n, p: Vec::new(), columns, stanford };
        point.p = match point.column("P") {
            // Stanford's P is a float4 with w = 1.
            Some(p) if stanford => p.chunks(4).flat_map(|xyzw| xyzw[..3].to_vec()).collect(),
            Some(p) => p.to_vec(),
            None => vec![0.0; n * 3],
        };
        point
    }

    /// The surface's column `name`, if it has one.
    fn column(&self, name: &str) -> Option<&[f64]> {
        self.columns.iter().find(|(c, _)| c == name).map(|(_, c)| c.as_slice())
    }

    /// A surface column, or zeros of `width` when the surface has none.
    fn column_or_zero(&self, name: &str, width: usize) -> Vec<f64> {
        self.column(name).map_or_else(|| vec![0.0; self.n * width], <[f64]>::to_vec)
    }
}

/// What a light delivers to the surface, per point: the vector from the point towards the light
/// (not normalized; RenderMan's `-L`), its colour (a RenderMan light's `Cl`, three wide; a
/// Stanford light's returned float4, four wide), and its variables the surface reads with
/// `lightsource`, in the order asked for.
struct Arrival {
    toward: Vec<f64>,
    cl: Vec<f64>,
    read_back: Vec<Vec<f64>>,
}

/// Runs each bound light's program at the surface point and returns the columns the surface
/// reads of them: `L[k]`, `Cl[k]` (and a Stanford surface's `H[k]`) in the surface's style, and
/// `lightsource(name)[k]`. The WGSL backend's fragment entry point computes the same
/// (`entry/fragment.rs`, "The lights, evaluated at the surface point").
fn light_columns(
    columns: &[(String, Vec<f64>)],
    n: usize,
    lights: &mut [Evaluator<f32>],
    prepared: &Prepared,
    surface: &SurfaceProgram,
) -> Result<Vec<(String, Vec<f64>)>, RenderError> {
    let stanford = surface.stages.fragment.stanford;
    let program = &surface.fragment;
    let point = SurfacePoint::new(n, columns, stanford);
    let mut out = Vec::new();
    for (k, light) in lights.iter_mut().enumerate() {
        let lp = &prepared.lights[k];
        // The surface's parameters the light reads with `surface`: as the fragment stage reads
        // them (a varying column, or the uniform value).
        let messages: Vec<(String, Vec<f64>)> = surface_messages(&lp.cpu, surface)
            .into_iter()
            .map(|(name, width, has)| {
                let column = match point.column(&name) {
                    Some(c) if has => c.to_vec(),
                    _ => uniform_column(surface, &name, width, n),
                };
                (surface_input(&name), column)
            })
            .collect();
        // The light's parameters the surface reads with `lightsource`: from the light's program
        // after it ran when it has them as variables, else their bound values.
        let lightsource: Vec<(String, &str)> = lp
            .loaded
            .shader
            .params
            .iter()
            .map(|p| lp.loaded.shader.local(*p).name.as_str())
            .map(|name| (lightsource_input(name, k), name))
            .filter(|(input, _)| program.slot(input).is_some())
            .collect();
        let read_back: Vec<&str> =
            lightsource.iter().map(|(_, name)| *name).filter(|name| lp.cpu.slot(name).is_some()).collect();
        let arrival = if lp.loaded.shader.stanford {
            stanford_light(light, lp, k, &point, &messages, &read_back)?
        } else {
            renderman_light(light, lp, &point, &messages, &read_back)?
        };
        for (input, name) in &lightsource {
            let column = match read_back.iter().position(|r| r == name) {
                Some(at) => arrival.read_back[at].clone(),
                None => broadcast(&lp.values, name, n).unwrap_or_default(),
            };
            out.push((input.clone(), column));
        }
        out.extend(surface_light_values(k, lp.loaded.shader.stanford, arrival, &point));
    }
    Ok(out)
}

/// The columns among `offered` that `program` takes per point: those named like its varying slots.
fn varying_inputs<'v>(program: &CpuProgram, offered: &'v [(String, Vec<f64>)]) -> Vec<(&'v str, &'v [f64])> {
    offered
        .iter()
        .filter(|(name, _)| {
            program.slot(name).is_some_and(|id| program.slots().any(|(i, s)| i == id && !s.uniform))
        })
        .map(|(name, c)| (name.as_str(), c.as_slice()))
        .collect()
}

/// Runs a RenderMan-style light at the surface point (`Ps` = `P`) and reads what it emitted.
fn renderman_light(
    light: &mut Evaluator<f32>,
    lp: &LightProgram,
    point: &SurfacePoint,
    messages: &[(String, Vec<f64>)],
    read_back: &[&str],
) -> Result<Arrival, RenderError> {
    let n = point.n;
    let nn = point.column_or_zero("N", 3);
    let mut offered: Vec<(String, Vec<f64>)> =
        vec![("Ps".into(), point.p.clone()), ("P".into(), point.p.clone()), ("N".into(), nn)];
    offered.extend_from_slice(messages);
    // A light that never sets `L` (an ambient light without `solar` or `illuminate`) leaves
    // it zero, as on the GPU.
    let has_l = lp.cpu.slot("L").is_some();
    let wanted: Vec<&str> = if has_l { vec!["L", "Cl"] } else { vec!["Cl"] }
        .into_iter()
        .chain(read_back.iter().copied())
        .collect();
    let mut outs = light
        .eval_points(n, &varying_inputs(&lp.cpu, &offered), &wanted)
        .map_err(|e| RenderError::Run(e.to_string()))?;
    if !has_l {
        outs.insert(0, vec![0.0; n * 3]);
    }
    let read_back = outs.split_off(2);
    let cl = outs.pop().unwrap_or_default();
    // The light's L runs from the light to the point.
    let toward = outs.pop().unwrap_or_default().iter().map(|x| -x).collect();
    Ok(Arrival { toward, cl, read_back })
}

/// Runs Stanford-style light `k` at the surface point and reads the colour it returned: its `L`
/// (towards the light, normalized) and `Sdist` come from the light's position, its other inputs
/// from the surface (a Stanford surface's own columns; a RenderMan surface's `P` with w = 1, `N`
/// normalized and `E` = normalize(-P)).
fn stanford_light(
    light: &mut Evaluator<f32>,
    lp: &LightProgram,
    k: usize,
    point: &SurfacePoint,
    messages: &[(String, Vec<f64>)],
    read_back: &[&str],
) -> Result<Arrival, RenderError> {
    let n = point.n;
    let position = lp.position.ok_or_else(|| {
        RenderError::Run(format!("internal error: Stanford-style light {k} has no position"))
    })?;
    let (mut toward, mut l, mut sdist) = (Vec::with_capacity(n * 3), Vec::with_capacity(n * 3), Vec::new());
    for i in 0..n {
        let v = position - vec3(&point.p, i);
        let d = v.length();
        push3(&mut toward, v);
        push3(&mut l, v / d);
        sdist.push(f64::from(d));
    }
    let mut offered: Vec<(String, Vec<f64>)> = vec![("L".into(), l), ("Sdist".into(), sdist)];
    if point.stanford {
        // The surface's inputs of the names of the light's own predefined variables (not its
        // derivative seeds, which no light is given on either backend).
        let light_input = |name: &str| {
            !matches!(name, "L" | "Sdist") && globals::lookup(name, ShaderKind::Light, true).is_some()
        };
        offered.extend(point.columns.iter().filter(|(name, _)| light_input(name)).cloned());
    } else {
        let nn = point.column_or_zero("N", 3);
        let (mut p4, mut unit_n, mut e) = (Vec::with_capacity(n * 4), Vec::new(), Vec::new());
        for i in 0..n {
            let p = vec3(&point.p, i);
            p4.extend([p.x, p.y, p.z, 1.0].map(f64::from));
            let nv = vec3(&nn, i);
            push3(&mut unit_n, nv / nv.length());
            push3(&mut e, -p / (-p).length());
        }
        offered.extend([("P".into(), p4), ("N".into(), unit_n), ("E".into(), e)]);
    }
    offered.extend_from_slice(messages);
    let wanted: Vec<&str> = std::iter::once("result").chain(read_back.iter().copied()).collect();
    let mut outs = light
        .eval_points(n, &varying_inputs(&lp.cpu, &offered), &wanted)
        .map_err(|e| RenderError::Run(e.to_string()))?;
    let read_back = outs.split_off(1);
    let cl = outs.pop().unwrap_or_default();
    Ok(Arrival { toward, cl, read_back })
}

/// Light `k`'s values in the surface's style: a RenderMan surface sees `L` from the point towards
/// the light (not normalized) and `Cl` as a colour (a Stanford light's rgb); a Stanford surface
/// sees `L` normalized, the half-angle vector `H` of `L` and `E`, and `Cl` as a float4 (a
/// RenderMan light's colour with alpha 1).
fn surface_light_values(
    k: usize,
    light_stanford: bool,
    arrival: Arrival,
    point: &SurfacePoint,
) -> Vec<(String, Vec<f64>)> {
    let n = point.n;
    let Arrival { toward, cl, .. } = arrival;
    if !point.stanford {
        let cl =
            if light_stanford { (0..n).flat_map(|i| cl[i * 4..i * 4 + 3].to_vec()).collect() } else { cl };
        return vec![(format!("Cl[{k}]"), cl), (format!("L[{k}]"), toward)];
    }
    let e = point.column("E");
    let (mut l, mut h) = (Vec::with_capacity(n * 3), vec![0f64; n * 3]);
    for i in 0..n {
        let lv = vec3(&toward, i);
        let lv = lv / lv.length();
        push3(&mut l, lv);
        if let Some(e) = e {
            let sum = lv + vec3(e, i);
            let hv = sum / sum.length();
            h[i * 3..i * 3 + 3].copy_from_slice(&hv.to_array().map(f64::from));
        }
    }
    let cl = if light_stanford {
        cl
    } else {
        (0..n).flat_map(|i| [cl[i * 3], cl[i * 3 + 1], cl[i * 3 + 2], 1.0]).collect()
    };
    vec![(format!("H[{k}]"), h), (format!("Cl[{k}]"), cl), (format!("L[{k}]"), l)]
}

/// Point `i` of a column of 3-vectors, as the f32 values the interpreter holds.
fn vec3(column: &[f64], i: usize) -> Vec3 {
    Vec3::new(column[i * 3] as f32, column[i * 3 + 1] as f32, column[i * 3 + 2] as f32)
}

/// Appends a 3-vector to a point-major column.
fn push3(column: &mut Vec<f64>, v: Vec3) {
    column.extend(v.to_array().map(f64::from));
}

/// The object's `Cs` or `Os` (per-point inputs of the interpreter, uniforms on the GPU).
fn object_colour(frame: &Frame, name: &str) -> Option<Vec<f64>> {
    let c = match name {
        "Cs" => frame.color,
        "Os" => frame.opacity,
        _ => return None,
    };
    Some(c.iter().map(|x| f64::from(*x)).collect())
}

/// The surface parameters `reader` (a light's or an atmosphere's program) reads with
/// `surface("name", v)`: each name, the width of the value it reads, and whether the object's
/// surface has a parameter of that name and type (the GPU module decides the same when it is
/// compiled).
fn surface_messages(reader: &CpuProgram, surface: &SurfaceProgram) -> Vec<(String, usize, bool)> {
    let shader = &surface.loaded.shader;
    reader
        .slots()
        .filter_map(|(_, s)| {
            let name = s.name.strip_prefix("surface(")?.strip_suffix(')')?;
            let has = shader.params.iter().map(|p| shader.local(*p)).any(|l| l.name == name && l.ty == s.ty);
            Some((name.to_string(), s.width, has))
        })
        .collect()
}

/// Tells `reader` which of the surface parameters it reads with `surface` the object's surface has.
fn set_surface_flags(eval: &mut Evaluator<f32>, reader: &CpuProgram, surface: &SurfaceProgram) {
    for (name, _, has) in surface_messages(reader, surface) {
        // Only names the program reads are set, so this cannot fail.
        let _ = eval.set(&surface_flag_input(&name), &[f64::from(u8::from(has))]);
    }
}

/// A surface parameter's per-draw value (what the host computed, as the GPU's uniform block
/// holds it) for each of `n` points; zeros where the surface has none of that width.
fn uniform_column(surface: &SurfaceProgram, name: &str, width: usize, n: usize) -> Vec<f64> {
    broadcast(&surface.uniforms, name, n)
        .filter(|c| c.len() == width * n)
        .unwrap_or_else(|| vec![0.0; n * width])
}

/// The value named `name` among `values` repeated for each of `n` points.
fn broadcast(values: &[(String, Vec<f64>)], name: &str, n: usize) -> Option<Vec<f64>> {
    let (_, v) = values.iter().find(|(v, _)| v == name)?;
    Some((0..n).flat_map(|_| v.iter().copied()).collect())
}

/// Gives a stage program the object's textures it reads.
fn bind_textures(eval: &mut Evaluator<f32>, program: &CpuProgram, object: &Object) {
    for (name, texture) in &object.textures {
        if program.textures().contains(name) {
            // Only names the program reads are offered, so this cannot fail.
            let _ = eval.set_texture(name, texture.clone());
        }
    }
}
