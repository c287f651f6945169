//! The WGSL backend: the split stages of a shader, and the light shaders bound to it, as one naga
//! module with a vertex and a fragment entry point, validated, with its interface as data.
//!
//! - `module`: naga types, private variables, the uniform block and its layout.
//! - `func`: one naga function under construction (`Emit` ranges kept right).
//! - `body`: statements and expressions; `builtins` and `geometry`: the built-in functions.
//! - `entry`: the entry points (geometry, varyings, derivative seeds, lights, output).
//! - `interface`: what the runtime binds and fills, as data; `params`: the parameters it lists,
//!   with the defaults the caller's [`ParamDefaults`] computes.
//!
//! It does not import the interpreter (the `cpu` backend): what the two must agree on lives in
//! `backend` beside them, and the one thing the interpreter computes for this backend, the
//! parameters' constant defaults, is passed in.
//!
//! The module is handed to wgpu as naga IR (`ShaderSource::Naga`); [`GpuProgram::wgsl`] writes it
//! as WGSL text for users.

mod body;
mod builtins;
mod entry;
mod func;
mod geometry;
pub mod interface;
mod kernel;
mod lowering;
mod matrices;
mod module;
mod params;
mod strings;
mod tables;
mod textures;
mod uses;
mod values;

use naga::Span as NSpan;

use crate::backend::binding::{BoundLight, LightBinding};
use crate::diag::{Code, Diagnostic};
use crate::ir::Shader;
use crate::source::Span;
use crate::split::Stages;
pub use body::MAX_LIGHTS;
use body::Translator;
pub use entry::RANDOM_ROW;
use interface::{INTERFACE_VERSION, Interface, Output, UniformSource};
pub use kernel::{KERNEL_WORKGROUP, Kernel, KernelValue, compile_kernel, compile_kernel_lowered};
pub use lowering::Lowering;
use module::ModuleBuilder;
pub use params::ParamDefaults;

/// A compiled GPU program: the module, naga's analysis of it, and its interface.
#[derive(Clone, Debug)]
pub struct GpuProgram {
    /// The validated module (one vertex and one fragment entry point).
    pub module: naga::Module,
    /// The validator's information (needed to write WGSL).
    pub info: naga::valid::ModuleInfo,
    /// What the runtime binds and fills.
    pub interface: Interface,
    /// [`module_fingerprint`] of `module`, taken when it was compiled: the key under which the
    /// runtime keeps the module's render pipeline. Recompute it after editing `module`.
    pub fingerprint: u64,
}

/// A 64-bit hash of everything in `module` (its debug form, which names every type, constant,
/// expression and statement in arena order): equal modules hash equal, and different ones
/// collide with probability about 2^-64, so a pipeline cache can key on it.
pub fn module_fingerprint(module: &naga::Module) -> u64 {
    use std::fmt::Write as _;
    use std::hash::Hasher as _;
    /// Feeds formatted text straight into the hasher, so no string of the module is built.
    struct Feed(std::collections::hash_map::DefaultHasher);
    impl std::fmt::Write for Feed {
        fn write_str(&mut self, s: &str) -> std::fmt::Result {
            self.0.write(s.as_bytes());
            Ok(())
        }
    }
    let mut feed = Feed(std::collections::hash_map::DefaultHasher::new());
    let _ = write!(feed, "{module:?}");
    feed.0.finish()
}

impl GpuProgram {
    /// The module as WGSL text.
    pub fn wgsl(&self) -> Result<String, Diagnostic> {
        naga::back::wgsl::write_string(&self.module, &self.info, naga::back::wgsl::WriterFlags::empty())
            .map_err(|e| internal(Span::default(), format!("internal error: writing WGSL failed: {e}")))
    }
}

pub use crate::ir::is_ambient;

/// Compiles the stages of a surface shader with its bound lights into a validated module, in the
/// exact lowering. `defaults` gives the interface the parameters' constant defaults
/// (`backend::defaults::constant_defaults`, the interpreter's).
pub fn compile(
    stages: &Stages,
    lights: &[BoundLight],
    strings: &[(String, String)],
    defaults: &ParamDefaults,
) -> Result<GpuProgram, Diagnostic> {
    compile_object(stages, None, lights, strings, defaults)
}

/// As [`compile`], with a displacement shader run before the surface at each fragment (bump
/// mapping: it moves `P` and `N` for shading, not the geometry).
pub fn compile_object(
    stages: &Stages,
    displacement: Option<&BoundLight>,
    lights: &[BoundLight],
    strings: &[(String, String)],
    defaults: &ParamDefaults,
) -> Result<GpuProgram, Diagnostic> {
    compile_shaded(stages, displacement, None, lights, strings, Lowering::Exact, defaults)
}

