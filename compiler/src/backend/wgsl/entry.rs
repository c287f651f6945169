//! The entry points: the vertex stage's geometry (predefined variables from the mesh's attributes
//! and the uniform block), the varyings, the fragment stage's derivative seeds and lights, and
//! the output. The CPU reference renderer (`patina-runtime`) computes the same inputs by the same
//! formulas; `docs/numerics.md` lists them.

use naga::{
    Binding, BuiltIn, Expression, FunctionArgument, FunctionResult, Handle, Interpolation, Sampling,
    ShaderStage, Span, Statement, StructMember, TypeInner,
};

use super::body::{Translator, Value};
use super::func::FnBuilder;
use super::interface::{Attribute, GeometryMatrix, UniformSource, Varying};
use super::module::{ModuleBuilder, sanitize};
use super::uses::Uses;
use crate::ir::types::{Base, Frequency, Type};
use crate::ir::{Axis, Input, LocalKind, Shader};
use crate::split::{StageKind, Stages};

/// The name of the private variable holding a derivative seed.
pub(crate) fn seed_name(shader: &Shader, input: Input, axis: Axis) -> String {
    let name = match input {
        Input::Global(g) => g.name.to_string(),
        Input::Param(l) => shader.local(l).name.to_string(),
    };
    let axis = match axis {
        Axis::X => "dx",
        Axis::Y => "dy",
    };
    format!("{axis}_{}", sanitize(&name))
}

/// The private variable holding the fragment's window position (`xyz_screen`): x and y in pixels
/// (pixel centres at +0.5), z the depth, w = 1 / clip w.
pub(crate) const SCREEN_POSITION: &str = "xyz_screen";

/// Pixels per row in the point index `random()` hashes in rendering: the fragment at pixel (x, y)
/// is point x + 4096 y (below 2^24, so the interpreter's f32 inputs carry it exactly).
pub const RANDOM_ROW: u32 = 4096;

/// The mesh attributes every vertex stage takes, at locations 0 to 4.
pub(crate) const GEOMETRY_ATTRIBUTES: [(&str, u32); 5] =
    [("P", 3), ("N", 3), ("uv", 2), ("dPdu", 3), ("dPdv", 3)];

/// A value that crosses from the vertex to the fragment stage.
pub(crate) struct Crossing {
    pub name: String,
    pub ty: Type,
    /// What fills it in the vertex stage and what it fills in the fragment stage.
    pub what: Carried,
}

