//! IR to interpreter code: every variable gets registers for the program's lifetime, every
//! statement is scalarized into instructions over them, and the binding (the lights, the values of
//! string parameters) is applied: light loops are unrolled over the bound lights, strings resolved.
//!
//! The shader must already have been through `opt::derivs` (the interpreter has no derivative
//! built-ins of its own; it reads [`ExprKind::Seed`] registers the caller fills).

mod builtins;
pub use builtins::{lightsource_input, surface_flag_input, surface_input};
mod emit;
mod expr;
mod geometry;
mod stmt;

use rustc_hash::FxHashMap;
use smol_str::SmolStr;

use crate::backend::binding::Binding;
use crate::backend::cpu::code::{Code, Node, Reg};
use crate::diag::Diagnostic;
use crate::ir::global::Global;
use crate::ir::types::{Base, Frequency, Type};
use crate::ir::{Axis, ExprId, ExprKind, Input, LocalId, LocalKind, Place, Shader, Stmt};
pub(crate) use emit::{Emitter, Val};

/// What a slot of registers holds, for the caller.
#[derive(Clone, Debug, PartialEq)]
pub enum SlotKind {
    /// A shader parameter (an `output` one is also read back).
    Param {
        /// Whether the shader writes it.
        output: bool,
    },
    /// A predefined variable (`P`, `Ci`, ...).
    Global,
    /// A predefined per-light variable (`L`, `Cl`) of one bound light.
    LightValue {
        /// The light's position in the binding.
        light: usize,
    },
    /// The derivative of an input along a screen axis.
    Seed {
        /// The axis.
        axis: Axis,
    },
    /// A named coordinate system: the matrix from "current" to it (16 registers) followed by its
    /// inverse (16 more).
    Space,
    /// The value a Stanford shader returns.
    Result,
    /// A variable of the body (not addressable by the caller).
    Variable,
}

/// A group of registers with a name the caller uses: an input to fill or an output to read.
#[derive(Clone, Debug, PartialEq)]
pub struct Slot {
    /// The name: the variable's, `dx(P)` for a seed, `L[1]` for a light's value, `space:world`.
    pub name: String,
    /// What it is.
    pub kind: SlotKind,
    /// Its type.
    pub ty: Type,
    /// Whether the registers are in the float file.
    pub float: bool,
    /// The registers, one per component.
    pub regs: Vec<Reg>,
}

/// A shader compiled for the interpreter.
#[derive(Clone, Debug, PartialEq)]
pub struct Lowered {
    /// The code run per batch.
    pub code: Code,
    /// The named registers.
    pub slots: Vec<Slot>,
    /// For each parameter with a default (by slot index): the code that stores the default, run
    /// when the caller does not set the parameter.
    pub defaults: Vec<(usize, Vec<Node>)>,
}

/// Compiles `shader` (after `opt::derivs`) for `binding`.
pub fn lower(shader: &Shader, binding: &Binding) -> Result<Lowered, Diagnostic> {
    let shader = &crate::opt::lights::unroll(shader, &binding.lights, &binding.strings);
    let mut l = Lower::new(shader, binding);
    l.allocate();
    let mut defaults = Vec::new();
    for &param in &shader.params {
        if let LocalKind::Param { default: Some(value), .. } = shader.local(param).kind {
            // Strings are compile-time values: their defaults are read where they are used.
            let Some(&slot) = l.local_slot.get(&(param, None)) else { continue };
            let mut stmts = shader.default_prelude(value);
            stmts.push(Stmt::Store { place: Place::Local(param), value, span: shader.local(param).span });
            let code = l.block(&stmts)?;
            defaults.push((slot, code));
        }
    }
    let mut body = l.block(&shader.body)?;
    for (_, code) in &mut defaults {
        l.emit.finish(code);
    }
    let files = l.emit.finish(&mut body);
    let code = Code {
        files,
        float_constants: l.emit.float_values.clone(),
        int_constants: l.emit.int_values.clone(),
        body,
        textures: l.textures.clone(),
    };
    Ok(Lowered { code, slots: l.slots, defaults })
}

/// The lowering state of one shader.
pub(crate) struct Lower<'a> {
    pub shader: &'a Shader,
    pub binding: &'a Binding,
    pub emit: Emitter,
    pub slots: Vec<Slot>,
    /// Slot of each local, per light for per-light locals.
    local_slot: FxHashMap<(LocalId, Option<usize>), usize>,
    /// Slot of each predefined variable, per light for per-light ones.
    global_slot: FxHashMap<(&'static str, Option<usize>), usize>,
    /// Slot of each seed.
    seed_slot: FxHashMap<(SeedKey, Axis), usize>,
    /// Slot of each named space.
    space_slot: FxHashMap<SmolStr, usize>,
    /// Values of the current statement's expressions, per light.
    memo: FxHashMap<(ExprId, Option<usize>), Val>,
    /// The bound light the code being lowered runs for (inside an unrolled light loop).
    pub light: Option<usize>,
    /// The next `random()` call site.
    pub random_sites: u32,
    /// The textures read, by name, numbered in order of first use.
    pub textures: Vec<String>,
}