/// As [`compile_object`], with an atmosphere (volume) shader run after the surface at each
/// fragment: it reads the surface's `Ci`, `Oi`, `P` and `I` and its `Ci` and `Oi` are the
/// fragment's colour and opacity (RenderMan's volume shader between the surface and the eye);
/// `lowering` chooses between the interpreter's bits and WGSL's built-ins ([`Lowering`]).
pub fn compile_shaded(
    stages: &Stages,
    displacement: Option<&BoundLight>,
    atmosphere: Option<&BoundLight>,
    lights: &[BoundLight],
    strings: &[(String, String)],
    lowering: Lowering,
    defaults: &ParamDefaults,
) -> Result<GpuProgram, Diagnostic> {
    body::check_light_count(&stages.fragment, &lights.iter().map(|l| l.shader.shader()).collect::<Vec<_>>())?;
    let bindings: Vec<LightBinding> = lights.iter().map(BoundLight::binding).collect();
    let mut mb = ModuleBuilder::new();
    mb.lowering = lowering;

    let mut light_functions = Vec::new();
    for (k, light) in lights.iter().enumerate() {
        check_stanford_light(&stages.fragment, light.shader)?;
        let prefix = format!("l{k}_");
        let lit = crate::opt::lights::unroll(light.shader, &[], &light.strings);
        let mut t = Translator::new(&mut mb, &lit, &prefix, &[], &light.strings, &format!("light{k}"));
        t.owner = Some(k);
        t.surface = Some(&stages.fragment);
        t.block(&lit.body)?;
        let f = std::mem::replace(&mut t.fb, func::FnBuilder::new("")).finish();
        drop(t);
        light_functions.push((mb.module.functions.append(f, NSpan::UNDEFINED), light.shader.shader()));
    }
    let body = |mb: &mut ModuleBuilder, shader: &Shader, name: &str| -> Result<_, Diagnostic> {
        let lit = crate::opt::lights::unroll(shader, &bindings, strings);
        let mut t = Translator::new(mb, &lit, "", &bindings, strings, name);
        t.light_shaders = lights.iter().map(|l| l.shader.shader()).collect();
        t.block(&lit.body)?;
        let f = std::mem::replace(&mut t.fb, func::FnBuilder::new("")).finish();
        drop(t);
        Ok(mb.module.functions.append(f, NSpan::UNDEFINED))
    };
    let displacement_function = match displacement {
        Some(d) => {
            let lit = crate::opt::lights::unroll(d.shader, &[], &d.strings);
            let mut t = Translator::new(&mut mb, &lit, "d_", &[], &d.strings, "displace");
            t.block(&lit.body)?;
            let f = std::mem::replace(&mut t.fb, func::FnBuilder::new("")).finish();
            drop(t);
            Some((mb.module.functions.append(f, NSpan::UNDEFINED), d.shader.shader()))
        }
        None => None,
    };
    let atmosphere_function = match atmosphere {
        Some(a) => {
            if stages.fragment.result_local.is_some() {
                return Err(Diagnostic::error(
                    Code::NotExecutable,
                    "an atmosphere shader needs a RenderMan-style surface (one that writes `Ci`)",
                    a.shader.span,
                    "this atmosphere",
                ));
            }
            let lit = crate::opt::lights::unroll(a.shader, &[], &a.strings);
            let mut t = Translator::new(&mut mb, &lit, "a_", &[], &a.strings, "atmosphere");
            t.surface = Some(&stages.fragment);
            t.block(&lit.body)?;
            let f = std::mem::replace(&mut t.fb, func::FnBuilder::new("")).finish();
            drop(t);
            Some((mb.module.functions.append(f, NSpan::UNDEFINED), a.shader.shader()))
        }
        None => None,
    };
    let vertex_body = body(&mut mb, &stages.vertex, "vertex_body")?;
    let fragment_body = body(&mut mb, &stages.fragment, "fragment_body")?;
    let (attributes, varyings) = entry::entry_points(
        &mut mb,
        stages,
        vertex_body,
        fragment_body,
        &light_functions,
        entry::Bound { displacement: displacement_function, atmosphere: atmosphere_function },
        strings,
    );
    let textures = mb.texture_slots();
    let (uniforms, uniform_size) = mb
        .finish_uniforms()
        .map_err(|e| internal(stages.fragment.span, format!("internal error: uniform layout: {e}")))?;
    let mb_uniform_var = mb.uniform_var;
    let module = mb.module;
    let info =
        naga::valid::Validator::new(naga::valid::ValidationFlags::all(), naga::valid::Capabilities::empty())
            .validate(&module)
            .map_err(|e| {
                internal(
                    stages.fragment.span,
                    format!("internal error: the generated module does not validate: {}", chain(&e)),
                )
            })?;
    let output = if stages.fragment.result_local.is_some() {
        Output::Result
    } else if atmosphere.is_some()
        || uses::Uses::of(&stages.fragment, &stages.fragment.body).written.contains("Oi")
    {
        Output::CiOi
    } else {
        Output::Ci
    };
    let mut interface = Interface {
        version: INTERFACE_VERSION,
        shader: stages.fragment.name.to_string(),
        vertex_entry: "vs_main".into(),
        fragment_entry: "fs_main".into(),
        uniform_struct: "Uniforms".into(),
        needs_host: uniforms.iter().any(|u| matches!(u.source, UniformSource::Host { .. })),
        uniforms,
        uniform_size,
        params: params::surface_parameters(stages, strings, defaults),
        lights: lights
            .iter()
            .map(|l| interface::LightInterface {
                shader: l.shader.name.to_string(),
                params: params::parameters(l.shader, &[], &l.strings, defaults),
            })
            .collect(),
        displacement: displacement.map(|d| interface::LightInterface {
            shader: d.shader.name.to_string(),
            params: params::parameters(d.shader, &[], &d.strings, defaults),
        }),
        atmosphere: atmosphere.map(|a| interface::LightInterface {
            shader: a.shader.name.to_string(),
            params: params::parameters(a.shader, &[], &a.strings, defaults),
        }),
        attributes,
        varyings,
        textures,
        output,
    };
    wgsl_names(&module, mb_uniform_var, &mut interface);
    let fingerprint = module_fingerprint(&module);
    Ok(GpuProgram { module, info, interface, fingerprint })
}

