//! What a body reads and writes: its variables, predefined variables and derivative seeds, so the
//! entry points initialize exactly the inputs it uses.

use crate::ir::builtin::BuiltinId;
use rustc_hash::FxHashSet;

use crate::ir::global::Global;
use crate::ir::{Axis, Block, ExprId, ExprKind, Input, LocalId, Place, Shader, Stmt};

/// The inputs and variables a body touches.
#[derive(Default)]
pub(crate) struct Uses {
    pub locals: FxHashSet<LocalId>,
    pub globals: Vec<&'static Global>,
    /// Globals the body stores into.
    pub written: FxHashSet<&'static str>,
    pub seeds: Vec<(Input, Axis, ExprId)>,
    /// Whether the body reads the fragment's window position (`xyz_screen`).
    pub screen: bool,
    /// Whether the body calls `random()` (which hashes the point index).
    pub random: bool,
    seen: FxHashSet<ExprId>,
}

impl Uses {
    /// Scans a body.
    pub fn of(shader: &Shader, body: &Block) -> Uses {
        let mut u = Uses::default();
        u.block(shader, body);
        u
    }

    /// Whether the body touches predefined variable `name`.
    pub fn has_global(&self, name: &str) -> bool {
        self.globals.iter().any(|g| g.name == name)
    }

    fn global(&mut self, g: &'static Global) {
        if !self.has_global(g.name) {
            self.globals.push(g);
        }
    }

    fn block(&mut self, shader: &Shader, block: &Block) {
        for stmt in block {
            match stmt {
                Stmt::Store { place, value, .. } => {
                    self.place(shader, place);
                    self.expr(shader, *value);
                }
                Stmt::Eval(id) => self.expr(shader, *id),
                Stmt::If { cond, then, otherwise } => {
                    self.expr(shader, *cond);
                    self.block(shader, then);
                    self.block(shader, otherwise);
                }
                Stmt::Loop { cond, body, step, .. } => {
                    if let Some(c) = cond {
                        self.expr(shader, *c);
                    }
                    self.block(shader, body);
                    self.block(shader, step);
                }
                Stmt::Inline { body, .. } | Stmt::Lights { body, .. } => self.block(shader, body),
                Stmt::Illuminance { args, body } | Stmt::Emit { args, body, .. } => {
                    for a in args {
                        self.expr(shader, *a);
                    }
                    self.block(shader, body);
                }
                Stmt::Break(_) | Stmt::Continue(_) | Stmt::Return => {}
            }
        }
    }

    fn place(&mut self, shader: &Shader, place: &Place) {
        match place {
            Place::Local(l) => {
                self.locals.insert(*l);
            }
            Place::Global(g) => {
                self.global(g);
                self.written.insert(g.name);
            }
            Place::Index(inner, index) => {
                self.place(shader, inner);
                self.expr(shader, *index);
            }
        }
    }

    fn expr(&mut self, shader: &Shader, id: ExprId) {
        if !self.seen.insert(id) {
            return;
        }
        match &shader.expr(id).kind {
            ExprKind::Local(l) => {
                self.locals.insert(*l);
            }
            ExprKind::Global(g) => self.global(g),
            ExprKind::Seed(input, axis) => {
                self.seeds.push((*input, *axis, id));
                match input {
                    Input::Global(g) => self.global(g),
                    Input::Param(l) => {
                        self.locals.insert(*l);
                    }
                }
            }
            kind => {
                if let ExprKind::Builtin(b, _) = kind {
                    self.screen |= b.id == BuiltinId::XyzScreen;
                    self.random |= b.id == BuiltinId::Random;
                }
                kind.for_each_operand(|o| self.expr(shader, o))
            }
        }
    }
}
