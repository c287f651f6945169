//! The stage split: one shader becomes a host program (run once per draw), a vertex stage and a
//! fragment stage, with the values that cross between them.
//!
//! Each stage is a slice of the differentiated shader: the statements its outputs depend on.
//! A value computed at a lower rate than the stage that uses it crosses over when that is sound —
//! it is computed once where it is written (not in a loop, not per light), so the lower stage can
//! compute it at the same point of the program and hand it up: through the uniform block from the
//! host, or as a varying from the vertex stage. Everything else a stage needs it recomputes
//! (loop counters, per-light work, reads of inputs), which keeps every stage a plain,
//! self-contained program over its own inputs.
//!
//! The stages are ordinary [`Shader`](crate::ir::Shader)s (each a [`Prepared`] one, as the input was) sharing one numbering of locals and expressions with the
//! input: a value that crosses is a parameter local of both stages — an `output` parameter stored
//! by the producer, and in the consumer the expression is overwritten with a read of that
//! parameter. Inputs that every stage reads directly (predefined variables and parameters the
//! body never writes, derivative seeds) do not cross: the backends supply them per stage.

mod placement;
mod slice;
#[cfg(test)]
mod tests;

use smol_str::SmolStr;

use crate::diag::Diagnostic;
use crate::ir::LocalId;
use crate::ir::types::{Base, Type};
use crate::opt::Prepared;
use crate::source::Span;

/// A stage of the split program, in execution order.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum StageKind {
    /// Once per draw, on the CPU (the interpreter), into the uniform block.
    Host,
    /// Once per vertex.
    Vertex,
    /// Once per fragment.
    Fragment,
}

impl StageKind {
    /// The stage's name, for messages and generated names.
    pub fn name(self) -> &'static str {
        match self {
            StageKind::Host => "host",
            StageKind::Vertex => "vertex",
            StageKind::Fragment => "fragment",
        }
    }
}

/// A variable: a local or a predefined variable (by name).
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Var {
    Local(LocalId),
    Global(&'static str),
}

/// A value handed from one stage to later ones.
#[derive(Clone, Debug, PartialEq)]
pub struct Transfer {
    /// The parameter local that carries it (an output parameter of the producer, an input
    /// parameter of each consumer).
    pub local: LocalId,
    /// A readable name, unique in the program (also the local's name).
    pub name: SmolStr,
    /// Its type.
    pub ty: Type,
    /// The stage that computes it.
    pub from: StageKind,
    /// Whether the vertex stage reads it (only for values from the host).
    pub to_vertex: bool,
    /// Whether the fragment stage reads it.
    pub to_fragment: bool,
    /// The expression in the source.
    pub span: Span,
}

impl Transfer {
    /// Whether a varying carrying it must not be interpolated (integers and booleans).
    pub fn flat(&self) -> bool {
        matches!(self.ty.base, Base::Bool | Base::Int | Base::Uint)
    }
}

/// A shader split into its stages.
#[derive(Clone, Debug, PartialEq)]
pub struct Stages {
    /// Once per draw: computes the transfers `from` the host.
    pub host: Prepared,
    /// Per vertex: computes the varyings.
    pub vertex: Prepared,
    /// Per fragment: computes the outputs.
    pub fragment: Prepared,
    /// The values that cross between stages.
    pub transfers: Vec<Transfer>,
}

impl Stages {
    /// The shader of one stage.
    pub fn stage(&self, kind: StageKind) -> &Prepared {
        match kind {
            StageKind::Host => &self.host,
            StageKind::Vertex => &self.vertex,
            StageKind::Fragment => &self.fragment,
        }
    }

    /// The names of the values the host stage hands to the others (what the host program's
    /// run must read back besides the parameters).
    pub fn host_outputs(&self) -> Vec<String> {
        self.transfers.iter().filter(|t| t.from == StageKind::Host).map(|t| t.name.to_string()).collect()
    }
}

/// Splits a prepared shader into its stages. An error is an internal one: a value the placement
/// put in a stage that cannot compute it.
pub fn split(shader: &Prepared) -> Result<Stages, Diagnostic> {
    let stages = slice::split(shader, false)?;
    crate::verify::assert_valid_stages(&stages);
    Ok(stages)
}

/// As [`split`], with the host part folded into the GPU stages: the host hands nothing up, so
/// the uniform block holds only parameters, predefined variables, spaces and geometry, which a
/// program without Patina's interpreter can fill, and the vertex and fragment stages recompute
/// what the host would have computed once per draw (the cost of needing no host code).
pub fn split_folding_host(shader: &Prepared) -> Result<Stages, Diagnostic> {
    let stages = slice::split(shader, true)?;
    crate::verify::assert_valid_stages(&stages);
    Ok(stages)
}
