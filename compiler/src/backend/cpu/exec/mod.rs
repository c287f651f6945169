//! The batch machine: runs [`Code`](super::code::Code) over up to [`LANES`] shading points at once,
//! with an execution mask for divergent control flow, the way the grid interpreters of PRMan, BMRT
//! and Aqsis run a micropolygon grid.
//!
//! Lanes that leave a construct early (`break`, `continue`, `return`) are *halted*: every later
//! statement runs without them until the construct they left is finished, when they rejoin.

mod instructions;
mod kernels;
mod mask;

use crate::backend::cpu::code::{Files, Inst, Node};
use crate::backend::cpu::scalar::Real;
use crate::source::Span;
pub(crate) use kernels::File;
pub(crate) use mask::Mask;

/// The number of shading points a batch holds. Large enough that an instruction's dispatch is
/// amortized over many lanes (256 ran the fBm benchmark in two thirds of 128's time), small
/// enough that a statement's registers stay in the L2 cache.
pub const LANES: usize = 256;

/// Whether the CPU has AVX2 (never, off x86-64).
fn has_avx2() -> bool {
    #[cfg(target_arch = "x86_64")]
    return std::arch::is_x86_feature_detected!("avx2");
    #[cfg(not(target_arch = "x86_64"))]
    false
}

/// Why a run stopped before the end of the program.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Stop {
    /// A loop ran more iterations than the budget allows (in some lane of the batch).
    IterationBudget {
        /// The loop.
        span: Span,
        /// The budget.
        budget: u64,
    },
}

/// What `break`, `continue` and `return` leave, and the lanes waiting to rejoin after it.
#[derive(Clone, Debug)]
enum Target {
    Loop { broke: Mask, continued: Mask },
    Function { returned: Mask },
}

/// The registers and the state of control flow for one batch.
pub(crate) struct Machine<F> {
    pub floats: File<F>,
    pub ints: File<u32>,
    /// Lanes that have left a construct that is still running.
    halted: Mask,
    targets: Vec<Target>,
    /// The most iterations one loop may run before the run stops.
    pub budget: u64,
    /// The textures, as the code numbers them.
    pub textures: Vec<Texture>,
    /// Whether the CPU has AVX2, so that instructions run in their AVX2 build.
    avx2: bool,
}

/// A texture the interpreter reads: RGBA texels, x fastest, then y, then z.
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    /// Texels along x, y and z (1 for unused axes).
    pub size: [u32; 3],
    /// The texels.
    pub texels: std::sync::Arc<[[f32; 4]]>,
}

impl Default for Texture {
    /// One black, transparent texel: what a lookup of an unbound texture reads.
    fn default() -> Self {
        Texture { size: [1, 1, 1], texels: std::sync::Arc::from(vec![[0.0f32; 4]]) }
    }
}

impl Texture {
    /// The texel at (x, y, z), each clamped into range.
    pub fn texel(&self, x: i32, y: i32, z: i32) -> [f32; 4] {
        let c = |v: i32, n: u32| v.clamp(0, n.max(1) as i32 - 1) as usize;
        let [w, h, d] = self.size;
        let i = (c(z, d) * h.max(1) as usize + c(y, h)) * w.max(1) as usize + c(x, w);
        self.texels.get(i).copied().unwrap_or([0.0; 4])
    }
}

impl<F: Real> Machine<F> {
    /// A machine with registers for code of these sizes, all zero.
    pub fn new(files: Files, budget: u64) -> Self {
        Machine {
            floats: File::new(files.uniform_floats, files.varying_floats, F::ZERO),
            ints: File::new(files.uniform_ints, files.varying_ints, 0),
            halted: Mask::none(),
            // Deep enough for any program the front end accepts without reallocating.
            targets: Vec::with_capacity(64),
            budget,
            textures: Vec::new(),
            avx2: has_avx2(),
        }
    }

    /// Runs one instruction, in the build for the widest vectors the CPU has. Each build computes
    /// the same IEEE operations lane for lane (no fused multiply-add is enabled, and the lane loops
    /// call the same library functions), so the results are bit-identical.
    #[inline(always)]
    fn dispatch(&mut self, inst: &Inst, mask: &Mask) {
        #[cfg(target_arch = "x86_64")]
        if self.avx2 {
            // SAFETY: `avx2` is set only when the CPU has AVX2.
            unsafe { self.inst_avx2(inst, mask) };
            return;
        }
        self.inst_baseline(inst, mask);
    }

    /// [`Machine::inst`] for the target's baseline features.
    #[inline(never)]
    fn inst_baseline(&mut self, inst: &Inst, mask: &Mask) {
        self.inst(inst, mask);
    }

