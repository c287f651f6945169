//! The entry points: the vertex stage's geometry (predefined variables from the mesh's attributes
//! and the uniform block), the varyings, the fragment stage's derivative seeds and lights, and
//! the output. The CPU reference renderer (`patina-runtime`) computes the same inputs by the same
//! formulas; `docs/numerics.md` lists them.

mod fragment;
mod vertex;

use naga::{Binding, Expression, Handle, Interpolation, Sampling, StructMember};

use super::body::{Translator, Value};
use super::interface::{Attribute, AttributeSource, MeshAttribute, UniformSource, Varying};
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

/// Whether the vertex entry point must set the predefined variable `name`: a stage reads it or
/// a varying carries its value on entry.
pub(crate) fn geometry_needed(name: &str, vertex: &Uses, fragment: &Uses, crossings: &[Crossing]) -> bool {
    vertex.has_global(name)
        || fragment.has_global(name)
        || crossings.iter().any(|c| matches!(c.what, Carried::Global(g) if g.name == name))
}

/// The mesh properties the vertex entry point reads to set the predefined variables `needed`
/// says it must (the position always: it places the vertex).
pub(crate) fn mesh_attributes_read(needed: impl Fn(&str) -> bool, stanford: bool) -> Vec<MeshAttribute> {
    let any = |names: &[&str]| names.iter().any(|n| needed(n));
    let (normal, uv, dpdu, dpdv) = if stanford {
        (any(&["N", "B", "__normal", "__objnormal"]), false, any(&["T", "B"]), false)
    } else {
        (any(&["N", "Ng"]), any(&["u", "v", "s", "t"]), any(&["dPdu"]), any(&["dPdv"]))
    };
    MeshAttribute::ALL
        .into_iter()
        .zip([true, normal, uv, dpdu, dpdv])
        .filter_map(|(a, read)| read.then_some(a))
        .collect()
}

/// Predefined variables of a RenderMan surface that the vertex entry point sets to another's
/// value (`I` is `P` in camera space; `s` and `t` are `u` and `v`), as (variable, the one whose
/// value it takes). When both cross to the fragment stage, one varying carries them: each
/// varying costs an interpolation per component at every fragment.
pub(crate) const SAME_ON_ENTRY: [(&str, &str); 3] = [("I", "P"), ("s", "u"), ("t", "v")];

/// A value that crosses from the vertex to the fragment stage.
pub(crate) struct Crossing {
    pub name: String,
    pub ty: Type,
    /// What fills it in the vertex stage and what it fills in the fragment stage.
    pub what: Carried,
    /// Predefined variables the fragment stage also fills from it: those [`SAME_ON_ENTRY`] makes
    /// equal to a [`Carried::Global`].
    pub also: Vec<&'static crate::ir::global::Global>,
}

