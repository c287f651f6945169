//! The record of a predefined variable, [`Global`]: what a read of one in the IR
//! (`ExprKind::Global`, `Place::Global`, `Input::Global`) points to. The table of them, per shader
//! kind and style, and its lookup by name are the semantic stage's (`sema::globals`).

use super::types::{Base, Frequency};
use crate::syntax::ast::ShaderKind;

/// Whether a shader may read or write a predefined variable.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Access {
    /// Read only.
    Read,
    /// Read and written (an input the shader may change, or an output it may read back).
    ReadWrite,
}

/// Which surface style sees a predefined variable.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Styles {
    /// RenderMan-style shaders and functions.
    RenderMan,
    /// Stanford-style shaders and functions.
    Stanford,
    /// Both.
    Both,
}

/// Where in a shader a predefined variable exists.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub enum Scope {
    /// Everywhere in the shader.
    Anywhere,
    /// In a surface shader only inside `illuminance` (one value per light: `L`, `Cl`); in Stanford
    /// surface shaders anywhere, as a `perlight` value.
    PerLight,
}

/// A predefined variable.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
pub struct Global {
    /// Its name.
    pub name: &'static str,
    /// Its type.
    pub ty: Base,
    /// How often it changes.
    pub frequency: Frequency,
    /// Whether there is one value per light.
    pub perlight: bool,
    /// Read only, or read and written.
    pub access: Access,
    /// The shader kinds that have it.
    pub shaders: &'static [ShaderKind],
    /// The styles that see it.
    pub styles: Styles,
    /// Where it exists.
    pub scope: Scope,
    /// What it is, for `patina explain` and the docs.
    pub doc: &'static str,
}

impl Global {
    /// Whether a shader of `kind`, written in Stanford style when `stanford`, has this variable.
    pub fn seen_by(&self, kind: ShaderKind, stanford: bool) -> bool {
        self.shaders.contains(&kind)
            && match self.styles {
                Styles::Both => true,
                Styles::RenderMan => !stanford,
                Styles::Stanford => stanford,
            }
    }
}
