//! Statements: stores (through run-time indices too), structured control flow, and light loops
//! (`Stmt::Lights`, which `opt::lights` made of the light constructs), run once per listed light.

use super::{Lower, Val};
use crate::backend::cpu::code::{IntBinary, Node, Reg};
use crate::diag::{Code as DiagCode, Diagnostic};
use crate::ir::types::{Base, Type};
use crate::ir::{ExprId, ExprKind, Literal, Place, Stmt};
use crate::source::Span;

/// A part of a variable's registers: `width` components from `offset`, or, with `dynamic`, the
/// element a run-time index selects.
pub(crate) struct Access {
    /// Every register of the root variable (contiguous).
    pub root: Vec<Reg>,
    /// Whether they are floats.
    pub float: bool,
    /// The first component addressed (of element 0, with `dynamic`).
    pub offset: u32,
    /// The number of components addressed.
    pub width: u32,
    /// A run-time element index.
    pub dynamic: Option<Dynamic>,
}

/// A run-time index into an array of registers.
#[derive(Copy, Clone)]
pub(crate) struct Dynamic {
    /// The index register (integer file).
    pub index: Reg,
    /// Whether it is an `int` (negative values clamp to 0) or a `uint`.
    pub signed: bool,
    /// The number of elements.
    pub len: u32,
    /// The components between consecutive elements.
    pub stride: u32,
}

