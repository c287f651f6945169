//! The module being built: naga types for the language's types, the per-invocation variables that
//! hold every language variable, and the uniform block, whose members are added as the stages ask
//! for them and laid out at the end with `naga::proc::Layouter`.

use naga::{
    AddressSpace, ArraySize, GlobalVariable, Handle, Module, ResourceBinding, Scalar, Span, StructMember,
    TypeInner, VectorSize,
};
use rustc_hash::FxHashMap;

use super::interface::{FieldLayout, ScalarKind, UniformField, UniformSource};
use crate::ir::types::{Base, Type};

/// The module and what has been added to it.
pub(crate) struct ModuleBuilder {
    pub module: Module,
    types: FxHashMap<(Type, bool), Handle<naga::Type>>,
    /// Private variables by name, so each name is made once.
    privates: FxHashMap<String, Handle<GlobalVariable>>,
    /// The uniform block variable (its type is set by [`ModuleBuilder::finish_uniforms`]).
    pub uniform_var: Handle<GlobalVariable>,
    /// The members asked for so far: (name, language type, source).
    uniforms: Vec<(String, Type, UniformSource)>,
    /// The textures read: (name, dimension, binding, variable).
    textures: Vec<(String, naga::ImageDimension, u32, Handle<GlobalVariable>)>,
    /// Constant tables by type and contents (`tables.rs`).
    pub(super) tables: FxHashMap<(Type, Vec<u64>), Handle<GlobalVariable>>,
    /// The uniform block's bytes taken by tables so far, and the most they may take
    /// (`tables.rs`).
    table_bytes: u32,
    table_budget: u32,
    /// How the built-ins are written (`lowering.rs`).
    pub lowering: super::Lowering,
}

/// A naga scalar for the language's scalar bases.
pub(crate) fn scalar_of(base: Base) -> Scalar {
    match base {
        Base::Int => Scalar::I32,
        Base::Uint => Scalar::U32,
        Base::Bool => Scalar::BOOL,
        _ => Scalar::F32,
    }
}

/// The vector size for `n` components.
pub(crate) fn vector_size(n: u32) -> VectorSize {
    match n {
        2 => VectorSize::Bi,
        3 => VectorSize::Tri,
        _ => VectorSize::Quad,
    }
}

impl ModuleBuilder {
    pub fn new() -> Self {
        let mut module = Module::default();
        let placeholder = module
            .types
            .insert(naga::Type { name: None, inner: TypeInner::Scalar(Scalar::F32) }, Span::UNDEFINED);
        let uniform_var = module.global_variables.append(
            GlobalVariable {
                name: Some("u".into()),
                space: AddressSpace::Uniform,
                binding: Some(ResourceBinding { group: 0, binding: 0 }),
                ty: placeholder,
                init: None,
                memory_decorations: naga::MemoryDecorations::empty(),
            },
            Span::UNDEFINED,
        );
        ModuleBuilder {
            module,
            types: FxHashMap::default(),
            privates: FxHashMap::default(),
            uniform_var,
            uniforms: Vec::new(),
            textures: Vec::new(),
            tables: FxHashMap::default(),
            table_bytes: 0,
            table_budget: super::tables::TABLE_BUDGET,
            lowering: super::Lowering::Exact,
        }
    }

    /// A builder whose tables all stay module variables: for kernels, whose callers bind no
    /// uniform block unless a shader reads a named space.
    pub fn without_uniform_tables() -> Self {
        ModuleBuilder { table_budget: 0, ..ModuleBuilder::new() }
    }

    /// The variable of texture `name`, if declared.
    pub fn texture_var(&self, name: &str) -> Option<Handle<GlobalVariable>> {
        self.textures.iter().find(|t| t.0 == name).map(|t| t.3)
    }

    /// How many textures are declared.
    pub fn texture_count(&self) -> u32 {
        self.textures.len() as u32
    }

    /// Records a declared texture.
    pub fn add_texture(
        &mut self,
        name: &str,
        dim: naga::ImageDimension,
        binding: u32,
        var: Handle<GlobalVariable>,
    ) {
        self.textures.push((name.to_string(), dim, binding, var));
    }

