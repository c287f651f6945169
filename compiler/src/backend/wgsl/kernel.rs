//! A whole (unsplit) shader as a compute kernel: one invocation per point, every input read from a
//! storage buffer and every output written to one. This is how conformance tests run exactly
//! what the interpreter runs — same inputs by the same names, derivative seeds included — on the
//! GPU.
//!
//! Layout: `input: array<u32>` at group 0 binding 1 and `output: array<u32>` at binding 2 (the
//! runtime's compute harness convention; binding 0 would be a uniform block, which kernels do
//! not use). Point `i`'s values start at `i * stride`; each named value occupies its components
//! in order, floats as their bit patterns, booleans as 0 or 1.

use naga::{
    AddressSpace, ArraySize, BinaryOperator as Op, Binding, BuiltIn, Expression, FunctionArgument,
    GlobalVariable, Literal, ResourceBinding, ScalarKind, ShaderStage, Span, Statement, StorageAccess,
    TypeInner,
};

use super::Lowering;
use super::body::{Translator, Value};
use super::entry::seed_name;
use super::func::FnBuilder;
use super::module::ModuleBuilder;
use crate::backend::binding::LightBinding;
use crate::diag::{Code, Diagnostic};
use crate::ir::types::{Base, Type};
use crate::ir::{Axis, Input, Shader};
use crate::opt::Prepared;

/// One named value of a kernel's input or output.
#[derive(Clone, Debug, PartialEq)]
pub struct KernelValue {
    /// The name, as the interpreter's slots spell it (`Kd`, `P`, `dx(s)`, `L[0]`, `result`).
    pub name: String,
    /// Its type.
    pub ty: Type,
    /// Its first word within a point's record.
    pub offset: u32,
    /// Its words (components).
    pub words: u32,
}

/// A compiled kernel.
#[derive(Clone, Debug)]
pub struct Kernel {
    /// The module, with the compute entry point `main` (workgroup size 64).
    pub module: naga::Module,
    /// The validator's information.
    pub info: naga::valid::ModuleInfo,
    /// The inputs, and the words per point.
    pub inputs: Vec<KernelValue>,
    /// Words per point of input.
    pub input_stride: u32,
    /// The outputs.
    pub outputs: Vec<KernelValue>,
    /// Words per point of output.
    pub output_stride: u32,
    /// The uniform block at `@group(0) @binding(0)`, when the shader reads uniforms the kernel
    /// does not take per point (the matrices of named spaces); empty when it has none.
    pub uniforms: Vec<super::interface::UniformField>,
    /// The uniform block's size in bytes (0 without one).
    pub uniform_size: u32,
    /// The textures the kernel fetches from, in `@group(1)` at their bindings (no samplers:
    /// kernels read texels with `textureLoad`, as draws do).
    pub textures: Vec<super::interface::TextureSlot>,
}

/// The workgroup size of kernels.
pub const KERNEL_WORKGROUP: u32 = 64;