impl Lower<'_> {
    pub(super) fn statement(&mut self, stmt: &Stmt) -> Result<(), Diagnostic> {
        self.next_statement();
        match stmt {
            Stmt::Store { place, value, span } => {
                let v = self.expr(*value)?;
                let access = self.access(place)?;
                self.store(&access, &v, *span)?;
            }
            Stmt::Eval(id) => {
                self.expr(*id)?;
            }
            Stmt::If { cond, then, otherwise } => {
                let cond = self.condition(*cond)?;
                let then = self.block(then)?;
                let otherwise = self.block(otherwise)?;
                self.emit.out.push(Node::If { cond, then, otherwise });
            }
            Stmt::Loop { cond, body, step, span } => {
                let (test, cond) = match cond {
                    Some(c) => {
                        let outer = std::mem::take(&mut self.emit.out);
                        let reg = self.condition(*c);
                        let test = std::mem::replace(&mut self.emit.out, outer);
                        (test, Some(reg?))
                    }
                    None => (Vec::new(), None),
                };
                let body = self.block(body)?;
                let step = self.block(step)?;
                self.emit.out.push(Node::Loop { test, cond, body, step, span: *span });
            }
            Stmt::Break(n) => self.emit.out.push(Node::Break(*n)),
            Stmt::Continue(n) => self.emit.out.push(Node::Continue(*n)),
            Stmt::Return => self.emit.out.push(Node::Return),
            Stmt::Inline { body, .. } => {
                let mut body = self.block(body)?;
                // Falling off the end is the same as a final `return`, which would only cost mask
                // bookkeeping.
                if body.last() == Some(&Node::Return) {
                    body.pop();
                }
                self.emit.out.push(Node::Function(body));
            }
            Stmt::Lights { lights, body } => {
                for &k in lights {
                    let outer = self.light.replace(k as usize);
                    let result = body.iter().try_for_each(|s| self.statement(s));
                    self.light = outer;
                    result?;
                }
            }
            Stmt::Illuminance { .. } | Stmt::Emit { .. } => {
                return Err(Diagnostic::error(
                    DiagCode::Internal,
                    "a light construct reached the interpreter",
                    self.shader.span,
                    "in this shader",
                )
                .with_note("opt::lights::unroll must run before the interpreter's lowering"));
            }
        }
        Ok(())
    }

    /// A condition as a bool register.
    pub(super) fn condition(&mut self, id: ExprId) -> Result<Reg, Diagnostic> {
        let v = self.expr(id)?;
        Ok(self.truth(&v))
    }

    /// Non-zero is true.
    pub(super) fn truth(&mut self, v: &Val) -> Reg {
        match v {
            Val::Float(r) => self.emit.convert(crate::backend::cpu::code::Convert::FloatToBool, r[0]),
            Val::Int(r) => r[0],
            Val::Str(_) | Val::Void => self.emit.int(0),
        }
    }

    /// Where a place's registers are.
    pub(super) fn access(&mut self, place: &Place) -> Result<Access, Diagnostic> {
        match place {
            Place::Local(id) => Ok(whole(self.local(*id))),
            Place::Global(g) => Ok(whole(self.global(g))),
            Place::Index(inner, index) => {
                let ty = self.shader.place_type(inner);
                let a = self.access(inner)?;
                self.index_access(a, ty, *index)
            }
        }
    }

    /// Narrows an access of a value of type `ty` to its element `index`.
    pub(super) fn index_access(
        &mut self,
        mut a: Access,
        ty: Type,
        index: ExprId,
    ) -> Result<Access, Diagnostic> {
        let elem = ty.element();
        let width = super::layout(elem).map_or(1, |(_, n)| n);
        let len = (a.width / width.max(1)).max(1);
        if let Some(k) = self.constant_index(index) {
            let k = k.clamp(0, i64::from(len) - 1) as u32;
            a.offset += k * width;
            a.width = width;
            return Ok(a);
        }
        let signed = self.shader.expr(index).ty.base != Base::Uint;
        let i = self.expr(index)?.ints()[0];
        a.dynamic = Some(match a.dynamic {
            None => Dynamic { index: i, signed, len, stride: width },
            Some(outer) => {
                // Two run-time indices: one flat component index from the first component
                // addressed, each part clamped on its own (so the flat index is in range).
                let outer_i = self.clamped(outer);
                let inner_i = self.clamped(Dynamic { index: i, signed, len, stride: width });
                let flat = self.emit.int_binary(IntBinary::Add, outer_i, inner_i);
                Dynamic { index: flat, signed: false, len: outer.len * outer.stride, stride: 1 }
            }
        });
        a.width = width;
        Ok(a)
    }

    /// `clamp(index, 0, len - 1) * stride` as a `uint`.
    fn clamped(&mut self, d: Dynamic) -> Reg {
        let last = self.emit.int(d.len.saturating_sub(1));
        let i = if d.signed {
            let zero = self.emit.int(0);
            let i = self.emit.int_binary(IntBinary::MaxI, d.index, zero);
            self.emit.int_binary(IntBinary::MinI, i, last)
        } else {
            self.emit.int_binary(IntBinary::MinU, d.index, last)
        };
        let stride = self.emit.int(d.stride);
        self.emit.int_binary(IntBinary::Mul, i, stride)
    }

    /// The value of an index known at compile time.
    pub(super) fn constant_index(&self, id: ExprId) -> Option<i64> {
        match self.kind(id) {
            ExprKind::Literal(Literal::Int(i)) => Some(i64::from(*i)),
            ExprKind::Literal(Literal::Uint(i)) => Some(i64::from(*i)),
            ExprKind::Convert(inner) => match self.kind(*inner) {
                ExprKind::Literal(Literal::Float(x)) if x.is_finite() => Some(x.trunc() as i64),
                _ => None,
            },
            _ => None,
        }
    }

    /// Reads the addressed components.
    pub(super) fn read(&mut self, a: &Access) -> Val {
        let regs: Vec<Reg> = (0..a.width)
            .map(|c| {
                let base = a.root[(a.offset + c) as usize];
                match a.dynamic {
                    None => base,
                    Some(d) => self.emit.gather(a.float, base, d.len, d.stride, d.index, d.signed),
                }
            })
            .collect();
        if a.float { Val::Float(regs) } else { Val::Int(regs) }
    }

    /// Stores `v` into the addressed components, in the lanes of the execution mask.
    pub(super) fn store(&mut self, a: &Access, v: &Val, span: Span) -> Result<(), Diagnostic> {
        let src = match v {
            Val::Float(r) | Val::Int(r) => r.clone(),
            Val::Str(_) | Val::Void => return Ok(()),
        };
        for c in 0..a.width.min(src.len() as u32) {
            let base = a.root[(a.offset + c) as usize];
            let s = src[c as usize];
            let varying_into_uniform =
                base.uniform && (!s.uniform || a.dynamic.is_some_and(|d| !d.index.uniform));
            if varying_into_uniform {
                return Err(Diagnostic::error(
                    DiagCode::Internal,
                    "the interpreter was asked to store a varying value into a uniform variable",
                    span,
                    "this store",
                )
                .with_note("the rate analysis should have made the variable varying; this is a bug"));
            }
            match a.dynamic {
                None => self.emit.store(a.float, base, s),
                Some(d) => self.emit.scatter(a.float, base, d.len, d.stride, d.index, d.signed, s),
            }
        }
        Ok(())
    }

    /// A string-valued expression, resolved at compile time.
    pub(super) fn string_of(&mut self, id: ExprId) -> Result<Option<smol_str::SmolStr>, Diagnostic> {
        match self.expr(id)? {
            Val::Str(s) => Ok(Some(s)),
            _ => Ok(None),
        }
    }
}

/// The whole of a variable.
fn whole(v: Val) -> Access {
    let float = matches!(v, Val::Float(_));
    let root = match v {
        Val::Float(r) | Val::Int(r) => r,
        _ => Vec::new(),
    };
    Access { width: root.len() as u32, root, float, offset: 0, dynamic: None }
}