    /// The textures for the interface.
    pub fn texture_slots(&self) -> Vec<super::interface::TextureSlot> {
        self.textures
            .iter()
            .map(|(name, dim, binding, _)| super::interface::TextureSlot {
                name: name.clone(),
                dimensions: if *dim == naga::ImageDimension::D3 { 3 } else { 2 },
                binding: *binding,
            })
            .collect()
    }

    /// The naga type of a language type; `uniform` gives the uniform block's form, where array
    /// elements are padded to 16 bytes (`vec4`).
    pub fn ty(&mut self, t: Type, uniform: bool) -> Handle<naga::Type> {
        if let Some(h) = self.types.get(&(t, uniform)) {
            return *h;
        }
        let inner = match t.array {
            Some(n) => {
                let element = Type::of(t.base);
                let (base, stride) = if uniform && t.base.components() < 4 && !is_matrix(t.base) {
                    (
                        self.inner(TypeInner::Vector {
                            size: VectorSize::Quad,
                            scalar: uniform_scalar(t.base),
                        }),
                        16,
                    )
                } else {
                    let h = self.ty(element, uniform);
                    (h, element_size(t.base))
                };
                TypeInner::Array {
                    base,
                    size: ArraySize::Constant(std::num::NonZeroU32::new(n.max(1)).expect("max(1)")),
                    stride,
                }
            }
            None => self.base_inner(t.base, uniform),
        };
        let h = self.inner(inner);
        self.types.insert((t, uniform), h);
        h
    }

    fn base_inner(&mut self, base: Base, uniform: bool) -> TypeInner {
        let scalar = if uniform { uniform_scalar(base) } else { scalar_of(base) };
        match base.components() {
            3 | 4 if !is_matrix(base) => {
                TypeInner::Vector { size: vector_size(base.components()), scalar: Scalar::F32 }
            }
            9 => TypeInner::Matrix { columns: VectorSize::Tri, rows: VectorSize::Tri, scalar: Scalar::F32 },
            16 => {
                TypeInner::Matrix { columns: VectorSize::Quad, rows: VectorSize::Quad, scalar: Scalar::F32 }
            }
            _ => TypeInner::Scalar(scalar),
        }
    }

    /// A type by its shape.
    pub fn inner(&mut self, inner: TypeInner) -> Handle<naga::Type> {
        self.module.types.insert(naga::Type { name: None, inner }, Span::UNDEFINED)
    }

    /// The private (per-invocation) variable `name` of type `t`, made on first use.
    pub fn private(&mut self, name: &str, t: Type) -> Handle<GlobalVariable> {
        if let Some(h) = self.privates.get(name) {
            return *h;
        }
        let ty = self.ty(t, false);
        let h = self.module.global_variables.append(
            GlobalVariable {
                name: Some(name.to_string()),
                space: AddressSpace::Private,
                binding: None,
                ty,
                init: None,
                memory_decorations: naga::MemoryDecorations::empty(),
            },
            Span::UNDEFINED,
        );
        self.privates.insert(name.to_string(), h);
        h
    }

    /// The index of the uniform member for `source` of type `t`, added on first use.
    pub fn uniform(&mut self, name: &str, t: Type, source: UniformSource) -> u32 {
        if let Some(i) = self.uniforms.iter().position(|(_, ty, s)| *s == source && *ty == t) {
            return i as u32;
        }
        let mut unique = sanitize(name);
        let mut n = 1;
        while self.uniforms.iter().any(|(m, _, _)| *m == unique) {
            unique = format!("{}_{n}", sanitize(name));
            n += 1;
        }
        self.uniforms.push((unique, t, source));
        (self.uniforms.len() - 1) as u32
    }

    /// The uniform member for a table's `source` of type `t`, taking `bytes` of the tables'
    /// budget when it is new; `None` when it does not fit.
    pub fn uniform_table(&mut self, name: &str, t: Type, source: UniformSource, bytes: u32) -> Option<u32> {
        let known = self.uniforms.iter().any(|(_, ty, s)| *s == source && *ty == t);
        if !known {
            if self.table_bytes + bytes > self.table_budget {
                return None;
            }
            self.table_bytes += bytes;
        }
        Some(self.uniform(name, t, source))
    }