/// What a varying carries.
#[derive(Clone, Copy)]
pub(crate) enum Carried {
    /// A predefined variable's value on entry to the vertex stage.
    Global(&'static crate::ir::global::Global),
    /// A vertex-rate parameter's value on entry.
    Param(crate::ir::LocalId),
    /// A transfer computed by the vertex stage.
    Transfer(crate::ir::LocalId),
}

/// The shaders bound beside the surface at each fragment: a displacement run before it and an
/// atmosphere run after it, each as its naga function and its shader.
#[derive(Clone, Copy, Default)]
pub(crate) struct Bound<'a> {
    pub displacement: Option<(Handle<naga::Function>, &'a Shader)>,
    pub atmosphere: Option<(Handle<naga::Function>, &'a Shader)>,
}

/// Builds both entry points; returns the attributes and varyings.
pub(crate) fn entry_points(
    mb: &mut ModuleBuilder,
    stages: &Stages,
    vertex_body: Handle<naga::Function>,
    fragment_body: Handle<naga::Function>,
    lights: &[(Handle<naga::Function>, &Shader)],
    bound: Bound,
    strings: &[(String, String)],
) -> (Vec<Attribute>, Vec<Varying>) {
    let vertex_uses = Uses::of(&stages.vertex, &stages.vertex.body);
    let fragment_uses = Uses::of(&stages.fragment, &stages.fragment.body);
    let surface = &stages.fragment;

    // What crosses: vertex-rate inputs the fragment stage reads, and the vertex stage's transfers.
    let mut crossings: Vec<Crossing> = Vec::new();
    // Lights are evaluated at the surface point and orientation, and Stanford's H needs E.
    let mut carried_globals = fragment_uses.globals.clone();
    // A displacement shader runs at the top of the fragment stage on the surface's inputs, an
    // atmosphere at the end on its results; a Stanford-style light reads the surface point's
    // inputs by their names (`Pobj`, `T`, ...).
    let stanford_lights = lights.iter().filter(|(_, l)| l.stanford).copied();
    for (_, d) in bound.displacement.into_iter().chain(bound.atmosphere).chain(stanford_lights) {
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
    // A RenderMan surface's fragment entry fills `Cs` and `Os` from the uniform block and
    // computes `Ng` from P's screen derivatives before its body reads them (`fragment.rs`,
    // `init_uniform_inputs`): varyings of them would be interpolated for nothing.
    let refilled = |name: &str| {
        !surface.stanford && matches!(name, "Cs" | "Os" | "Ng") && fragment_uses.has_global(name)
    };
    let crossing_globals: Vec<&'static crate::ir::global::Global> = carried_globals
        .iter()
        .copied()
        .filter(|g| g.frequency == Frequency::Vertex && !g.perlight && !refilled(g.name))
        .collect();
    // The variable whose varying also carries `name`, when both cross.
    let carrier = |name: &str| {
        SAME_ON_ENTRY
            .iter()
            .find(|(alias, _)| !surface.stanford && *alias == name)
            .map(|(_, of)| *of)
            .filter(|of| crossing_globals.iter().any(|g| g.name == *of))
    };
    for &g in crossing_globals.iter().filter(|g| carrier(g.name).is_none()) {
        crossings.push(Crossing {
            name: format!("in_{}", sanitize(g.name)),
            ty: Type::of(g.ty),
            what: Carried::Global(g),
            also: crossing_globals.iter().copied().filter(|a| carrier(a.name) == Some(g.name)).collect(),
        });
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
                also: Vec::new(),
            });
        }
    }
    for t in stages.transfers.iter().filter(|t| t.from == StageKind::Vertex && t.to_fragment) {
        crossings.push(Crossing {
            name: t.name.to_string(),
            ty: t.ty,
            what: Carried::Transfer(t.local),
            also: Vec::new(),
        });
    }

    // Vertex attributes: the mesh properties read (each at its own location), then vertex-rate
    // parameters from the first location after them.
    let needed = |name: &str| geometry_needed(name, &vertex_uses, &fragment_uses, &crossings);
    let mut attributes: Vec<Attribute> = mesh_attributes_read(needed, surface.stanford)
        .into_iter()
        .map(|what| Attribute {
            name: format!("a_{}", what.name()),
            source: AttributeSource::Mesh { what },
            location: what.location(),
            components: what.components(),
        })
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
    for (k, l) in vertex_params.iter().enumerate() {
        let local = surface.local(*l);
        attributes.push(Attribute {
            // `p_` keeps a parameter's argument apart from a mesh property of the same name.
            name: format!("p_{}", sanitize(&local.name)),
            source: AttributeSource::Param { name: local.name.to_string() },
            location: MeshAttribute::ALL.len() as u32 + k as u32,
            components: local.ty.base.components(),
        });
    }

    let varyings = vertex::vertex_entry(
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
    fragment::fragment_entry(mb, stages, fragment_body, &fragment_uses, &crossings, lights, bound, strings);
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
}

/// A value read from the uniform block in the language's form (booleans from `u32`, arrays
/// unpadded element by element).
pub(super) fn uniform_input(t: &mut Translator, name: &str, ty: Type, source: UniformSource) -> Value {
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
