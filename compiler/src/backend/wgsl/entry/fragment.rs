//! The fragment entry point: inputs from the varyings and the uniform block, derivative seeds
//! at the top (uniform control flow), the bound displacement and light shaders, the body, and
//! the output colour.

use naga::{Binding, BuiltIn, Expression, FunctionArgument, FunctionResult, Handle, ShaderStage, Statement};

use crate::backend::arith::Arith;
use crate::backend::wgsl::body::{Translator, Value};
use crate::backend::wgsl::func::FnBuilder;
use crate::backend::wgsl::interface::UniformSource;
use crate::backend::wgsl::module::{ModuleBuilder, sanitize};
use crate::backend::wgsl::uses::Uses;
use crate::ir::global::Global;
use crate::ir::types::{Base, Frequency, Type};
use crate::ir::{Axis, Input, Shader};
use crate::split::{StageKind, Stages};

use super::{
    Carried, Crossing, RANDOM_ROW, SCREEN_POSITION, init_params, init_uniform_inputs, location, plain,
    seed_name, uniform_input, varying_type,
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
        let var = t.mb.private(crate::backend::POINT_INDEX, Type::of(Base::Uint));
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
                store_bound_global(&mut t, prefix, g, value);
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
                let v = load_bound_global(&mut t, prefix, g);
                let dst = t.global_var(sg.name, Type::of(sg.ty), false);
                let dp = t.pointer(dst);
                t.store(dp, v);
            }
        }
    }

    // The lights, evaluated at the surface point.
    if !lights.is_empty() {
        let point = SurfacePoint {
            p: read_global(&mut t, "P").map(|p| if shader.stanford { t.xyz(p) } else { p }),
            n: read_global(&mut t, "N"),
            // Stanford's H is made of L and E.
            e: if shader.stanford { read_global(&mut t, "E") } else { None },
        };
        for (k, &(function, light)) in lights.iter().enumerate() {
            let arrival = if light.stanford {
                stanford_light(&mut t, k, function, light, &point)
            } else {
                renderman_light(&mut t, k, function, light, &point, uses.has_global("Ol"))
            };
            if let Some(arrival) = arrival {
                surface_light_values(&mut t, k, light, arrival, point.e);
            }
        }
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
                store_bound_global(&mut t, prefix, g, value);
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
                load_bound_global(&mut t, prefix, g)
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

/// The surface point the lights are evaluated at, as the surface sees it after displacement
/// (`P` as a 3-vector in either style; `N` and `E` in the surface's own style).
struct SurfacePoint {
    p: Option<Value>,
    n: Option<Value>,
    e: Option<Value>,
}

/// What a light delivers to the surface: the vector from the point towards the light (not
/// normalized; RenderMan's `-L`), the light's colour (a RenderMan light's `color Cl`, a Stanford
/// light's returned `float4`) and a RenderMan light's `Ol`.
struct Arrival {
    toward: Value,
    cl: Value,
    ol: Option<Value>,
}

/// The private variable holding predefined variable `g` of the shader bound beside the surface
/// whose variables are named after `prefix` (`l0_`, `d_`, `a_`).
fn bound_global_var(t: &mut Translator, prefix: &str, g: &Global) -> Handle<naga::GlobalVariable> {
    t.mb.private(&format!("{prefix}{}", sanitize(g.name)), Type::of(g.ty))
}

/// Stores `value` into a bound shader's predefined variable `g` (one of its inputs).
fn store_bound_global(t: &mut Translator, prefix: &str, g: &Global, value: Value) {
    let var = bound_global_var(t, prefix, g);
    let ptr = t.pointer(var);
    t.store(ptr, value);
}

/// Loads a bound shader's predefined variable `g` (one of its results).
fn load_bound_global(t: &mut Translator, prefix: &str, g: &Global) -> Value {
    let var = bound_global_var(t, prefix, g);
    let ptr = t.pointer(var);
    t.load(ptr)
}

/// Runs RenderMan-style light `k` at the surface point (`Ps` = `P`) and reads what it emitted:
/// its `Ol` only for a surface that reads it (`wants_ol`).
fn renderman_light(
    t: &mut Translator,
    k: usize,
    function: Handle<naga::Function>,
    light: &Shader,
    point: &SurfacePoint,
    wants_ol: bool,
) -> Option<Arrival> {
    let prefix = format!("l{k}_");
    let reads = Uses::of(light, &light.body);
    for (name, value) in [("Ps", point.p), ("P", point.p), ("N", point.n)] {
        // `illuminate` and `solar` read Ps without naming it; P and N are stored only for a light
        // that reads them, so that the module holds no copy nothing reads.
        if name != "Ps" && !reads.has_global(name) {
            continue;
        }
        if let (Some(g), Some(v)) = (crate::sema::globals::lookup(name, light.kind, light.stanford), value) {
            store_bound_global(t, &prefix, g, v);
        }
    }
    init_params(t, light, &prefix, &|name| UniformSource::LightParam { light: k, name: name.into() });
    t.fb.push(Statement::Call { function, arguments: Vec::new(), result: None });
    let mut result = |name| {
        let g = crate::sema::globals::lookup(name, light.kind, light.stanford)?;
        Some(load_bound_global(t, &prefix, g))
    };
    let (l, cl) = (result("L")?, result("Cl")?);
    let ol = if wants_ol { result("Ol") } else { None };
    // The light's L runs from the light to the point.
    let toward = t.fb.add(Expression::Unary { op: naga::UnaryOperator::Negate, expr: l });
    Some(Arrival { toward, cl, ol })
}

/// Runs Stanford-style light `k` at the surface point and reads the colour it returned. Its `L`
/// (towards the light, normalized) and `Sdist` come from the light's position in the uniform
/// block; its other inputs are the surface's: under a Stanford surface its own variables of the
/// same names, under a RenderMan one `P` with w = 1, `N` normalized and `E` = normalize(-P)
/// (`check_stanford_light` refused the rest).
fn stanford_light(
    t: &mut Translator,
    k: usize,
    function: Handle<naga::Function>,
    light: &Shader,
    point: &SurfacePoint,
) -> Option<Arrival> {
    let prefix = format!("l{k}_");
    let p = point.p?;
    let position = t.uniform_value(
        &format!("{prefix}position"),
        Type::of(Base::Float3),
        UniformSource::LightPosition { light: k },
    );
    let toward = t.binary(naga::BinaryOperator::Subtract, position, p);
    let sdist = t.length(toward);
    let spread = t.splat(sdist, 3);
    let l = t.div(toward, spread);
    let surface_stanford = t.shader.stanford;
    for g in Uses::of(light, &light.body).globals {
        let value = match g.name {
            "L" => Some(l),
            "Sdist" => Some(sdist),
            "PI" | "ncomps" => None,
            _ if g.frequency <= Frequency::PrimitiveGroup => Some(uniform_input(
                t,
                g.name,
                Type::of(g.ty),
                UniformSource::Global { name: g.name.to_string() },
            )),
            name if surface_stanford => {
                let var = t.global_var(name, Type::of(g.ty), false);
                let ptr = t.pointer(var);
                Some(t.load(ptr))
            }
            "P" => {
                let one = t.float(1.0);
                let f4 = t.mb.ty(Type::of(Base::Float4), false);
                Some(t.fb.add(Expression::Compose { ty: f4, components: vec![p, one] }))
            }
            "N" => point.n.map(|n| t.normalize(n)),
            "E" => {
                let to_eye = t.fb.add(Expression::Unary { op: naga::UnaryOperator::Negate, expr: p });
                Some(t.normalize(to_eye))
            }
            _ => None,
        };
        if let Some(value) = value {
            store_bound_global(t, &prefix, g, value);
        }
    }
    init_params(t, light, &prefix, &|name| UniformSource::LightParam { light: k, name: name.into() });
    t.fb.push(Statement::Call { function, arguments: Vec::new(), result: None });
    let result = light.result_local?;
    let name = &crate::backend::wgsl::body::variable_names(light, &prefix)[&result];
    let var = t.mb.private(name, light.local(result).ty);
    let ptr = t.pointer(var);
    let cl = t.load(ptr);
    Some(Arrival { toward, cl, ol: None })
}

/// Gives the surface light `k`'s values in its own style: a RenderMan surface sees `L` from the
/// point towards the light (not normalized), `Cl` as a color (a Stanford light's rgb) and `Ol`;
/// a Stanford surface sees `L` normalized, the half-angle vector `H` of `L` and `E`, and `Cl` as
/// a float4 (a RenderMan light's colour with alpha 1).
fn surface_light_values(t: &mut Translator, k: usize, light: &Shader, arrival: Arrival, e: Option<Value>) {
    let surface = t.shader;
    // The surface's per-light variables are its copies for light k.
    t.light = Some(k);
    let mut values = Vec::new();
    if surface.stanford {
        let l = t.normalize(arrival.toward);
        values.push(("L", l));
        if let Some(e) = e {
            let sum = t.binary(naga::BinaryOperator::Add, l, e);
            values.push(("H", t.normalize(sum)));
        }
        let cl = if light.stanford {
            arrival.cl
        } else {
            let one = t.float(1.0);
            let f4 = t.mb.ty(Type::of(Base::Float4), false);
            t.fb.add(Expression::Compose { ty: f4, components: vec![arrival.cl, one] })
        };
        values.push(("Cl", cl));
    } else {
        values.push(("L", arrival.toward));
        let cl = if light.stanford { t.xyz(arrival.cl) } else { arrival.cl };
        values.push(("Cl", cl));
        values.extend(arrival.ol.map(|ol| ("Ol", ol)));
    }
    for (name, v) in values {
        if let Some(sg) = crate::sema::globals::lookup(name, surface.kind, surface.stanford) {
            let dst = t.global_var(sg.name, Type::of(sg.ty), sg.perlight);
            let dp = t.pointer(dst);
            t.store(dp, v);
        }
    }
    t.light = None;
}