/// What a Stanford-style light reads of the surface point under a RenderMan-style surface, which
/// gives it its `P`, `N` and `E` in Stanford's terms (`entry::fragment`), with the light's own
/// `L` and `Sdist` and the uniform inputs; a Stanford surface gives it every input it has.
const STANFORD_LIGHT_FROM_RENDERMAN: [&str; 5] = ["P", "N", "E", "L", "Sdist"];

/// Refuses a Stanford-style light that reads a geometric input the surface cannot give it: a
/// RenderMan-style surface has no `Pobj`, `B`, `T` or raw `__position` in Stanford's sense.
fn check_stanford_light(surface: &Shader, light: &Shader) -> Result<(), Diagnostic> {
    if !light.stanford || surface.stanford {
        return Ok(());
    }
    let uses = uses::Uses::of(light, &light.body);
    let Some(g) = uses.globals.iter().find(|g| {
        g.frequency > crate::ir::types::Frequency::PrimitiveGroup
            && !STANFORD_LIGHT_FROM_RENDERMAN.contains(&g.name)
    }) else {
        return Ok(());
    };
    Err(Diagnostic::error(
        Code::NotExecutable,
        format!(
            "Stanford-style light `{}` reads `{}`, which RenderMan-style surface `{}` does not give a light",
            light.name, g.name, surface.name
        ),
        light.span,
        "this light",
    )
    .with_help(format!(
        "under a RenderMan-style surface a Stanford light sees {} and the uniform inputs; bind it to a \
         Stanford-style surface to read the rest",
        STANFORD_LIGHT_FROM_RENDERMAN.map(|n| format!("`{n}`")).join(", ")
    )))
}

/// Renames the interface's uniform members and its struct as naga's WGSL writer spells them (it
/// renames identifiers that end in a digit or collide with a keyword), so the interface's names
/// are the WGSL text's.
fn wgsl_names(
    module: &naga::Module,
    uniform_var: naga::Handle<naga::GlobalVariable>,
    interface: &mut Interface,
) {
    use naga::proc::{NameKey, Namer};
    let mut names = naga::FastHashMap::default();
    Namer::default().reset(
        module,
        &naga::keywords::wgsl::RESERVED_SET,
        &naga::keywords::wgsl::BUILTIN_IDENTIFIER_SET,
        naga::proc::CaseInsensitiveKeywordSet::empty(),
        &["__", "_naga"],
        &mut names,
    );
    let ty = module.global_variables[uniform_var].ty;
    if let Some(name) = names.get(&NameKey::Type(ty)) {
        interface.uniform_struct = name.clone();
    }
    for (i, field) in interface.uniforms.iter_mut().enumerate() {
        if let Some(name) = names.get(&NameKey::StructMember(ty, i as u32)) {
            field.name = name.clone();
        }
    }
}

/// An error's message with its causes.
pub(crate) fn chain(e: &dyn std::error::Error) -> String {
    let mut s = e.to_string();
    let mut source = e.source();
    while let Some(c) = source {
        s.push_str(" -> ");
        s.push_str(&c.to_string());
        source = c.source();
    }
    s
}

pub(crate) fn internal(span: Span, message: String) -> Diagnostic {
    Diagnostic::error(Code::Internal, message, span, "while compiling this shader")
        .with_help("this is a bug in Patina's WGSL backend; please report it with the shader")
}

#[cfg(test)]
mod tests;