    /// [`Machine::inst`] compiled for AVX2: twice the lanes per vector instruction of the
    /// baseline's SSE2, and SSE4.1's rounding and blends. Both builds are functions of their own
    /// rather than inlined into the recursive `block`, whose frames would then hold every
    /// instruction's temporaries (a stack overflow on rayon's threads in unoptimized builds).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn inst_avx2(&mut self, inst: &Inst, mask: &Mask) {
        self.inst(inst, mask);
    }

    /// Runs `code` over the first `active` lanes.
    pub fn run(&mut self, code: &[Node], active: usize) -> Result<(), Stop> {
        self.halted = Mask::none();
        self.targets.clear();
        self.block(code, &Mask::first(active))
    }

    /// Runs `nodes` for the lanes of `entry`. Control flow nests up to the parser's limit, and the
    /// batch machine may run on a rayon worker's smaller stack: grow it rather than overflow.
    fn block(&mut self, nodes: &[Node], entry: &Mask) -> Result<(), Stop> {
        stacker::maybe_grow(64 * 1024, 1024 * 1024, || self.block_here(nodes, entry))
    }

    fn block_here(&mut self, nodes: &[Node], entry: &Mask) -> Result<(), Stop> {
        let mut mask = entry.clone();
        for node in nodes {
            if self.halted.any() {
                mask.remove(&self.halted);
                if !mask.any() {
                    return Ok(());
                }
            }
            match node {
                Node::Inst(inst) => self.dispatch(inst, &mask),
                Node::If { cond, then, otherwise } => {
                    let (yes, no) = mask.split(self.ints.read(*cond));
                    if yes.any() {
                        self.block(then, &yes)?;
                    }
                    if no.any() {
                        self.block(otherwise, &no)?;
                    }
                }
                Node::Loop { test, cond, body, step, span } => {
                    self.repeat(test, *cond, body, step, *span, &mask)?;
                }
                Node::Break(levels) => {
                    if let Target::Loop { broke, .. } = self.loop_target(*levels) {
                        broke.add(&mask);
                    }
                    self.halted.add(&mask);
                    return Ok(());
                }
                Node::Continue(levels) => {
                    if let Target::Loop { continued, .. } = self.loop_target(*levels) {
                        continued.add(&mask);
                    }
                    self.halted.add(&mask);
                    return Ok(());
                }
                Node::Return => {
                    // A return from the shader itself halts its lanes for good.
                    if let Some(Target::Function { returned }) =
                        self.targets.iter_mut().rev().find(|t| matches!(t, Target::Function { .. }))
                    {
                        returned.add(&mask);
                    }
                    self.halted.add(&mask);
                    return Ok(());
                }
                Node::Function(body) => {
                    self.targets.push(Target::Function { returned: Mask::none() });
                    self.block(body, &mask)?;
                    if let Some(Target::Function { returned }) = self.targets.pop() {
                        self.halted.remove(&returned);
                    }
                }
            }
        }
        Ok(())
    }

    /// The loop `levels` out (1 is the innermost).
    fn loop_target(&mut self, levels: u32) -> &mut Target {
        self.targets
            .iter_mut()
            .rev()
            .filter(|t| matches!(t, Target::Loop { .. }))
            .nth(levels.saturating_sub(1) as usize)
            .expect("the semantic stage checks that break and continue are inside enough loops")
    }

    fn repeat(
        &mut self,
        test: &[Node],
        cond: Option<crate::backend::cpu::code::Reg>,
        body: &[Node],
        step: &[Node],
        span: Span,
        entry: &Mask,
    ) -> Result<(), Stop> {
        self.targets.push(Target::Loop { broke: Mask::none(), continued: Mask::none() });
        let mut mask = entry.clone();
        let mut iterations = 0u64;
        loop {
            if let Some(cond) = cond {
                self.block(test, &mask)?;
                mask = mask.split(self.ints.read(cond)).0;
            }
            if !mask.any() {
                break;
            }
            iterations += 1;
            if iterations > self.budget {
                return Err(Stop::IterationBudget { span, budget: self.budget });
            }
            self.block(body, &mask)?;
            if let Some(Target::Loop { continued, .. }) = self.targets.last_mut() {
                self.halted.remove(continued);
                *continued = Mask::none();
            }
            mask.remove(&self.halted);
            if !mask.any() {
                break;
            }
            self.block(step, &mask)?;
            mask.remove(&self.halted);
        }
        if let Some(Target::Loop { broke, .. }) = self.targets.pop() {
            self.halted.remove(&broke);
        }
        Ok(())
    }
}