/// What a varying carries.
#[derive(Clone, Copy)]
pub(crate) enum Carried {
    /// A predefined variable's value on entry to the vertex stage.
    Global(&'static crate::sema::globals::Global),
    /// A vertex-rate parameter's value on entry.
    Param(crate::ir::LocalId),
    /// A transfer computed by the vertex stage.
    Transfer(crate::ir::LocalId),
}

/// Builds both entry points; returns the attributes and varyings.
pub(crate) fn entry_points(
    mb: &mut ModuleBuilder,
    stages: &Stages,
    vertex_body: Handle<naga::Function>,
    fragment_body: Handle<naga::Function>,
    lights: &[(Handle<naga::Function>, &Shader)],
    displacement: Option<(Handle<naga::Function>, &Shader)>,
    strings: &[(String, String)],
) -> (Vec<Attribute>, Vec<Varying>) {
    let vertex_uses = Uses::of(&stages.vertex, &stages.vertex.body);
    let fragment_uses = Uses::of(&stages.fragment, &stages.fragment.body);
    let surface = &stages.fragment;

    // What crosses: vertex-rate inputs the fragment stage reads, and the vertex stage's transfers.
    let mut crossings: Vec<Crossing> = Vec::new();
    // Lights are evaluated at the surface point and orientation, and Stanford's H needs E.
    let mut carried_globals = fragment_uses.globals.clone();
    // A displacement shader runs at the top of the fragment stage on the surface's inputs.
    if let Some((_, d)) = displacement {
        for g in Uses::of(d, &d.body).globals {
            if let Some(sg) = crate::sema::globals::lookup(g.name, surface.kind, surface.stanford)
                && !carried_globals.iter().any(|c| c.name == sg.name)
            {
                carried_globals.push(sg);
            }
        }
    }
    // Ng is computed from P's derivatives, oriented by N.
    if !lights.is_empty() || fragment_uses.has_global("Ng") {
        for name in ["P", "N", "E"] {
            if let Some(g) = crate::sema::globals::lookup(name, surface.kind, surface.stanford)
                && !carried_globals.iter().any(|c| c.name == name)
            {
                carried_globals.push(g);
            }
        }
    }
    for g in &carried_globals {
        if g.frequency == Frequency::Vertex && !g.perlight {
            crossings.push(Crossing {
                name: format!("in_{}", sanitize(g.name)),
                ty: Type::of(g.ty),
                what: Carried::Global(g),
            });
        }
    }
    for &l in &surface.params {
        let local = surface.local(l);
        let is_transfer = stages.transfers.iter().any(|t| t.local == l);
        if !is_transfer
            && fragment_uses.locals.contains(&l)
            && local.rate.frequency == Frequency::Vertex
            && carries(local.ty)
        {
            crossings.push(Crossing {
                name: format!("in_{}", sanitize(&local.name)),
                ty: local.ty,
                what: Carried::Param(l),
            });
        }
    }
    for t in stages.transfers.iter().filter(|t| t.from == StageKind::Vertex && t.to_fragment) {
        crossings.push(Crossing { name: t.name.to_string(), ty: t.ty, what: Carried::Transfer(t.local) });
    }

    // Vertex attributes: the geometry, then vertex-rate parameters.
    let mut attributes: Vec<Attribute> = GEOMETRY_ATTRIBUTES
        .iter()
        .enumerate()
        .map(|(i, (n, c))| Attribute { name: n.to_string(), location: i as u32, components: *c })
        .collect();
    let vertex_params: Vec<crate::ir::LocalId> = surface
        .params
        .iter()
        .copied()
        .filter(|l| {
            let local = surface.local(*l);
            local.rate.frequency == Frequency::Vertex
                && carries(local.ty)
                && !stages.transfers.iter().any(|t| t.local == *l)
                && (vertex_uses.locals.contains(l) || fragment_uses.locals.contains(l))
        })
        .collect();
    for l in &vertex_params {
        let local = surface.local(*l);
        attributes.push(Attribute {
            name: local.name.to_string(),
            location: attributes.len() as u32,
            components: local.ty.base.components(),
        });
    }

    let varyings = vertex_entry(
        mb,
        stages,
        vertex_body,
        &vertex_uses,
        &fragment_uses,
        &crossings,
        &attributes,
        &vertex_params,
        strings,
    );
    fragment_entry(mb, stages, fragment_body, &fragment_uses, &crossings, lights, displacement, strings);
    (attributes, varyings)
}

/// Whether values of this type can be attributes or varyings.
fn carries(ty: Type) -> bool {
    !ty.is_array() && matches!(ty.base.components(), 1..=4) && !matches!(ty.base, Base::String | Base::Texref)
}

/// The naga type a varying of language type `ty` travels as (booleans as `u32`).
fn varying_type(mb: &mut ModuleBuilder, ty: Type) -> Handle<naga::Type> {
    if ty.base == Base::Bool { mb.ty(Type::of(Base::Uint), false) } else { mb.ty(ty, false) }
}

/// The binding of a varying: perspective-correct, or flat for integers and booleans.
fn location(location: u32, ty: Type) -> Binding {
    let flat = matches!(ty.base, Base::Bool | Base::Int | Base::Uint);
    Binding::Location {
        location,
        interpolation: Some(if flat { Interpolation::Flat } else { Interpolation::Perspective }),
        sampling: if flat { None } else { Some(Sampling::Center) },
        blend_src: None,
        per_primitive: false,
    }
}

/// The binding of a vertex attribute or a fragment output (no interpolation).
fn plain(location: u32) -> Binding {
    Binding::Location { location, interpolation: None, sampling: None, blend_src: None, per_primitive: false }
}

#[allow(clippy::too_many_arguments)]
fn vertex_entry(
    mb: &mut ModuleBuilder,
    stages: &Stages,
    body: Handle<naga::Function>,
    uses: &Uses,
    fragment_uses: &Uses,
    crossings: &[Crossing],
    attributes: &[Attribute],
    vertex_params: &[crate::ir::LocalId],
    strings: &[(String, String)],
) -> Vec<Varying> {
    let shader = &stages.vertex;
    let mut t = Translator::new(mb, shader, "", &[], strings, "vs_main");
    let mut args = Vec::new();
    for a in attributes {
        let ty = t.mb.ty(
            Type::of(match a.components {
                1 => Base::Float,
                2 => Base::Float4, // replaced below
                3 => Base::Float3,
                _ => Base::Float4,
            }),
            false,
        );
        let ty = if a.components == 2 {
            t.mb.inner(TypeInner::Vector { size: naga::VectorSize::Bi, scalar: naga::Scalar::F32 })
        } else {
            ty
        };
        t.fb.f.arguments.push(FunctionArgument {
            name: Some(format!("a_{}", sanitize(&a.name))),
            ty,
            binding: Some(plain(a.location)),
        });
        args.push(t.fb.add(Expression::FunctionArgument(args.len() as u32)));
    }

    // The geometry: predefined variables the stages read, in camera ("current") space.
    let oc = t.uniform_value(
        "object_to_camera",
        Type::of(Base::Matrix4),
        UniformSource::Geometry { matrix: GeometryMatrix::ObjectToCamera },
    );
    let p_cam = t.transform_by(oc, args[0], 1.0);
    let carried =
        |name: &str| crossings.iter().any(|c| matches!(c.what, Carried::Global(g) if g.name == name));
    let needed = |name: &str| uses.has_global(name) || fragment_uses.has_global(name) || carried(name);
    let stanford = shader.stanford;
    let set = |t: &mut Translator, name: &str, value: Value| {
        if let Some(g) = crate::sema::globals::lookup(name, shader.kind, stanford) {
            let var = t.global_var(g.name, Type::of(g.ty), false);
            let p = t.pointer(var);
            t.store(p, value);
        }
    };
    let nc = t.uniform_value(
        "normal_to_camera",
        Type::of(Base::Matrix4),
        UniformSource::Geometry { matrix: GeometryMatrix::NormalToCamera },
    );
    let n_cam = t.transform_by(nc, args[1], 0.0);
    let u = t.fb.add(Expression::AccessIndex { base: args[2], index: 0 });
    let v = t.fb.add(Expression::AccessIndex { base: args[2], index: 1 });
    let dpdu = t.transform_by(oc, args[3], 0.0);
    let dpdv = t.transform_by(oc, args[4], 0.0);
    if stanford {
        let one = t.float(1.0);
        let f4 = t.mb.ty(Type::of(Base::Float4), false);
        let p4 = t.fb.add(Expression::Compose { ty: f4, components: vec![p_cam, one] });
        let pobj = t.fb.add(Expression::Compose { ty: f4, components: vec![args[0], one] });
        let n = t.normalize(n_cam);
        let tangent = t.normalize(dpdu);
        let b = t.math2(naga::MathFunction::Cross, n, tangent);
        let minus_p = t.fb.add(Expression::Unary { op: naga::UnaryOperator::Negate, expr: p_cam });
        let e = t.normalize(minus_p);
        for (name, value) in [
            ("P", p4),
            ("Pobj", pobj),
            ("N", n),
            ("T", tangent),
            ("B", b),
            ("E", e),
            ("__position", pobj),
            ("__normal", args[1]),
            ("__objnormal", args[1]),
        ] {
            if needed(name) {
                set(&mut t, name, value);
            }
        }
    } else {
        let zero = t.float(0.0);
        let origin = t.splat(zero, 3);
        for (name, value) in [
            ("P", p_cam),
            ("N", n_cam),
            ("Ng", n_cam),
            ("I", p_cam),
            ("E", origin),
            ("u", u),
            ("v", v),
            ("s", u),
            ("t", v),
            ("dPdu", dpdu),
            ("dPdv", dpdv),
            ("dPdtime", origin),
        ] {
            if needed(name) {
                set(&mut t, name, value);
            }
        }
    }
    init_uniform_inputs(&mut t, shader, uses, StageKind::Vertex, stages);
    for (k, l) in vertex_params.iter().enumerate() {
        let var = t.local_var(*l);
        let p = t.pointer(var);
        let value = args[GEOMETRY_ATTRIBUTES.len() + k];
        t.store(p, value);
    }

    // The fragment stage's raw inputs are the values on entry, before the body runs.
    let mut carried = Vec::new();
    for c in crossings {
        let value = match c.what {
            Carried::Global(g) => {
                let var = t.global_var(g.name, Type::of(g.ty), false);
                let p = t.pointer(var);
                Some(t.load(p))
            }
            Carried::Param(l) => {
                let var = t.local_var(l);
                let p = t.pointer(var);
                Some(t.load(p))
            }
            Carried::Transfer(_) => None,
        };
        carried.push(value);
    }
    t.fb.push(Statement::Call { function: body, arguments: Vec::new(), result: None });
    for (c, value) in crossings.iter().zip(carried.iter_mut()) {
        if let Carried::Transfer(l) = c.what {
            let var = t.local_var(l);
            let p = t.pointer(var);
            *value = Some(t.load(p));
        }
    }

    // Position: the (possibly displaced) surface point, projected.
    let p_final = match crate::sema::globals::lookup("P", shader.kind, stanford) {
        Some(g) if uses.written.contains("P") => {
            let var = t.global_var(g.name, Type::of(g.ty), false);
            let p = t.pointer(var);
            let v = t.load(p);
            if stanford { t.xyz(v) } else { v }
        }
        _ => p_cam,
    };
    let cc = t.uniform_value(
        "camera_to_clip",
        Type::of(Base::Matrix4),
        UniformSource::Geometry { matrix: GeometryMatrix::CameraToClip },
    );
    let one = t.float(1.0);
    let f4 = t.mb.ty(Type::of(Base::Float4), false);
    let p4 = t.fb.add(Expression::Compose { ty: f4, components: vec![p_final, one] });
    let clip = t.binary(naga::BinaryOperator::Multiply, cc, p4);

    let mut members = vec![StructMember {
        name: Some("position".into()),
        ty: f4,
        binding: Some(Binding::BuiltIn(BuiltIn::Position { invariant: false })),
        offset: 0,
    }];
    let mut components = vec![clip];
    let mut varyings = Vec::new();
    for (k, (c, value)) in crossings.iter().zip(carried).enumerate() {
        let ty = varying_type(t.mb, c.ty);
        let value = value.expect("every crossing has a value");
        let value = if c.ty.base == Base::Bool {
            t.fb.add(Expression::As { expr: value, kind: naga::ScalarKind::Uint, convert: Some(4) })
        } else {
            value
        };
        members.push(StructMember {
            name: Some(c.name.clone()),
            ty,
            binding: Some(location(k as u32, c.ty)),
            offset: 0,
        });
        components.push(value);
        varyings.push(Varying {
            name: c.name.clone(),
            location: k as u32,
            components: c.ty.base.components(),
            flat: matches!(c.ty.base, Base::Bool | Base::Int | Base::Uint),
        });
    }
    let span = lay_out(t.mb, &mut members);
    let out_ty = t.mb.module.types.insert(
        naga::Type { name: Some("VertexOutput".into()), inner: TypeInner::Struct { members, span } },
        Span::UNDEFINED,
    );
    let out = t.fb.add(Expression::Compose { ty: out_ty, components });
    t.fb.push(Statement::Return { value: Some(out) });
    let mut f = std::mem::replace(&mut t.fb, FnBuilder::new("")).finish();
    f.result = Some(FunctionResult { ty: out_ty, binding: None });
    drop(t);
    mb.module.entry_points.push(super::module::entry_point("vs_main", ShaderStage::Vertex, [0, 0, 0], f));
    varyings
}

/// Gives struct members increasing, aligned offsets (naga checks them on every struct); returns
/// the struct's size.
fn lay_out(mb: &mut ModuleBuilder, members: &mut [StructMember]) -> u32 {
    let mut layouter = naga::proc::Layouter::default();
    if layouter.update(mb.module.to_ctx()).is_err() {
        return 0;
    }
    let mut offset = 0;
    let mut align = naga::proc::Alignment::ONE;
    for m in members.iter_mut() {
        let l = layouter[m.ty];
        offset = l.alignment.round_up(offset);
        m.offset = offset;
        offset += l.size;
        align = align.max(l.alignment);
    }
    align.round_up(offset)
}

/// Uniform-rate inputs of a stage from the uniform block: parameters, host transfers and
/// predefined variables.
fn init_uniform_inputs(t: &mut Translator, shader: &Shader, uses: &Uses, stage: StageKind, stages: &Stages) {
    for &l in &shader.params {
        if !uses.locals.contains(&l) {
            continue;
        }
        let local = shader.local(l);
        if matches!(local.ty.base, Base::String | Base::Texref)
            || local.rate.frequency > Frequency::PrimitiveGroup
        {
            continue;
        }
        let source = match stages.transfers.iter().find(|tr| tr.local == l) {
            Some(tr) if tr.from == StageKind::Host && tr.from < stage => {
                UniformSource::Host { name: tr.name.to_string() }
            }
            Some(_) => continue,
            None => {
                if let LocalKind::Param { output: true, .. } = local.kind {
                    continue;
                }
                UniformSource::Param { name: local.name.to_string() }
            }
        };
        let var = t.local_var(l);
        let value = uniform_input(t, &local.name, local.ty, source);
        let p = t.pointer(var);
        t.store(p, value);
    }
    for g in &uses.globals {
        if g.frequency <= Frequency::PrimitiveGroup && g.name != "PI" && g.name != "ncomps" && g.name != "E" {
            let var = t.global_var(g.name, Type::of(g.ty), false);
            let value =
                uniform_input(t, g.name, Type::of(g.ty), UniformSource::Global { name: g.name.to_string() });
            let p = t.pointer(var);
            t.store(p, value);
        }
        if !t.shader.stanford && matches!(g.name, "Cs" | "Os") {
            let var = t.global_var(g.name, Type::of(g.ty), false);
            let value =
                uniform_input(t, g.name, Type::of(g.ty), UniformSource::Global { name: g.name.to_string() });
            let p = t.pointer(var);
            t.store(p, value);
        }
    }
    for (name, value) in [("PI", std::f64::consts::PI), ("ncomps", 3.0)] {
        if uses.has_global(name) {
            let var = t.global_var(name, Type::FLOAT, false);
            let v = t.float(value);
            let p = t.pointer(var);
            t.store(p, v);
        }
    }
}

/// A value read from the uniform block in the language's form (booleans from `u32`, arrays
/// unpadded element by element).
fn uniform_input(t: &mut Translator, name: &str, ty: Type, source: UniformSource) -> Value {
    let raw = t.uniform_value(name, ty, source);
    if let Some(n) = ty.array {
        let element = Type::of(ty.base);
        let padded = ty.base.components() < 4 && !matches!(ty.base, Base::Matrix3 | Base::Matrix4);
        let parts: Vec<Value> = (0..n)
            .map(|i| {
                let e = t.fb.add(Expression::AccessIndex { base: raw, index: i });
                if !padded {
                    return e;
                }
                match element.base.components() {
                    3 => t.xyz(e),
                    _ => {
                        let x = t.fb.add(Expression::AccessIndex { base: e, index: 0 });
                        if element.base == Base::Bool {
                            let zero = t.fb.add(Expression::Literal(naga::Literal::U32(0)));
                            t.binary(naga::BinaryOperator::NotEqual, x, zero)
                        } else {
                            x
                        }
                    }
                }
            })
            .collect();
        let ty_h = t.mb.ty(ty, false);
        return t.fb.add(Expression::Compose { ty: ty_h, components: parts });
    }
    if ty.base == Base::Bool {
        let zero = t.fb.add(Expression::Literal(naga::Literal::U32(0)));
        return t.binary(naga::BinaryOperator::NotEqual, raw, zero);
    }
    raw
}

#[allow(clippy::too_many_arguments)]
fn fragment_entry(
    mb: &mut ModuleBuilder,
    stages: &Stages,
    body: Handle<naga::Function>,
    uses: &Uses,
    crossings: &[Crossing],
    lights: &[(Handle<naga::Function>, &Shader)],
    displacement: Option<(Handle<naga::Function>, &Shader)>,
    strings: &[(String, String)],
) {
    let shader = &stages.fragment;
    let mut t = Translator::new(mb, shader, "", &[], strings, "fs_main");
    let f4 = t.mb.ty(Type::of(Base::Float4), false);
    t.fb.f.arguments.push(FunctionArgument {
        name: Some("position".into()),
        ty: f4,
        binding: Some(Binding::BuiltIn(BuiltIn::Position { invariant: false })),
    });
    let position = t.fb.add(Expression::FunctionArgument(0));
    if uses.screen {
        let var = t.mb.private(SCREEN_POSITION, Type::of(Base::Float4));
        let p = t.pointer(var);
        t.store(p, position);
    }
    if uses.random {
        let coord = |t: &mut Translator, i: u32| {
            let c = t.fb.add(Expression::AccessIndex { base: position, index: i });
            t.fb.add(Expression::As { expr: c, kind: naga::ScalarKind::Uint, convert: Some(4) })
        };
        let (x, y) = (coord(&mut t, 0), coord(&mut t, 1));
        let row = t.fb.add(Expression::Literal(naga::Literal::U32(RANDOM_ROW)));
        let y = t.binary(naga::BinaryOperator::Multiply, y, row);
        let point = t.binary(naga::BinaryOperator::Add, x, y);
        let var = t.mb.private(crate::backend::cpu::POINT_INDEX, Type::of(Base::Uint));
        let p = t.pointer(var);
        t.store(p, point);
    }
    for (k, c) in crossings.iter().enumerate() {
        let ty = varying_type(t.mb, c.ty);
        t.fb.f.arguments.push(FunctionArgument {
            name: Some(c.name.clone()),
            ty,
            binding: Some(location(k as u32, c.ty)),
        });
        let arg = t.fb.add(Expression::FunctionArgument(k as u32 + 1));
        let value = if c.ty.base == Base::Bool {
            let zero = t.fb.add(Expression::Literal(naga::Literal::U32(0)));
            t.binary(naga::BinaryOperator::NotEqual, arg, zero)
        } else {
            arg
        };
        let var = match c.what {
            Carried::Global(g) => t.global_var(g.name, Type::of(g.ty), false),
            Carried::Param(l) | Carried::Transfer(l) => t.local_var(l),
        };
        let p = t.pointer(var);
        t.store(p, value);
    }
    if !shader.stanford && uses.has_global("E") {
        let var = t.global_var("E", Type::of(Base::Point), false);
        let zero = t.float(0.0);
        let origin = t.splat(zero, 3);
        let p = t.pointer(var);
        t.store(p, origin);
    }
    init_uniform_inputs(&mut t, shader, uses, StageKind::Fragment, stages);

    // Screen derivatives, here at the top where control flow is uniform.
    let derivative = |t: &mut Translator, axis: Axis, v: Value| {
        let axis = match axis {
            Axis::X => naga::DerivativeAxis::X,
            Axis::Y => naga::DerivativeAxis::Y,
        };
        t.fb.add(Expression::Derivative { axis, ctrl: naga::DerivativeControl::None, expr: v })
    };
    let read_global = |t: &mut Translator, name: &str| -> Option<Value> {
        let g = crate::sema::globals::lookup(name, shader.kind, shader.stanford)?;
        let var = t.global_var(g.name, Type::of(g.ty), false);
        let p = t.pointer(var);
        Some(t.load(p))
    };
    if !shader.stanford {
        if uses.has_global("Ng") {
            // The geometric normal from the surface's screen derivatives, on the side of N.
            if let (Some(p), Some(n)) = (read_global(&mut t, "P"), read_global(&mut t, "N")) {
                let (dx, dy) = (derivative(&mut t, Axis::X, p), derivative(&mut t, Axis::Y, p));
                let c = t.math2(naga::MathFunction::Cross, dy, dx);
                let c = t.normalize(c);
                let d = t.math2(naga::MathFunction::Dot, c, n);
                let zero = t.float(0.0);
                let same = t.binary(naga::BinaryOperator::GreaterEqual, d, zero);
                let neg = t.fb.add(Expression::Unary { op: naga::UnaryOperator::Negate, expr: c });
                let ng = t.fb.add(Expression::Select { condition: same, accept: c, reject: neg });
                let var = t.global_var("Ng", Type::of(Base::Normal), false);
                let ptr = t.pointer(var);
                t.store(ptr, ng);
            }
        }
        for (d, param) in [("du", "u"), ("dv", "v")] {
            if uses.has_global(d)
                && let Some(x) = read_global(&mut t, param)
            {
                let (dx, dy) = (derivative(&mut t, Axis::X, x), derivative(&mut t, Axis::Y, x));
                let (ax, ay) = (t.math1(naga::MathFunction::Abs, dx), t.math1(naga::MathFunction::Abs, dy));
                let sum = t.binary(naga::BinaryOperator::Add, ax, ay);
                let var = t.global_var(d, Type::FLOAT, false);
                let ptr = t.pointer(var);
                t.store(ptr, sum);
            }
        }
    }
    for (input, axis, id) in &uses.seeds {
        let value = match input {
            Input::Global(g) => {
                let var = t.global_var(g.name, Type::of(g.ty), false);
                let p = t.pointer(var);
                t.load(p)
            }
            Input::Param(l) => {
                let var = t.local_var(*l);
                let p = t.pointer(var);
                t.load(p)
            }
        };
        let value = if shader.expr(*id).ty.base.components() == 3
            && matches!(input, Input::Global(g) if g.ty == Base::Float4)
        {
            t.xyz(value)
        } else {
            value
        };
        let d = derivative(&mut t, *axis, value);
        let var = t.mb.private(&seed_name(shader, *input, *axis), shader.expr(*id).ty);
        let p = t.pointer(var);
        t.store(p, d);
    }

    // Displacement, as bump mapping: the displacement shader moves P and N for the surface's
    // shading (the geometry itself does not move); its derivative seeds are the inputs'.
    if let Some((function, d)) = displacement {
        let prefix = "d_";
        let d_uses = Uses::of(d, &d.body);
        for g in &d_uses.globals {
            if let Some(value) = read_global(&mut t, g.name) {
                let var = t.mb.private(&format!("{prefix}{}", sanitize(g.name)), Type::of(g.ty));
                let ptr = t.pointer(var);
                t.store(ptr, value);
            }
        }
        for (input, axis, id) in &d_uses.seeds {
            let Input::Global(g) = input else { continue };
            let Some(value) = read_global(&mut t, g.name) else { continue };
            let dv = derivative(&mut t, *axis, value);
            let var = t.mb.private(&format!("{prefix}{}", seed_name(d, *input, *axis)), d.expr(*id).ty);
            let ptr = t.pointer(var);
            t.store(ptr, dv);
        }
        init_params(&mut t, d, prefix, &|name| UniformSource::DisplacementParam { name: name.into() });
        t.fb.push(Statement::Call { function, arguments: Vec::new(), result: None });
        for name in ["P", "N"] {
            let (Some(g), Some(sg)) = (
                crate::sema::globals::lookup(name, d.kind, d.stanford),
                crate::sema::globals::lookup(name, shader.kind, shader.stanford),
            ) else {
                continue;
            };
            if d_uses.written.contains(name) && g.ty == sg.ty {
                let src = t.mb.private(&format!("{prefix}{}", sanitize(g.name)), Type::of(g.ty));
                let ptr = t.pointer(src);
                let v = t.load(ptr);
                let dst = t.global_var(sg.name, Type::of(sg.ty), false);
                let dp = t.pointer(dst);
                t.store(dp, v);
            }
        }
    }

    // The lights, evaluated at the surface point.
    for (k, (function, light)) in lights.iter().enumerate() {
        let prefix = format!("l{k}_");
        let p = read_global(&mut t, "P").map(|p| if shader.stanford { t.xyz(p) } else { p });
        let n = read_global(&mut t, "N");
        for (name, value) in [("Ps", p), ("P", p), ("N", n)] {
            if let (Some(g), Some(v)) =
                (crate::sema::globals::lookup(name, light.kind, light.stanford), value)
            {
                let var = t.mb.private(&format!("{prefix}{}", sanitize(g.name)), Type::of(g.ty));
                let ptr = t.pointer(var);
                t.store(ptr, v);
            }
        }
        init_params(&mut t, light, &prefix, &|name| UniformSource::LightParam {
            light: k,
            name: name.into(),
        });
        t.fb.push(Statement::Call { function: *function, arguments: Vec::new(), result: None });
        // The surface sees L from the point towards the light; a Stanford surface sees it
        // normalized, with the colour as a float4 and the half-angle vector H.
        t.light = Some(k);
        let mut values: Vec<(&str, Value)> = Vec::new();
        for name in ["L", "Cl", "Ol"] {
            let Some(g) = crate::sema::globals::lookup(name, light.kind, light.stanford) else { continue };
            let src = t.mb.private(&format!("{prefix}{}", sanitize(g.name)), Type::of(g.ty));
            let ptr = t.pointer(src);
            let v = t.load(ptr);
            values.push((name, v));
        }
        for (name, mut v) in values {
            if name == "L" {
                v = t.fb.add(Expression::Unary { op: naga::UnaryOperator::Negate, expr: v });
            }
            if shader.stanford {
                match name {
                    "L" => {
                        v = t.normalize(v);
                        if let Some(e) = read_global(&mut t, "E") {
                            let sum = t.binary(naga::BinaryOperator::Add, v, e);
                            let h = t.normalize(sum);
                            let dst = t.global_var("H", Type::of(Base::Float3), true);
                            let dp = t.pointer(dst);
                            t.store(dp, h);
                        }
                    }
                    "Cl" => {
                        let one = t.float(1.0);
                        v = t.fb.add(Expression::Compose { ty: f4, components: vec![v, one] });
                    }
                    _ => {}
                }
            }
            if let Some(sg) = crate::sema::globals::lookup(name, shader.kind, shader.stanford) {
                let dst = t.global_var(sg.name, Type::of(sg.ty), sg.perlight);
                let dp = t.pointer(dst);
                t.store(dp, v);
            }
        }
        t.light = None;
    }

    t.fb.push(Statement::Call { function: body, arguments: Vec::new(), result: None });

    let color = if let Some(r) = shader.result_local {
        let var = t.local_var(r);
        let p = t.pointer(var);
        t.load(p)
    } else {
        let zero = t.float(0.0);
        let black = t.splat(zero, 3);
        let ci = read_global(&mut t, "Ci").unwrap_or(black);
        let alpha = if uses.written.contains("Oi") {
            let oi = read_global(&mut t, "Oi").unwrap_or(black);
            let third = t.float(1.0 / 3.0);
            let third = t.splat(third, 3);
            t.math2(naga::MathFunction::Dot, oi, third)
        } else {
            t.float(1.0)
        };
        t.fb.add(Expression::Compose { ty: f4, components: vec![ci, alpha] })
    };
    t.fb.push(Statement::Return { value: Some(color) });
    let mut f = std::mem::replace(&mut t.fb, FnBuilder::new("")).finish();
    f.result = Some(FunctionResult { ty: f4, binding: Some(plain(0)) });
    drop(t);
    mb.module.entry_points.push(super::module::entry_point("fs_main", ShaderStage::Fragment, [0, 0, 0], f));
}

/// A bound shader's parameters from the uniform block.
fn init_params(t: &mut Translator, shader: &Shader, prefix: &str, source: &dyn Fn(&str) -> UniformSource) {
    let uses = Uses::of(shader, &shader.body);
    let names = super::body::variable_names(shader, prefix);
    for &l in &shader.params {
        let local = shader.local(l);
        if !uses.locals.contains(&l) || matches!(local.ty.base, Base::String | Base::Texref) {
            continue;
        }
        let value = uniform_input(t, &format!("{prefix}{}", local.name), local.ty, source(&local.name));
        let var = t.mb.private(&names[&l], local.ty);
        let p = t.pointer(var);
        t.store(p, value);
    }
}
