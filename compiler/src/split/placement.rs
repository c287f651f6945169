//! Which stage can compute each value: the stage of its rate, raised by what the value reads and
//! by the control flow it is computed under.
//!
//! Rates already say this for well-typed programs; placement recomputes it over the whole body so
//! that the split never moves a value to a stage that cannot compute it: a variable stored inside
//! `illuminance` is a fragment-stage value whatever its declared rate (lights are evaluated per
//! fragment), and a variable stored under a fragment-rate condition or after a fragment-rate early
//! exit belongs to the fragment stage.

use rustc_hash::FxHashMap;

use super::{StageKind, Var};
use crate::ir::types::{Frequency, Rate};
use crate::ir::{Block, ExprId, ExprKind, Place, Shader, Stmt};

/// The stage that computes values of `rate`.
pub(crate) fn stage_of(rate: Rate) -> StageKind {
    if rate.perlight {
        return StageKind::Fragment;
    }
    match rate.frequency {
        Frequency::Constant | Frequency::PrimitiveGroup => StageKind::Host,
        Frequency::Vertex => StageKind::Vertex,
        Frequency::Fragment => StageKind::Fragment,
    }
}

/// The variable a place stores into.
pub(crate) fn root(place: &Place) -> Var {
    match place {
        Place::Local(l) => Var::Local(*l),
        Place::Global(g) => Var::Global(g.name),
        Place::Index(inner, _) => root(inner),
    }
}

/// The earliest stage able to compute each variable and expression of a shader.
pub(crate) struct Placement {
    /// Variables that are stored somewhere in the body, with their stage.
    pub written: FxHashMap<Var, StageKind>,
    /// The stage of each expression.
    expr: Vec<StageKind>,
    /// For each `if` and inlined call that may leave its block early, the stage of the conditions
    /// under which it does, by the statement's address (the body does not move while placement
    /// runs); recomputed with `expr` each round, so that a chain of `else if`s is walked once,
    /// not once per link.
    exits: FxHashMap<*const Stmt, StageKind>,
}

impl Placement {
    /// Computes the placement of every value of `shader`.
    pub fn new(shader: &Shader) -> Placement {
        let mut p =
            Placement { written: FxHashMap::default(), expr: Vec::new(), exits: FxHashMap::default() };
        // Stages only rise, and there are three: the fixpoint is reached in a few rounds.
        loop {
            p.expr = exprs(shader, &p.written);
            p.exits.clear();
            p.exits_of(&shader.body);
            let before = p.written.clone();
            p.block(shader, &shader.body, StageKind::Host, false);
            if p.written == before {
                p.expr = exprs(shader, &p.written);
                return p;
            }
        }
    }

    /// The stage of expression `id`.
    pub fn of(&self, id: ExprId) -> StageKind {
        self.expr[id.0 as usize]
    }

    fn raise(&mut self, var: Var, stage: StageKind) {
        let entry = self.written.entry(var).or_insert(StageKind::Host);
        *entry = (*entry).max(stage);
    }

    fn block(&mut self, shader: &Shader, block: &Block, control: StageKind, light: bool) {
        let mut control = control;
        for stmt in block {
            self.statement(shader, stmt, control, light);
            // Everything after a statement that may leave early depends on why it left.
            control = control.max(self.exit_stage(stmt));
        }
    }

    fn statement(&mut self, shader: &Shader, stmt: &Stmt, control: StageKind, light: bool) {
        let at = |s: StageKind| if light { StageKind::Fragment } else { s.max(control) };
        match stmt {
            Stmt::Store { place, value, .. } => {
                let stage = at(self.of(*value).max(self.place_stage(place)));
                self.raise(root(place), stage);
            }
            Stmt::Eval(id) => {
                if let ExprKind::Builtin(b, args) = &shader.expr(*id).kind {
                    let stage = at(self.of(*id));
                    for (param, arg) in b.params.iter().zip(args) {
                        if let (true, ExprKind::Local(l)) = (param.output, &shader.expr(*arg).kind) {
                            self.raise(Var::Local(*l), stage);
                        }
                    }
                }
            }
            Stmt::If { cond, then, otherwise } => {
                let inner = control.max(self.of(*cond));
                self.block(shader, then, inner, light);
                self.block(shader, otherwise, inner, light);
            }
            Stmt::Loop { cond, body, step, .. } => {
                let mut inner = control.max(cond.map_or(StageKind::Host, |c| self.of(c)));
                inner = inner.max(self.exits_in(body));
                self.block(shader, body, inner, light);
                self.block(shader, step, inner, light);
            }
            Stmt::Inline { body, .. } => self.block(shader, body, control, light),
            Stmt::Illuminance { body, .. } | Stmt::Lights { body, .. } => {
                self.block(shader, body, StageKind::Fragment, true)
            }
            Stmt::Emit { body, .. } => self.block(shader, body, StageKind::Fragment, light),
            Stmt::Break(_) | Stmt::Continue(_) | Stmt::Return => {}
        }
    }

