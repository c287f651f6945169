//! Binding (DESIGN.md §4): a shader specialized for what a scene fixes. Parameters the scene fixes
//! become constants (`fold.rs`), and so do comparisons of strings (which are always known at
//! compile time: the scene's value or the default); conditions that become constant decide their
//! branches at compile time, also inside inlined functions whose parameters received a fixed
//! parameter or a literal (a library function's mode or variant argument), and the code nobody
//! reads any more, or that follows a `return` always taken, is dropped (`prune.rs`). What remains is a smaller
//! shader with the same meaning for that binding; the split and both backends then leave out the
//! uniforms, textures, varyings and functions it no longer reads.
//!
//! The values a specialized shader computes are bit for bit those of the unspecialized one: a
//! fixed parameter becomes a literal of the value the uniform block would hold, and only
//! conditions are evaluated here (in f64, as the host evaluates per-draw conditions), never the
//! values they choose between.

mod fold;
mod prune;
mod strings;

use crate::ir::{LocalKind, Shader};
use crate::source::Span;
use crate::verify::{Pass, assert_valid};

/// The value a scene fixes for one parameter: its components, in the language's order.
#[derive(Clone, Debug, PartialEq)]
pub struct Fixed {
    /// The parameter's name.
    pub name: String,
    /// Its value (one number for scalars, three for colours and points, ...).
    pub value: Vec<f64>,
}

/// What binding decided or left out, and why: for `patina explain` and for tests.
#[derive(Clone, Debug, PartialEq)]
pub enum Decision {
    /// A parameter became a constant.
    Folded {
        /// The parameter.
        name: String,
        /// Its value.
        value: Vec<f64>,
    },
    /// A conditional statement (or `?:`) was decided at compile time; the other side is gone.
    Branch {
        /// The condition.
        condition: Span,
        /// Which side remains.
        taken: bool,
        /// The fixed parameters the condition reads.
        because: Vec<String>,
    },
    /// A loop whose condition is false from the start is gone.
    Loop {
        /// The condition.
        condition: Span,
        /// The fixed parameters the condition reads.
        because: Vec<String>,
    },
    /// An output parameter the caller does not consume: the code that only computed it is gone.
    UnconsumedOutput {
        /// The parameter.
        name: String,
    },
    /// Stores into a variable that nothing reads any more are gone.
    DeadVariable {
        /// The variable.
        name: String,
        /// Where it was declared.
        declared: Span,
    },
}

/// Which of a shader's `output` parameters the caller reads back (RenderMan's arbitrary output
/// values); the stores into the others are dead once nothing else reads them.
#[derive(Copy, Clone, Debug, PartialEq)]
pub enum Consumed<'a> {
    /// Every output parameter (a caller that may read any of them).
    All,
    /// Only these (the renderer reads none: it consumes `Ci`, `Oi` or the result).
    Only(&'a [&'a str]),
}

impl Consumed<'_> {
    fn includes(&self, name: &str) -> bool {
        match self {
            Consumed::All => true,
            Consumed::Only(names) => names.contains(&name),
        }
    }
}

/// A specialized shader and what binding decided.
#[derive(Clone, Debug)]
pub struct Bound {
    /// The shader for this binding.
    pub shader: Shader,
    /// What was folded, decided and removed, in that order.
    pub decisions: Vec<Decision>,
}

/// Specializes `shader` for the parameter values in `fixed` (names it does not declare, output
/// parameters, parameters the shader writes and values of the wrong width are left dynamic) and
/// the string parameters' values in `strings` (the others keep their defaults), for a caller that
/// reads back the `consumed` output parameters.
pub fn specialize(
    shader: &Shader,
    fixed: &[Fixed],
    strings: &[(String, String)],
    consumed: Consumed,
) -> Bound {
    let mut shader = shader.clone();
    strings::propagate(&mut shader);
    assert_valid(&shader, Pass::Bind("string variables"));
    let (mut decisions, mut reads) = fold::substitute(&mut shader, fixed);
    assert_valid(&shader, Pass::Bind("fixed parameters"));
    fold::compare_strings(&mut shader, strings, &mut reads);
    assert_valid(&shader, Pass::Bind("string comparisons"));
    let (decided, changed) = prune::decide(&mut shader, &reads);
    decisions.extend(decided);
    assert_valid(&shader, Pass::Bind("decided branches"));
    let unconsumed: Vec<String> = shader
        .params
        .iter()
        .map(|p| shader.local(*p))
        .filter(|l| matches!(l.kind, LocalKind::Param { output: true, .. }) && !consumed.includes(&l.name))
        .map(|l| l.name.to_string())
        .collect();
    if changed || !unconsumed.is_empty() {
        decisions.extend(unconsumed.iter().map(|name| Decision::UnconsumedOutput { name: name.clone() }));
        decisions.extend(prune::dead_stores(&mut shader, &unconsumed));
        assert_valid(&shader, Pass::Bind("dead stores"));
    }
    Bound { shader, decisions }
}

#[cfg(test)]
mod tests;
