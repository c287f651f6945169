//! The fragment entry point: inputs from the varyings and the uniform block, derivative seeds
//! at the top (uniform control flow), the bound displacement and light shaders, the body, and
//! the output colour.

use naga::{Binding, BuiltIn, Expression, FunctionArgument, FunctionResult, Handle, ShaderStage, Statement};

use crate::backend::wgsl::body::{Translator, Value};
use crate::backend::wgsl::func::FnBuilder;
use crate::backend::wgsl::interface::UniformSource;
use crate::backend::wgsl::module::{ModuleBuilder, sanitize};
use crate::backend::wgsl::uses::Uses;
use crate::ir::types::{Base, Type};
use crate::ir::{Axis, Input, Shader};
use crate::split::{StageKind, Stages};

use super::{
    Carried, Crossing, RANDOM_ROW, SCREEN_POSITION, init_params, init_uniform_inputs, location, plain,
    seed_name, varying_type,
};

#[allow(clippy::too_many_arguments)]
pub(super) fn fragment_entry(
    mb: &mut ModuleBuilder,
    stages: &Stages,
    body: Handle<naga::Function>,
    uses: &Uses,
    crossings: &[Crossing],
    lights: &[(Handle<naga::Function>, &Shader)],
    bound: super::Bound,
    strings: &[(String, String)],
) {
    let displacement = bound.displacement;
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
        for g in &c.also {
            let var = t.global_var(g.name, Type::of(g.ty), false);
            let p = t.pointer(var);
            t.store(p, value);
        }
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

    // The atmosphere's derivative seeds, also here at the top: those of the surface's inputs.
    if let Some((_, a)) = bound.atmosphere {
        for (input, axis, id) in &Uses::of(a, &a.body).seeds {
            let Input::Global(g) = input else { continue };
            let Some(value) = read_global(&mut t, g.name) else { continue };
            let dv = derivative(&mut t, *axis, value);
            let var = t.mb.private(&format!("a_{}", seed_name(a, *input, *axis)), a.expr(*id).ty);
            let ptr = t.pointer(var);
            t.store(ptr, dv);
        }
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

    // The atmosphere, between the surface and the eye: it reads the surface's results (an
    // opaque Oi when the surface writes none) and its Ci and Oi are the fragment's.
    let mut writes_oi = uses.written.contains("Oi");
    if let Some((function, a)) = bound.atmosphere {
        let prefix = "a_";
        let a_uses = Uses::of(a, &a.body);
        for g in &a_uses.globals {
            let value = if g.name == "Oi" && !uses.written.contains("Oi") {
                let one = t.float(1.0);
                Some(t.splat(one, 3))
            } else {
                read_global(&mut t, g.name)
            };
            if let Some(value) = value {
                let var = t.mb.private(&format!("{prefix}{}", sanitize(g.name)), Type::of(g.ty));
                let ptr = t.pointer(var);
                t.store(ptr, value);
            }
        }
        init_params(&mut t, a, prefix, &|name| UniformSource::AtmosphereParam { name: name.into() });
        t.fb.push(Statement::Call { function, arguments: Vec::new(), result: None });
        for name in ["Ci", "Oi"] {
            let (Some(g), Some(sg)) = (
                crate::sema::globals::lookup(name, a.kind, a.stanford),
                crate::sema::globals::lookup(name, shader.kind, shader.stanford),
            ) else {
                continue;
            };
            let value = if a_uses.globals.iter().any(|u| u.name == name) {
                let src = t.mb.private(&format!("{prefix}{}", sanitize(g.name)), Type::of(g.ty));
                let ptr = t.pointer(src);
                t.load(ptr)
            } else if name == "Oi" && !uses.written.contains("Oi") {
                let one = t.float(1.0);
                t.splat(one, 3)
            } else {
                continue;
            };
            let dst = t.global_var(sg.name, Type::of(sg.ty), false);
            let dp = t.pointer(dst);
            t.store(dp, value);
        }
        writes_oi = true;
    }

    let color = if let Some(r) = shader.result_local {
        let var = t.local_var(r);
        let p = t.pointer(var);
        t.load(p)
    } else {
        let zero = t.float(0.0);
        let black = t.splat(zero, 3);
        let ci = read_global(&mut t, "Ci").unwrap_or(black);
        let alpha = if writes_oi {
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
    mb.module.entry_points.push(crate::backend::wgsl::module::entry_point(
        "fs_main",
        ShaderStage::Fragment,
        [0, 0, 0],
        f,
    ));
}
