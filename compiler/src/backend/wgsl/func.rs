//! Building one naga function: expressions appended with their `Emit` ranges kept right, and
//! statements pushed into the innermost open block.

use naga::{Block, Expression, Function, Handle, Span, Statement};

/// A function under construction.
pub(crate) struct FnBuilder {
    pub f: Function,
    /// Open blocks, innermost last.
    blocks: Vec<Block>,
    /// The first expression not yet covered by an `Emit`.
    start: usize,
}

impl FnBuilder {
    pub fn new(name: &str) -> Self {
        FnBuilder {
            f: Function { name: Some(name.to_string()), ..Default::default() },
            blocks: vec![Block::new()],
            start: 0,
        }
    }

    /// Appends an expression. Expressions that naga treats as already in scope (literals,
    /// variables, arguments) must stay out of `Emit` ranges, so the pending range is closed first.
    pub fn add(&mut self, e: Expression) -> Handle<Expression> {
        if e.needs_pre_emit() {
            self.flush();
            let h = self.f.expressions.append(e, Span::UNDEFINED);
            self.start = self.f.expressions.len();
            h
        } else {
            self.f.expressions.append(e, Span::UNDEFINED)
        }
    }

    /// Appends an expression that a statement, not an `Emit`, brings into scope (a call's result).
    pub fn add_unemitted(&mut self, e: Expression) -> Handle<Expression> {
        self.flush();
        let h = self.f.expressions.append(e, Span::UNDEFINED);
        self.start = self.f.expressions.len();
        h
    }

    /// Closes the pending `Emit` range.
    fn flush(&mut self) {
        if self.start < self.f.expressions.len() {
            let range = self.f.expressions.range_from(self.start);
            self.blocks.last_mut().expect("a block is open").push(Statement::Emit(range), Span::UNDEFINED);
        }
        self.start = self.f.expressions.len();
    }

    /// Pushes a statement after the expressions it uses.
    pub fn push(&mut self, s: Statement) {
        self.flush();
        self.blocks.last_mut().expect("a block is open").push(s, Span::UNDEFINED);
    }

    /// Opens a nested block.
    pub fn open(&mut self) {
        self.flush();
        self.blocks.push(Block::new());
    }

    /// Closes the innermost block and returns it.
    pub fn close(&mut self) -> Block {
        self.flush();
        self.blocks.pop().unwrap_or_default()
    }

    /// Finishes the function (its body is the outermost block).
    pub fn finish(mut self) -> Function {
        self.flush();
        self.f.body = self.blocks.pop().unwrap_or_default();
        self.f
    }
}