    fn place_stage(&self, place: &Place) -> StageKind {
        match place {
            Place::Local(_) | Place::Global(_) => StageKind::Host,
            Place::Index(inner, index) => self.place_stage(inner).max(self.of(*index)),
        }
    }

    /// The stage of the conditions under which `stmt` may leave its block early (`Host` when it
    /// never does, or does unconditionally).
    fn exit_stage(&self, stmt: &Stmt) -> StageKind {
        self.exits.get(&(stmt as *const Stmt)).copied().unwrap_or(StageKind::Host)
    }

    fn exits_in(&self, block: &Block) -> StageKind {
        block.iter().map(|s| self.exit_stage(s)).max().unwrap_or(StageKind::Host)
    }

    /// Whether `block` may leave early (a `break`, `continue` or `return` at any depth outside
    /// loops) and the stage of the conditions under which it does, recording the stage of each
    /// `if` and inlined call in it (nested ones, in loops and light constructs too) in `exits`:
    /// one walk of the body.
    fn exits_of(&mut self, block: &Block) -> (bool, StageKind) {
        let (mut leaves, mut stage) = (false, StageKind::Host);
        for stmt in block {
            let (l, s) = match stmt {
                Stmt::Break(_) | Stmt::Continue(_) | Stmt::Return => (true, StageKind::Host),
                Stmt::If { cond, then, otherwise } => {
                    let (lt, st) = self.exits_of(then);
                    let (lo, so) = self.exits_of(otherwise);
                    let l = lt || lo;
                    let s = if l { st.max(so).max(self.of(*cond)) } else { st.max(so) };
                    self.exits.insert(stmt as *const Stmt, s);
                    (l, s)
                }
                Stmt::Inline { body, .. } => {
                    let (l, s) = self.exits_of(body);
                    self.exits.insert(stmt as *const Stmt, s);
                    (l, s)
                }
                // Their own exits stay inside them; the statements in them are recorded.
                Stmt::Loop { body, step, .. } => {
                    self.exits_of(body);
                    self.exits_of(step);
                    (false, StageKind::Host)
                }
                Stmt::Illuminance { body, .. } | Stmt::Emit { body, .. } => {
                    self.exits_of(body);
                    (false, StageKind::Host)
                }
                _ => (false, StageKind::Host),
            };
            leaves |= l;
            stage = stage.max(s);
        }
        (leaves, stage)
    }
}

/// The stage of every expression, given the stages of the variables written in the body.
fn exprs(shader: &Shader, written: &FxHashMap<Var, StageKind>) -> Vec<StageKind> {
    let mut memo: Vec<Option<StageKind>> = vec![None; shader.exprs.len()];
    for id in 0..shader.exprs.len() {
        expr(shader, written, &mut memo, ExprId(id as u32));
    }
    memo.into_iter().map(|s| s.unwrap_or(StageKind::Fragment)).collect()
}

fn expr(
    shader: &Shader,
    written: &FxHashMap<Var, StageKind>,
    memo: &mut Vec<Option<StageKind>>,
    id: ExprId,
) -> StageKind {
    if let Some(s) = memo[id.0 as usize] {
        return s;
    }
    let e = shader.expr(id);
    let mut stage = stage_of(e.rate);
    match &e.kind {
        ExprKind::Local(l) => {
            let own = stage_of(shader.local(*l).rate);
            stage = stage.max(written.get(&Var::Local(*l)).map_or(own, |w| (*w).max(own)));
        }
        ExprKind::Global(g) => {
            if let Some(w) = written.get(&Var::Global(g.name)) {
                stage = stage.max(*w);
            }
        }
        ExprKind::Seed(..) => stage = StageKind::Fragment,
        kind => {
            let mut operands = Vec::new();
            kind.for_each_operand(|o| operands.push(o));
            for o in operands {
                stage = stage.max(crate::split::placement::expr(shader, written, memo, o));
            }
        }
    }
    memo[id.0 as usize] = Some(stage);
    stage
}

#[cfg(test)]
mod tests {
    //! `exits_of` (issue 23: one walk of the body, where each `if` used to walk its whole `else
    //! if` chain again) against the definition it replaced, statement by statement.

    use super::*;
    use crate::syntax::preprocess::MemoryLoader;

    /// The checked and differentiated shader of `src`.
    fn shader(src: &str) -> Shader {
        let checked = crate::check_source("placement.sl", src, &MemoryLoader::default());
        assert!(!checked.has_errors(), "{:?}", checked.diagnostics);
        let mut shader = checked.program.shaders[0].clone();
        crate::opt::derivs::differentiate(&mut shader);
        shader
    }