    /// Lays out the uniform block (std140-like rules, as WGSL's uniform address space requires)
    /// and gives the block variable its type. Returns the fields and the size.
    pub fn finish_uniforms(&mut self) -> Result<(Vec<UniformField>, u32), String> {
        let members: Vec<(String, Type, UniformSource)> = self.uniforms.clone();
        let handles: Vec<Handle<naga::Type>> = members.iter().map(|(_, t, _)| self.ty(*t, true)).collect();
        let mut layouter = naga::proc::Layouter::default();
        layouter.update(self.module.to_ctx()).map_err(|e| e.to_string())?;
        let mut offset = 0u32;
        let mut struct_members = Vec::new();
        let mut fields = Vec::new();
        for ((name, t, source), h) in members.into_iter().zip(handles) {
            let l = layouter[h];
            offset = l.alignment.round_up(offset);
            struct_members.push(StructMember { name: Some(name.clone()), ty: h, binding: None, offset });
            fields.push(UniformField { name, source, ty: t.to_string(), offset, layout: field_layout(t) });
            offset += l.size;
        }
        // A block with no members would be an empty struct, which WGSL forbids: keep one word.
        if struct_members.is_empty() {
            let h = self.inner(TypeInner::Scalar(Scalar::U32));
            struct_members.push(StructMember {
                name: Some("unused".into()),
                ty: h,
                binding: None,
                offset: 0,
            });
            offset = 4;
        }
        let span = offset.div_ceil(16) * 16;
        let ty = self.module.types.insert(
            naga::Type {
                name: Some("Uniforms".into()),
                inner: TypeInner::Struct { members: struct_members, span },
            },
            Span::UNDEFINED,
        );
        self.module.global_variables[self.uniform_var].ty = ty;
        Ok((fields, span))
    }
}

fn is_matrix(base: Base) -> bool {
    matches!(base, Base::Matrix3 | Base::Matrix4)
}

/// Booleans cross the uniform block as `u32`.
fn uniform_scalar(base: Base) -> Scalar {
    match base {
        Base::Bool => Scalar::U32,
        b => scalar_of(b),
    }
}

fn element_size(base: Base) -> u32 {
    match base {
        Base::Matrix3 => 48,
        Base::Matrix4 => 64,
        b if b.components() >= 3 => 16,
        _ => 4,
    }
}

fn field_layout(t: Type) -> FieldLayout {
    let elements = t.array.unwrap_or(1).max(1);
    let components = t.base.components();
    let element_stride = if t.is_array() && !is_matrix(t.base) { 16 } else { element_size(t.base) };
    FieldLayout {
        components,
        elements,
        element_stride,
        column_stride: if t.base == Base::Matrix3 { 16 } else { 0 },
        scalar: match t.base {
            Base::Int => ScalarKind::I32,
            Base::Uint | Base::Bool => ScalarKind::U32,
            _ => ScalarKind::F32,
        },
    }
}

/// A name usable as a WGSL identifier.
pub(crate) fn sanitize(name: &str) -> String {
    let mut s: String =
        name.chars().map(|c| if c.is_ascii_alphanumeric() || c == '_' { c } else { '_' }).collect();
    if s.is_empty() || s.starts_with(|c: char| c.is_ascii_digit()) {
        s.insert(0, 'v');
    }
    // WGSL reserves identifiers starting with two underscores.
    while s.starts_with("__") {
        s.remove(0);
    }
    s
}

/// An entry point of `stage` running `function` (`workgroup` only for compute).
pub(crate) fn entry_point(
    name: &str,
    stage: naga::ShaderStage,
    workgroup: [u32; 3],
    function: naga::Function,
) -> naga::EntryPoint {
    naga::EntryPoint {
        name: name.into(),
        stage,
        early_depth_test: None,
        workgroup_size: workgroup,
        workgroup_size_overrides: None,
        function,
        mesh_info: None,
        task_payload: None,
        incoming_ray_payload: None,
    }
}
