//! The vertex entry point: the geometry (predefined variables from the mesh's attributes and the
//! uniform block), the vertex stage's body, the clip position and the varyings.

use naga::{
    Binding, BuiltIn, Expression, FunctionArgument, FunctionResult, Handle, ShaderStage, Span, Statement,
    StructMember, TypeInner,
};

use crate::backend::wgsl::body::{Translator, Value};
use crate::backend::wgsl::func::FnBuilder;
use crate::backend::wgsl::interface::{
    Attribute, AttributeSource, GeometryMatrix, MeshAttribute, UniformSource, Varying,
};
use crate::backend::wgsl::module::ModuleBuilder;
use crate::backend::wgsl::uses::Uses;
use crate::ir::types::{Base, Type};
use crate::split::{StageKind, Stages};

use super::{
    Carried, Crossing, SAME_ON_ENTRY, geometry_needed, init_uniform_inputs, lay_out, location, plain,
    varying_type,
};

#[allow(clippy::too_many_arguments)]
pub(super) fn vertex_entry(
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
            name: Some(a.name.clone()),
            ty,
            binding: Some(plain(a.location)),
        });
        args.push(t.fb.add(Expression::FunctionArgument(args.len() as u32)));
    }
    let mesh = |what: MeshAttribute| {
        attributes.iter().position(|a| a.source == AttributeSource::Mesh { what }).map(|i| args[i])
    };

    // The geometry: predefined variables the stages read, in camera ("current") space, from the
    // mesh properties `mesh_attributes_read` chose (the position is always read).
    let needed = |name: &str| geometry_needed(name, uses, fragment_uses, crossings);
    let stanford = shader.stanford;
    let set = |t: &mut Translator, name: &str, value: Value| {
        if let Some(g) = crate::sema::globals::lookup(name, shader.kind, stanford) {
            let var = t.global_var(g.name, Type::of(g.ty), false);
            let p = t.pointer(var);
            t.store(p, value);
        }
    };
    let oc = t.uniform_value(
        "object_to_camera",
        Type::of(Base::Matrix4),
        UniformSource::Geometry { matrix: GeometryMatrix::ObjectToCamera },
    );
    let position = mesh(MeshAttribute::Position).expect("the position is always read");
    let p_cam = t.transform_by(oc, position, 1.0);
    let n_cam = mesh(MeshAttribute::Normal).map(|n| {
        let nc = t.uniform_value(
            "normal_to_camera",
            Type::of(Base::Matrix4),
            UniformSource::Geometry { matrix: GeometryMatrix::NormalToCamera },
        );
        t.transform_by(nc, n, 0.0)
    });
    let uv = mesh(MeshAttribute::Uv).map(|uv| {
        let u = t.fb.add(Expression::AccessIndex { base: uv, index: 0 });
        let v = t.fb.add(Expression::AccessIndex { base: uv, index: 1 });
        (u, v)
    });
    let dpdu = mesh(MeshAttribute::DpDu).map(|d| t.transform_by(oc, d, 0.0));
    let dpdv = mesh(MeshAttribute::DpDv).map(|d| t.transform_by(oc, d, 0.0));
    let mut values: Vec<(&str, Value)> = Vec::new();
    if stanford {
        let one = t.float(1.0);
        let f4 = t.mb.ty(Type::of(Base::Float4), false);
        let p4 = t.fb.add(Expression::Compose { ty: f4, components: vec![p_cam, one] });
        let pobj = t.fb.add(Expression::Compose { ty: f4, components: vec![position, one] });
        let minus_p = t.fb.add(Expression::Unary { op: naga::UnaryOperator::Negate, expr: p_cam });
        let e = t.normalize(minus_p);
        values.extend([("P", p4), ("Pobj", pobj), ("E", e), ("__position", pobj)]);
        let n = n_cam.map(|n| t.normalize(n));
        let tangent = dpdu.map(|d| t.normalize(d));
        if let (Some(n), Some(tangent)) = (n, tangent) {
            let b = t.math2(naga::MathFunction::Cross, n, tangent);
            values.push(("B", b));
        }
        if let Some(n) = n {
            values.push(("N", n));
        }
        if let Some(tangent) = tangent {
            values.push(("T", tangent));
        }
        if let Some(n_obj) = mesh(MeshAttribute::Normal) {
            values.extend([("__normal", n_obj), ("__objnormal", n_obj)]);
        }
    } else {
        let zero = t.float(0.0);
        let origin = t.splat(zero, 3);
        values.extend([("P", p_cam), ("E", origin), ("dPdtime", origin)]);
        if let Some(n) = n_cam {
            values.extend([("N", n), ("Ng", n)]);
        }
        if let Some((u, v)) = uv {
            values.extend([("u", u), ("v", v)]);
        }
        // The fragment stage fills these from one varying when both cross, so they are set from
        // the table that decides it.
        for (alias, of) in SAME_ON_ENTRY {
            if let Some(&(_, value)) = values.iter().find(|(name, _)| *name == of) {
                values.push((alias, value));
            }
        }
        if let Some(d) = dpdu {
            values.push(("dPdu", d));
        }
        if let Some(d) = dpdv {
            values.push(("dPdv", d));
        }
    }
    for (name, value) in values {
        if needed(name) {
            set(&mut t, name, value);
        }
    }
    init_uniform_inputs(&mut t, shader, uses, StageKind::Vertex, stages);
    for (k, l) in vertex_params.iter().enumerate() {
        let var = t.local_var(*l);
        let p = t.pointer(var);
        let value = args[attributes.len() - vertex_params.len() + k];
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
            also: c.also.iter().map(|g| g.name.to_string()).collect(),
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
    mb.module.entry_points.push(crate::backend::wgsl::module::entry_point(
        "vs_main",
        ShaderStage::Vertex,
        [0, 0, 0],
        f,
    ));
    varyings
}