    /// Whether a block contains a `break`, `continue` or `return` at any depth outside loops.
    fn leaves(block: &Block) -> bool {
        block.iter().any(|s| match s {
            Stmt::Break(_) | Stmt::Continue(_) | Stmt::Return => true,
            Stmt::If { then, otherwise, .. } => leaves(then) || leaves(otherwise),
            Stmt::Inline { body, .. } => leaves(body),
            _ => false,
        })
    }

    /// The exit stage of `stmt` by the old definition: each `if` walks everything below it.
    fn reference(p: &Placement, stmt: &Stmt) -> StageKind {
        let within = |b: &Block| b.iter().map(|s| reference(p, s)).max().unwrap_or(StageKind::Host);
        match stmt {
            Stmt::If { cond, then, otherwise } => {
                let inner = within(then).max(within(otherwise));
                if leaves(then) || leaves(otherwise) { inner.max(p.of(*cond)) } else { inner }
            }
            Stmt::Inline { body, .. } => within(body),
            _ => StageKind::Host,
        }
    }

    /// Checks every statement of `block` (nested ones too) against the reference; returns how
    /// many `if`s and inlined calls were checked and how many leave under a condition the host
    /// cannot decide (`s` is per vertex).
    fn check(p: &Placement, block: &Block, counts: &mut (usize, usize)) {
        for stmt in block {
            assert_eq!(p.exit_stage(stmt), reference(p, stmt), "{stmt:?}");
            if matches!(stmt, Stmt::If { .. } | Stmt::Inline { .. }) {
                counts.0 += 1;
                counts.1 += usize::from(p.exit_stage(stmt) != StageKind::Host);
            }
            match stmt {
                Stmt::If { then, otherwise, .. } => {
                    check(p, then, counts);
                    check(p, otherwise, counts);
                }
                Stmt::Loop { body, step, .. } => {
                    check(p, body, counts);
                    check(p, step, counts);
                }
                Stmt::Inline { body, .. } | Stmt::Illuminance { body, .. } | Stmt::Emit { body, .. } => {
                    check(p, body, counts)
                }
                _ => {}
            }
        }
    }

    /// A chain of `n` links on `cond(i)`, link `k` (if any) leaving by `exit`.
    fn chain(n: usize, cond: &str, exit: Option<(usize, &str)>) -> String {
        (0..n)
            .map(|i| {
                let head = if i == 0 { "if" } else { "else if" };
                let body = match exit {
                    Some((k, e)) if k == i => e.to_string(),
                    _ => format!("v += {i};"),
                };
                format!("    {head} ({}) {{ {body} }}\n", cond.replace('#', &i.to_string()))
            })
            .collect()
    }

    #[test]
    fn exit_stages_match_the_definition_they_replaced() {
        let varying = "s < # / 40.0";
        let uniform = "u < #";
        let cases: Vec<(String, usize)> = vec![
            // A varying return deep in the chain: every link above it leaves, per vertex.
            (
                format!(
                    "surface c(float u = 0) {{\n    float v = 0;\n{}    Ci = v;\n}}\n",
                    chain(40, varying, Some((30, "return;")))
                ),
                31,
            ),
            // The same chain on a uniform parameter leaves on the host.
            (
                format!(
                    "surface c(float u = 0) {{\n    float v = 0;\n{}    Ci = v;\n}}\n",
                    chain(40, uniform, Some((30, "return;")))
                ),
                0,
            ),
            // No exit at all.
            (
                format!(
                    "surface c(float u = 0) {{\n    float v = 0;\n{}    Ci = v;\n}}\n",
                    chain(40, varying, None)
                ),
                0,
            ),
            // A `break` inside a loop stays inside it: the chain in the loop still records it.
            (
                format!(
                    "surface c(float u = 0) {{\n    float v = 0;\n    float i;\n    for (i = 0; i < 2; i += 1) {{\n{}    }}\n    Ci = v;\n}}\n",
                    chain(20, varying, Some((5, "break;")))
                ),
                6,
            ),
            // A return inside an inlined function called from a chain: the call leaves the
            // function under a varying condition (its own chain), nested in the shader's.
            (
                format!(
                    "float f(float x) {{\n    float v = 0;\n{}    return v;\n}}\nsurface c(float u = 0) {{\n    float v = 0;\n{}    Ci = v;\n}}\n",
                    chain(10, "x < # / 10.0", Some((4, "return 1;"))),
                    chain(10, varying, Some((3, "v = f(s);")))
                ),
                5 + 1 + 4,
            ),
        ];
        for (src, varying_exits) in cases {
            let shader = shader(&src);
            let p = Placement::new(&shader);
            let mut counts = (0, 0);
            check(&p, &shader.body, &mut counts);
            assert!(counts.0 >= 10, "{} ifs and calls checked in\n{src}", counts.0);
            assert_eq!(counts.1, varying_exits, "exits under varying conditions in\n{src}");
        }
    }
}