/// A seed's input, hashable.
#[derive(Copy, Clone, Debug, PartialEq, Eq, Hash)]
enum SeedKey {
    Global(&'static str),
    Param(LocalId),
}

/// How many registers of which file a type needs, or `None` for strings and textures.
pub(crate) fn layout(ty: Type) -> Option<(bool, u32)> {
    let n = ty.array.unwrap_or(1).max(1);
    match ty.base {
        Base::Bool | Base::Int | Base::Uint => Some((false, n)),
        Base::Void | Base::String | Base::Texref => None,
        b => Some((true, b.components() * n)),
    }
}

/// Whether values of this rate are stored once per batch.
fn uniform_rate(f: Frequency) -> bool {
    f <= Frequency::PrimitiveGroup
}

impl<'a> Lower<'a> {
    fn new(shader: &'a Shader, binding: &'a Binding) -> Self {
        Lower {
            shader,
            binding,
            emit: Emitter::default(),
            slots: Vec::new(),
            local_slot: FxHashMap::default(),
            global_slot: FxHashMap::default(),
            seed_slot: FxHashMap::default(),
            space_slot: FxHashMap::default(),
            memo: FxHashMap::default(),
            light: None,
            random_sites: 0,
            textures: Vec::new(),
        }
    }

    /// Registers for every local, per light for per-light ones (the parameters first, in order).
    fn allocate(&mut self) {
        let lights = self.binding.lights.len();
        let stores = crate::ir::stores::stores(self.shader);
        let mut order: Vec<LocalId> = self.shader.params.clone();
        order.extend(
            (0..self.shader.locals.len() as u32).map(LocalId).filter(|id| !self.shader.params.contains(id)),
        );
        for id in order {
            let local = self.shader.local(id);
            let instances: Vec<Option<usize>> =
                if local.rate.perlight { (0..lights).map(Some).collect() } else { vec![None] };
            for light in instances {
                let Some((float, n)) = layout(local.ty) else { continue };
                let uniform = uniform_rate(local.rate.frequency) || self.is_table(id, &stores);
                let kind = match local.kind {
                    LocalKind::Param { output, .. } => SlotKind::Param { output },
                    _ if Some(id) == self.shader.result_local => SlotKind::Result,
                    _ => SlotKind::Variable,
                };
                let name = match light {
                    Some(k) => format!("{}[{k}]", local.name),
                    None => local.name.to_string(),
                };
                let regs = self.emit.fixed_block(float, uniform, n);
                self.slots.push(Slot { name, kind, ty: local.ty, float, regs });
                self.local_slot.insert((id, light), self.slots.len() - 1);
            }
        }
    }

    /// Whether a varying variable holds the same value in every lane wherever it is read, so that
    /// uniform registers can hold it: its only store is its declaration, of a constant (a table
    /// such as a noise permutation, which RenderMan's rules make varying at file scope). Only
    /// constants: a per-draw value may still reach the interpreter as a varying input.
    /// It is read only in its scope, after that store, which gave each lane the same value
    /// whatever the mask. Storing it once per batch rather than per lane, and reading it as a
    /// uniform table, is what makes lookups into it cheap.
    fn is_table(&self, id: LocalId, stores: &[crate::ir::stores::Stores]) -> bool {
        let local = self.shader.local(id);
        local.kind == LocalKind::Var
            && Some(id) != self.shader.result_local
            && !local.rate.perlight
            && stores[id.0 as usize]
                .only_initialiser(local.span)
                .is_some_and(|value| self.literal_only(value))
    }

    /// Whether `id` is made of literals by operators, conversions and constructors alone. A rate
    /// of constant is not enough: a texture lookup of a literal name has it, yet its expansion
    /// reads `s` and `t`.
    fn literal_only(&self, id: ExprId) -> bool {
        let e = self.shader.expr(id);
        if e.rate.frequency != Frequency::Constant {
            return false;
        }
        match &e.kind {
            ExprKind::Literal(_) => true,
            ExprKind::Unary(..) | ExprKind::Binary(..) | ExprKind::Convert(_) | ExprKind::Construct(_) => {
                let mut all = true;
                e.kind.for_each_operand(|op| all &= self.literal_only(op));
                all
            }
            _ => false,
        }
    }

    /// The registers of a local (for the current light when it is per-light).
    pub fn local(&self, id: LocalId) -> Val {
        let light = if self.shader.local(id).rate.perlight { self.light } else { None };
        let slot = self.local_slot.get(&(id, light)).or_else(|| self.local_slot.get(&(id, None)));
        match slot {
            Some(&s) => self.slot_val(s),
            None => Val::Void,
        }
    }

    fn slot_val(&self, s: usize) -> Val {
        let slot = &self.slots[s];
        if slot.float { Val::Float(slot.regs.clone()) } else { Val::Int(slot.regs.clone()) }
    }