/// Where a named value lives in the module.
enum Target {
    Local(crate::ir::LocalId),
    Global(&'static crate::ir::global::Global, Option<usize>),
    Seed(Input, Axis),
    /// A private variable of the module by name (`xyz_screen`).
    Private(&'static str),
}

/// Compiles a prepared shader as a kernel reading `inputs` and writing `outputs`.
pub fn compile_kernel(
    shader: &Prepared,
    lights: &[LightBinding],
    strings: &[(String, String)],
    inputs: &[&str],
    outputs: &[&str],
) -> Result<Kernel, Diagnostic> {
    compile_kernel_lowered(shader, lights, strings, inputs, outputs, Lowering::Exact)
}

/// As [`compile_kernel`], in the given lowering (the fast one measures what users' modules
/// compute, against the same f64 reference).
pub fn compile_kernel_lowered(
    shader: &Prepared,
    lights: &[LightBinding],
    strings: &[(String, String)],
    inputs: &[&str],
    outputs: &[&str],
    lowering: Lowering,
) -> Result<Kernel, Diagnostic> {
    let mut mb = ModuleBuilder::without_uniform_tables();
    mb.lowering = lowering;
    let lit = crate::opt::lights::unroll(shader, lights, strings);
    let mut t = Translator::new(&mut mb, &lit, "", lights, strings, "body");
    t.block(&lit.body)?;
    let body_fn = std::mem::replace(&mut t.fb, FnBuilder::new("")).finish();
    drop(t);
    let body = mb.module.functions.append(body_fn, Span::UNDEFINED);

    let resolve = |name: &str| -> Result<(Target, Type), Diagnostic> {
        resolve(shader, name).ok_or_else(|| {
            Diagnostic::error(
                Code::UnknownInput,
                format!("the shader has no input or output `{name}`"),
                shader.span,
                "",
            )
        })
    };
    let layout = |names: &[&str]| -> Result<(Vec<(KernelValue, Target)>, u32), Diagnostic> {
        let mut offset = 0;
        let mut out = Vec::new();
        for name in names {
            let (target, ty) = resolve(name)?;
            let words = ty.base.components() * ty.array.unwrap_or(1).max(1);
            out.push((KernelValue { name: name.to_string(), ty, offset, words }, target));
            offset += words;
        }
        Ok((out, offset.max(1)))
    };
    let (ins, input_stride) = layout(inputs)?;
    let (outs, output_stride) = layout(outputs)?;

    let u32_ty = mb.ty(Type::of(Base::Uint), false);
    let array = mb.inner(TypeInner::Array { base: u32_ty, size: ArraySize::Dynamic, stride: 4 });
    let buffer = |mb: &mut ModuleBuilder, name: &str, binding: u32, access: StorageAccess| {
        mb.module.global_variables.append(
            GlobalVariable {
                name: Some(name.into()),
                space: AddressSpace::Storage { access },
                binding: Some(ResourceBinding { group: 0, binding }),
                ty: array,
                init: None,
                memory_decorations: naga::MemoryDecorations::empty(),
            },
            Span::UNDEFINED,
        )
    };
    let input_buf = buffer(&mut mb, "input", 1, StorageAccess::LOAD);
    let output_buf = buffer(&mut mb, "output", 2, StorageAccess::LOAD | StorageAccess::STORE);

    let mut t = Translator::new(&mut mb, shader, "", lights, strings, "main");
    let uvec3 = t.mb.inner(TypeInner::Vector { size: naga::VectorSize::Tri, scalar: naga::Scalar::U32 });
    t.fb.f.arguments.push(FunctionArgument {
        name: Some("id".into()),
        ty: uvec3,
        binding: Some(Binding::BuiltIn(BuiltIn::GlobalInvocationId)),
    });
    let id = t.fb.add(Expression::FunctionArgument(0));
    let index = t.fb.add(Expression::AccessIndex { base: id, index: 0 });
    let out_ptr = t.fb.add(Expression::GlobalVariable(output_buf));
    let in_ptr = t.fb.add(Expression::GlobalVariable(input_buf));
    // Points past the end (the last workgroup's padding) do nothing.
    let len = t.fb.add(Expression::ArrayLength(out_ptr));
    let stride = t.fb.add(Expression::Literal(Literal::U32(output_stride)));
    let count = t.binary(Op::Divide, len, stride);
    let past = t.binary(Op::GreaterEqual, index, count);
    t.fb.open();
    t.fb.push(Statement::Return { value: None });
    let accept = t.fb.close();
    t.fb.push(Statement::If { condition: past, accept, reject: naga::Block::new() });

    // `random()` hashes the point's index, as the interpreter's default (an input may override).
    let point = t.mb.private(crate::backend::POINT_INDEX, Type::of(Base::Uint));
    let point = t.pointer(point);
    t.store(point, index);
    // What the interpreter gives a shader before its inputs: each parameter that is not an input
    // its default (the interpreter evaluates defaults once per batch; here once per invocation,
    // in declaration order). The constant predefined variables are literals where they are read.
    for &param in &shader.params {
        let local = shader.local(param);
        let is_input = ins.iter().any(|(_, target)| matches!(target, Target::Local(l) if *l == param));
        // Strings and textures are resolved at compile time (`strings`, texture bindings).
        let value_type = local.ty.base.components() > 0;
        if let (crate::ir::LocalKind::Param { default: Some(default), .. }, false, true) =
            (&local.kind, is_input, value_type)
        {
            let value = t.expr(*default)?;
            let ptr = target_pointer(&mut t, shader, &Target::Local(param), local.ty);
            t.store(ptr, value);
        }
    }
    let in_stride = t.fb.add(Expression::Literal(Literal::U32(input_stride)));
    let in_base = t.binary(Op::Multiply, index, in_stride);
    for (v, target) in &ins {
        let words: Vec<Value> = (0..v.words)
            .map(|w| {
                let off = t.fb.add(Expression::Literal(Literal::U32(v.offset + w)));
                let i = t.binary(Op::Add, in_base, off);
                let p = t.fb.add(Expression::Access { base: in_ptr, index: i });
                let bits = t.load(p);
                from_bits(&mut t, bits, v.ty.base)
            })
            .collect();
        let value = assemble(&mut t, &words, v.ty);
        let ptr = target_pointer(&mut t, shader, target, v.ty);
        t.store(ptr, value);
    }
    t.fb.push(Statement::Call { function: body, arguments: Vec::new(), result: None });
    let out_stride = t.fb.add(Expression::Literal(Literal::U32(output_stride)));
    let out_base = t.binary(Op::Multiply, index, out_stride);
    for (v, target) in &outs {
        let ptr = target_pointer(&mut t, shader, target, v.ty);
        let value = t.load(ptr);
        let words = disassemble(&mut t, value, v.ty);
        for (w, word) in words.into_iter().enumerate() {
            let bits = to_bits(&mut t, word, v.ty.base);
            let off = t.fb.add(Expression::Literal(Literal::U32(v.offset + w as u32)));
            let i = t.binary(Op::Add, out_base, off);
            let p = t.fb.add(Expression::Access { base: out_ptr, index: i });
            t.store(p, bits);
        }
    }
    let f = std::mem::replace(&mut t.fb, FnBuilder::new("")).finish();
    drop(t);
    mb.module.entry_points.push(super::module::entry_point(
        "main",
        ShaderStage::Compute,
        [KERNEL_WORKGROUP, 1, 1],
        f,
    ));
    // A kernel reads per-point values from its buffers; the uniform block stays at binding 0
    // only when the shader reads uniforms (named spaces), and is moved out of the way otherwise.
    let textures = mb.texture_slots();
    let (module, uniforms, uniform_size) = uniform_block(mb)?;
    let info =
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::empty())
            .validate(&module)
            .map_err(|e| {
                super::internal(
                    shader.span,
                    format!("internal error: the kernel does not validate: {}", super::chain(&e)),
                )
            })?;
    let strip = |v: Vec<(KernelValue, Target)>| v.into_iter().map(|(k, _)| k).collect();
    Ok(Kernel {
        module,
        info,
        inputs: strip(ins),
        input_stride,
        outputs: strip(outs),
        output_stride,
        uniforms,
        uniform_size,
        textures,
    })
}

/// The module with its uniform block laid out: kept at binding 0 when it has fields, else (an
/// unused placeholder) moved to group 2, where nothing refers to it.
#[allow(clippy::type_complexity)]
fn uniform_block(
    mut mb: ModuleBuilder,
) -> Result<(naga::Module, Vec<super::interface::UniformField>, u32), Diagnostic> {
    let (fields, size) =
        mb.finish_uniforms().map_err(|e| super::internal(crate::source::Span::default(), e))?;
    if !fields.is_empty() {
        return Ok((mb.module, fields, size));
    }
    let mut module = mb.module;
    // An unused resource is harmless to naga; wgpu's auto layout leaves it out. Give it group 2
    // so it can never collide with the kernel's buffers (group 0) or textures (group 1).
    for (_, g) in module.global_variables.iter_mut() {
        if g.space == AddressSpace::Uniform {
            g.binding = Some(ResourceBinding { group: 2, binding: 0 });
        }
    }
    Ok((module, Vec::new(), 0))
}

/// What a name refers to, and its type.
fn resolve(shader: &Shader, name: &str) -> Option<(Target, Type)> {
    if let Some(inner) = name.strip_prefix("dx(").or_else(|| name.strip_prefix("dy(")) {
        let axis = if name.starts_with("dx") { Axis::X } else { Axis::Y };
        let input_name = inner.strip_suffix(')')?;
        let (input, ty) = match crate::sema::globals::lookup(input_name, shader.kind, shader.stanford) {
            Some(g) => (Input::Global(g), Type::of(g.ty)),
            None => {
                let l = shader.params.iter().find(|l| shader.local(**l).name == input_name)?;
                (Input::Param(*l), shader.local(*l).ty)
            }
        };
        let ty = if ty.base == Base::Point { Type::of(Base::Vector) } else { ty };
        return Some((Target::Seed(input, axis), ty));
    }
    if name == crate::backend::POINT_INDEX {
        return Some((Target::Private(crate::backend::POINT_INDEX), Type::of(Base::Uint)));
    }
    if name == super::entry::SCREEN_POSITION {
        return Some((Target::Private(super::entry::SCREEN_POSITION), Type::of(Base::Float4)));
    }
    if let Some((base, rest)) = name.split_once('[') {
        let k: usize = rest.strip_suffix(']')?.parse().ok()?;
        let g = crate::sema::globals::lookup(base, shader.kind, shader.stanford)?;
        return Some((Target::Global(g, Some(k)), Type::of(g.ty)));
    }
    if let Some(l) = (0..shader.locals.len() as u32).map(crate::ir::LocalId).find(|l| {
        shader.local(*l).name == name && (shader.params.contains(l) || shader.result_local == Some(*l))
    }) {
        return Some((Target::Local(l), shader.local(l).ty));
    }
    let g = crate::sema::globals::lookup(name, shader.kind, shader.stanford)?;
    Some((Target::Global(g, None), Type::of(g.ty)))
}

fn target_pointer(t: &mut Translator, shader: &Shader, target: &Target, ty: Type) -> Value {
    let var = match target {
        Target::Local(l) => t.local_var(*l),
        Target::Global(g, light) => {
            let outer = std::mem::replace(&mut t.light, *light);
            let v = t.global_var(g.name, Type::of(g.ty), g.perlight);
            t.light = outer;
            v
        }
        Target::Seed(input, axis) => t.mb.private(&seed_name(shader, *input, *axis), ty),
        Target::Private(name) => t.mb.private(name, ty),
    };
    t.pointer(var)
}

fn from_bits(t: &mut Translator, bits: Value, base: Base) -> Value {
    match base {
        Base::Uint => bits,
        Base::Int => t.fb.add(Expression::As { expr: bits, kind: ScalarKind::Sint, convert: None }),
        Base::Bool => {
            let zero = t.fb.add(Expression::Literal(Literal::U32(0)));
            t.binary(Op::NotEqual, bits, zero)
        }
        _ => t.fb.add(Expression::As { expr: bits, kind: ScalarKind::Float, convert: None }),
    }
}

fn to_bits(t: &mut Translator, v: Value, base: Base) -> Value {
    match base {
        Base::Uint => v,
        Base::Bool => t.fb.add(Expression::As { expr: v, kind: ScalarKind::Uint, convert: Some(4) }),
        _ => t.fb.add(Expression::As { expr: v, kind: ScalarKind::Uint, convert: None }),
    }
}

/// A value of type `ty` from its scalar components.
fn assemble(t: &mut Translator, words: &[Value], ty: Type) -> Value {
    if words.len() == 1 {
        return words[0];
    }
    let element = Type::of(ty.base);
    let per = ty.base.components() as usize;
    let elements: Vec<Value> = words
        .chunks(per)
        .map(|c| {
            if c.len() == 1 {
                return c[0];
            }
            match ty.base {
                Base::Matrix3 | Base::Matrix4 => {
                    let n = if ty.base == Base::Matrix3 { 3 } else { 4 };
                    let col_ty = t.mb.ty(Type::of(if n == 3 { Base::Float3 } else { Base::Float4 }), false);
                    let cols = c
                        .chunks(n)
                        .map(|r| t.fb.add(Expression::Compose { ty: col_ty, components: r.to_vec() }))
                        .collect();
                    let h = t.mb.ty(element, false);
                    t.fb.add(Expression::Compose { ty: h, components: cols })
                }
                _ => {
                    let h = t.mb.ty(element, false);
                    t.fb.add(Expression::Compose { ty: h, components: c.to_vec() })
                }
            }
        })
        .collect();
    if ty.is_array() {
        let h = t.mb.ty(ty, false);
        t.fb.add(Expression::Compose { ty: h, components: elements })
    } else {
        elements[0]
    }
}

/// The scalar components of a value of type `ty`, in the interpreter's order (matrices row by
/// row, which is WGSL's column by column).
fn disassemble(t: &mut Translator, v: Value, ty: Type) -> Vec<Value> {
    let n = ty.array.unwrap_or(0);
    let elements: Vec<Value> = if ty.is_array() {
        (0..n.max(1)).map(|i| t.fb.add(Expression::AccessIndex { base: v, index: i })).collect()
    } else {
        vec![v]
    };
    let mut out = Vec::new();
    for e in elements {
        match ty.base {
            Base::Matrix3 | Base::Matrix4 => {
                let side = if ty.base == Base::Matrix3 { 3 } else { 4 };
                for c in 0..side {
                    let col = t.fb.add(Expression::AccessIndex { base: e, index: c });
                    for r in 0..side {
                        out.push(t.fb.add(Expression::AccessIndex { base: col, index: r }));
                    }
                }
            }
            b if b.components() > 1 => {
                for c in 0..b.components() {
                    out.push(t.fb.add(Expression::AccessIndex { base: e, index: c }));
                }
            }
            _ => out.push(e),
        }
    }
    out
}
