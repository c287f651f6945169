//! Collects visible fragments into batches for the batch callback, in an order that gives exactly
//! the result of shading and blending each fragment as it comes, as long as the batches are
//! blended in the order they are handed out.

use super::Varyings;
use super::framebuffer::Framebuffer;
use super::interpolate::Sample;

/// A batch of visible fragments handed to the shading callback: their pixels, depths, facing, and
/// interpolated varyings with derivatives, structure-of-arrays like the interpreter's registers.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Fragments {
    /// Fragments in the batch.
    pub count: usize,
    /// Varying components per fragment.
    pub components: usize,
    /// Pixel `(x, y)` of each fragment (row 0 at the top); the sample is at the pixel's centre.
    pub pixels: Vec<(u32, u32)>,
    /// Depth z/w of each fragment, in [0, 1].
    pub depth: Vec<f32>,
    /// Whether each fragment's triangle is front facing.
    pub front_facing: Vec<bool>,
    /// Component `c` of fragment `k` at `[c * count + k]`.
    pub values: Vec<f32>,
    /// d/dx (one pixel right) of each value, laid out like `values`.
    pub ddx: Vec<f32>,
    /// d/dy (one row down) of each value, laid out like `values`.
    pub ddy: Vec<f32>,
}

impl Fragments {
    /// Component `c` of every fragment (empty if `c` is out of range).
    pub fn values_of(&self, c: usize) -> &[f32] {
        self.values.get(c * self.count..(c + 1) * self.count).unwrap_or(&[])
    }

    /// d/dx of component `c` of every fragment.
    pub fn ddx_of(&self, c: usize) -> &[f32] {
        self.ddx.get(c * self.count..(c + 1) * self.count).unwrap_or(&[])
    }

    /// d/dy of component `c` of every fragment.
    pub fn ddy_of(&self, c: usize) -> &[f32] {
        self.ddy.get(c * self.count..(c + 1) * self.count).unwrap_or(&[])
    }
}

/// A fragment that passed the depth test and waits for shading.
pub(super) struct Record {
    pub(super) x: u32,
    pub(super) y: u32,
    pub(super) depth: f32,
    pub(super) front: bool,
    /// The original triangle's vertex indices, provoking vertex first.
    pub(super) tri: [u32; 3],
    pub(super) sample: Sample,
}

/// The batch being collected, and which pixels it holds.
pub(super) struct Batcher<'a> {
    varyings: &'a Varyings<'a>,
    capacity: usize,
    records: Vec<Record>,
    /// `stamps[pixel] == generation` while the pixel has a fragment in the batch.
    stamps: Vec<u32>,
    generation: u32,
    fragments: Fragments,
    batches: usize,
}

impl<'a> Batcher<'a> {
    /// A batcher for `fb`'s pixels that flushes at `capacity` fragments.
    pub(super) fn new(varyings: &'a Varyings<'a>, fb: &Framebuffer, capacity: usize) -> Self {
        Batcher {
            varyings,
            capacity,
            records: Vec::with_capacity(capacity),
            stamps: vec![0; fb.color.len()],
            generation: 1,
            fragments: Fragments { components: varyings.components, ..Fragments::default() },
            batches: 0,
        }
    }

    /// Calls of the shading callback so far.
    pub(super) fn batches(&self) -> usize {
        self.batches
    }

    /// Adds a fragment, handing out the batch first if it is full or already holds this pixel
    /// (the new fragment must blend over the waiting one, not beside it).
    pub(super) fn push<E>(
        &mut self,
        fb: &mut Framebuffer,
        record: Record,
        on_batch: &mut impl FnMut(&mut Framebuffer, &Fragments) -> Result<(), E>,
    ) -> Result<(), E> {
        let pixel = record.y as usize * fb.width as usize + record.x as usize;
        if self.records.len() >= self.capacity || self.stamps[pixel] == self.generation {
            self.flush(fb, on_batch)?;
        }
        self.stamps[pixel] = self.generation;
        self.records.push(record);
        Ok(())
    }

    /// Hands the waiting fragments to `on_batch`.
    pub(super) fn flush<E>(
        &mut self,
        fb: &mut Framebuffer,
        on_batch: &mut impl FnMut(&mut Framebuffer, &Fragments) -> Result<(), E>,
    ) -> Result<(), E> {
        if self.records.is_empty() {
            return Ok(());
        }
        self.fill();
        self.batches += 1;
        let result = on_batch(fb, &self.fragments);
        self.records.clear();
        self.next_generation();
        result
    }

    fn next_generation(&mut self) {
        if self.generation == u32::MAX {
            self.stamps.fill(0);
            self.generation = 0;
        }
        self.generation += 1;
    }

    /// Interpolates every component at every waiting fragment, in f64 and rounded once.
    fn fill(&mut self) {
        let (n, comps) = (self.records.len(), self.varyings.components);
        let f = &mut self.fragments;
        f.count = n;
        f.pixels.clear();
        f.pixels.extend(self.records.iter().map(|r| (r.x, r.y)));
        f.depth.clear();
        f.depth.extend(self.records.iter().map(|r| r.depth));
        f.front_facing.clear();
        f.front_facing.extend(self.records.iter().map(|r| r.front));
        for buf in [&mut f.values, &mut f.ddx, &mut f.ddy] {
            buf.clear();
            buf.resize(n * comps, 0.0);
        }
        let data = self.varyings.data;
        for c in 0..comps {
            let flat = self.varyings.is_flat(c);
            let at = |v: u32| f64::from(data[v as usize * comps + c]);
            for (k, r) in self.records.iter().enumerate() {
                let i = c * n + k;
                if flat {
                    // The provoking vertex's value, untouched; constant, so no derivative.
                    f.values[i] = data[r.tri[0] as usize * comps + c];
                    continue;
                }
                let a = r.tri.map(at);
                let s = &r.sample;
                f.values[i] = dot(s.bary, a) as f32;
                f.ddx[i] = dot(s.ddx, a) as f32;
                f.ddy[i] = dot(s.ddy, a) as f32;
            }
        }
    }
}

fn dot(a: [f64; 3], b: [f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}