    /// The registers of a predefined variable, made on first use.
    pub fn global(&mut self, g: &'static Global) -> Val {
        // The constant predefined variables are values, not inputs.
        match g.name {
            "PI" => return Val::Float(vec![self.emit.float(std::f64::consts::PI)]),
            "ncomps" => return Val::Float(vec![self.emit.float(3.0)]),
            _ => {}
        }
        let light = if g.perlight { self.light } else { None };
        let key = (g.name, light);
        if let Some(&s) = self.global_slot.get(&key) {
            return self.slot_val(s);
        }
        let ty = Type::of(g.ty);
        let Some((float, n)) = layout(ty) else { return Val::Void };
        let uniform = uniform_rate(g.frequency);
        let regs = self.emit.fixed_block(float, uniform, n);
        let (name, kind) = match light {
            Some(k) => (format!("{}[{k}]", g.name), SlotKind::LightValue { light: k }),
            None => (g.name.to_string(), SlotKind::Global),
        };
        self.slots.push(Slot { name, kind, ty, float, regs });
        self.global_slot.insert(key, self.slots.len() - 1);
        self.slot_val(self.slots.len() - 1)
    }

    /// The registers of a seed, made on first use.
    pub fn seed(&mut self, input: Input, axis: Axis, ty: Type) -> Val {
        let (key, name) = match input {
            Input::Global(g) => (SeedKey::Global(g.name), g.name.to_string()),
            Input::Param(id) => (SeedKey::Param(id), self.shader.local(id).name.to_string()),
        };
        if let Some(&s) = self.seed_slot.get(&(key, axis)) {
            return self.slot_val(s);
        }
        let Some((float, n)) = layout(ty) else { return Val::Void };
        let regs = self.emit.fixed_block(float, false, n);
        let axis_name = match axis {
            Axis::X => "dx",
            Axis::Y => "dy",
        };
        self.slots.push(Slot {
            name: format!("{axis_name}({name})"),
            kind: SlotKind::Seed { axis },
            ty,
            float,
            regs,
        });
        self.seed_slot.insert((key, axis), self.slots.len() - 1);
        self.slot_val(self.slots.len() - 1)
    }

    /// A caller-supplied input that is not a predefined variable (`xyz_screen`, the clipping
    /// range of `depth`, the point index `random` hashes), made on first use.
    pub fn named_input(&mut self, name: &str, ty: Type, uniform: bool) -> Vec<Reg> {
        if let Some(slot) = self.slots.iter().find(|s| s.name == name) {
            return slot.regs.clone();
        }
        let (float, n) = layout(ty).unwrap_or((true, 0));
        let regs = self.emit.fixed_block(float, uniform, n);
        self.slots.push(Slot {
            name: name.to_string(),
            kind: SlotKind::Global,
            ty,
            float,
            regs: regs.clone(),
        });
        regs
    }

    /// The matrices of a named coordinate system: (current to space, space to current).
    pub fn space(&mut self, name: &str) -> (Vec<Reg>, Vec<Reg>) {
        let slot = match self.space_slot.get(name) {
            Some(&s) => s,
            None => {
                let regs = self.emit.fixed_block(true, true, 32);
                self.slots.push(Slot {
                    name: format!("space:{name}"),
                    kind: SlotKind::Space,
                    ty: Type::of(Base::Matrix4),
                    float: true,
                    regs,
                });
                self.space_slot.insert(name.into(), self.slots.len() - 1);
                self.slots.len() - 1
            }
        };
        let regs = &self.slots[slot].regs;
        (regs[..16].to_vec(), regs[16..].to_vec())
    }

    /// The value of a string parameter in the binding.
    pub fn bound_string(&self, id: LocalId) -> Option<SmolStr> {
        let local = self.shader.local(id);
        self.binding.strings.iter().find(|(n, _)| *n == local.name).map(|(_, v)| SmolStr::new(v))
    }

    /// Lowers a statement list to nodes (in a fresh output list).
    pub fn block(&mut self, block: &[Stmt]) -> Result<Vec<Node>, Diagnostic> {
        let outer = std::mem::take(&mut self.emit.out);
        let result = block.iter().try_for_each(|s| self.statement(s));
        let nodes = std::mem::replace(&mut self.emit.out, outer);
        result.map(|()| nodes)
    }

    /// Forgets the values of the previous statement's expressions (their temporaries are reused).
    pub fn next_statement(&mut self) {
        self.memo.clear();
        self.emit.next_statement();
    }

    pub(crate) fn memo_get(&self, id: ExprId) -> Option<Val> {
        self.memo.get(&(id, self.light)).cloned()
    }

    pub(crate) fn memo_put(&mut self, id: ExprId, v: &Val) {
        self.memo.insert((id, self.light), v.clone());
    }

    /// The kind of an expression.
    pub fn kind(&self, id: ExprId) -> &'a ExprKind {
        &self.shader.expr(id).kind
    }
}
