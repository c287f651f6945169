//! The library API: compile a shader ([`Compiler`]), fill its uniform block ([`Uniforms`]),
//! and, with the `wgpu` feature, make its pipeline ([`gpu`](crate::gpu)).

mod compiler;
mod uniforms;
mod watch;

pub use compiler::{CompileError, Compiled, Compiler, Diagnostics, Light};
pub use uniforms::{UniformError, Uniforms, View};
pub use watch::{FileWatcher, Update, WatchError, Watcher};

use patina_compiler::ir::types::{Base, Type};

/// A parameter's value: numbers in the language's component order (one for a float, three for a
/// colour or point, sixteen for a matrix, element after element for arrays), or a string.
#[derive(Clone, Debug, PartialEq)]
#[non_exhaustive]
pub enum Value {
    /// Numbers.
    Numbers(Vec<f64>),
    /// A string (texture names, space names).
    String(String),
}

impl From<f64> for Value {
    fn from(x: f64) -> Value {
        Value::Numbers(vec![x])
    }
}

impl From<f32> for Value {
    fn from(x: f32) -> Value {
        Value::Numbers(vec![f64::from(x)])
    }
}

impl From<i32> for Value {
    fn from(x: i32) -> Value {
        Value::Numbers(vec![f64::from(x)])
    }
}

impl From<bool> for Value {
    fn from(x: bool) -> Value {
        Value::Numbers(vec![f64::from(u8::from(x))])
    }
}

impl<const N: usize> From<[f32; N]> for Value {
    fn from(x: [f32; N]) -> Value {
        Value::Numbers(x.iter().map(|v| f64::from(*v)).collect())
    }
}

impl<const N: usize> From<[f64; N]> for Value {
    fn from(x: [f64; N]) -> Value {
        Value::Numbers(x.to_vec())
    }
}

impl From<&[f64]> for Value {
    fn from(x: &[f64]) -> Value {
        Value::Numbers(x.to_vec())
    }
}

impl From<Vec<f64>> for Value {
    fn from(x: Vec<f64>) -> Value {
        Value::Numbers(x)
    }
}

impl From<glam::Vec3> for Value {
    fn from(x: glam::Vec3) -> Value {
        Value::from(x.to_array())
    }
}

impl From<glam::Mat4> for Value {
    /// In the layout of `to_cols_array`, which the language reads as a matrix written row by
    /// row (RenderMan's row-vector convention; see the interface's documentation).
    fn from(x: glam::Mat4) -> Value {
        Value::from(x.to_cols_array())
    }
}

impl From<&str> for Value {
    fn from(x: &str) -> Value {
        Value::String(x.to_string())
    }
}

impl From<String> for Value {
    fn from(x: String) -> Value {
        Value::String(x)
    }
}

/// The numbers a value of `ty` takes.
pub(crate) fn components(ty: Type) -> usize {
    ty.base.components() as usize * ty.array.map_or(1, |n| n as usize)
}

/// Whether a value of `ty` is given in world space and moved to camera space per view (as
/// `to_current` moves it).
pub(crate) fn depends_on_view(ty: Type) -> bool {
    !ty.is_array() && matches!(ty.base, Base::Point | Base::Vector | Base::Normal)
}
