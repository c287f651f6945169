//! Texel fetches for the shared texture filter of `opt::textures`: `__texel2d`, `__texel3d` and
//! `__texsize2d`/`__texsize3d` as `textureLoad` and `textureDimensions`. Each texture the program reads is a
//! `texture_2d<f32>` or `texture_3d<f32>` at group 1, binding k, with no sampler (the fetches
//! use none, so the texture need not be filterable).

use naga::{
    AddressSpace, Expression, GlobalVariable, ImageClass, ImageDimension, ImageQuery, Literal,
    ResourceBinding, ScalarKind, Span, TypeInner, VectorSize,
};

use super::body::{Translator, Value};
use crate::diag::Diagnostic;
use crate::ir::builtin::BuiltinId;
use crate::ir::types::Base;
use crate::ir::{ExprId, ExprKind};

/// A texel-fetch built-in.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub(super) enum Fetch {
    /// `__texel2d` or `__texel3d`: a texel of a texture of this dimension.
    Texel(ImageDimension),
    /// `__texsize2d` or `__texsize3d`: a texture's size along an axis.
    Size(ImageDimension),
}

impl Fetch {
    /// The fetch `id` is, if it is one.
    pub(super) fn of(id: BuiltinId) -> Option<Fetch> {
        match id {
            BuiltinId::Texel2d => Some(Fetch::Texel(ImageDimension::D2)),
            BuiltinId::Texel3d => Some(Fetch::Texel(ImageDimension::D3)),
            BuiltinId::Texsize2d => Some(Fetch::Size(ImageDimension::D2)),
            BuiltinId::Texsize3d => Some(Fetch::Size(ImageDimension::D3)),
            _ => None,
        }
    }
}

impl Translator<'_> {
    /// A texel-fetch built-in (`coords`: the values of the arguments after the texture).
    pub(super) fn texel_builtin(
        &mut self,
        fetch: Fetch,
        args: &[ExprId],
        coords: &[Value],
    ) -> Result<Value, Diagnostic> {
        let dim = match fetch {
            Fetch::Texel(dim) => dim,
            Fetch::Size(dim) => {
                let axis = match &self.shader.expr(args[1]).kind {
                    ExprKind::Literal(crate::ir::Literal::Int(a)) => (*a).clamp(0, 2) as u32,
                    _ => 0,
                };
                let key = self.texture_key(args[0]);
                let image = self.texture(&key, dim);
                let size =
                    self.fb.add(Expression::ImageQuery { image, query: ImageQuery::Size { level: None } });
                let axis = if dim == ImageDimension::D2 { axis.min(1) } else { axis };
                let n = self.fb.add(Expression::AccessIndex { base: size, index: axis });
                return Ok(self.fb.add(Expression::As { expr: n, kind: ScalarKind::Sint, convert: Some(4) }));
            }
        };
        let key = self.texture_key(args[0]);
        let image = self.texture(&key, dim);
        let (size, count) =
            if dim == ImageDimension::D2 { (VectorSize::Bi, 2) } else { (VectorSize::Tri, 3) };
        let ty = self.mb.inner(TypeInner::Vector { size, scalar: naga::Scalar::I32 });
        let coordinate = self.fb.add(Expression::Compose { ty, components: coords[..count].to_vec() });
        let level = self.fb.add(Expression::Literal(Literal::I32(0)));
        Ok(self.fb.add(Expression::ImageLoad {
            image,
            coordinate,
            array_index: None,
            sample: None,
            level: Some(level),
        }))
    }

    /// The texture a name or `texref` argument denotes, as the interpreter decides it.
    fn texture_key(&self, id: ExprId) -> String {
        match &self.shader.expr(id).kind {
            ExprKind::Local(l) if self.shader.local(*l).ty.base == Base::Texref => {
                let local = self.shader.local(*l);
                self.strings
                    .iter()
                    .find(|(n, _)| *n == local.name)
                    .map_or_else(|| local.name.to_string(), |(_, v)| v.clone())
            }
            _ => self.fold_string(id).map(|s| s.to_string()).unwrap_or_default(),
        }
    }

    /// The image expression of a texture, declared on first use.
    fn texture(&mut self, key: &str, dim: ImageDimension) -> Value {
        let var = match self.mb.texture_var(key) {
            Some(v) => v,
            None => {
                let ty = self.mb.inner(TypeInner::Image {
                    dim,
                    arrayed: false,
                    class: ImageClass::Sampled { kind: ScalarKind::Float, multi: false },
                });
                let binding = self.mb.texture_count();
                let name = format!("tex_{}", super::module::sanitize(key));
                let v = self.mb.module.global_variables.append(
                    GlobalVariable {
                        name: Some(name),
                        space: AddressSpace::Handle,
                        binding: Some(ResourceBinding { group: 1, binding }),
                        ty,
                        init: None,
                        memory_decorations: naga::MemoryDecorations::empty(),
                    },
                    Span::UNDEFINED,
                );
                self.mb.add_texture(key, dim, binding, v);
                v
            }
        };
        self.fb.add(Expression::GlobalVariable(var))
    }
}
