//! The wgpu side of the runtime: a device (`Gpu`), offscreen rendering of draws into an `Image`, and a
//! compute harness that runs compiled shader functions over buffers for conformance tests.
//!
//! Every fallible step returns `GpuError`; wgpu's validation errors are caught with error scopes, so
//! a bad module or bad input never panics the process.

mod compute;
mod device;
mod limits;
mod pipeline;
mod render;
mod texture;

pub use device::Gpu;
pub use render::{Attribute, Blend, Draw, Target, TargetFormat};
pub use texture::{Address, Filter, TextureData, TextureDimension};

use std::fmt;

/// Name of the environment variable that turns GPU work off (`PATINA_GPU=off`).
pub const GPU_ENV: &str = "PATINA_GPU";

/// Why a GPU operation failed.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum GpuError {
    /// No adapter was found; the payload is wgpu's reason.
    NoAdapter(String),
    /// The adapter refused to create a device.
    Device(String),
    /// wgpu reported an error (validation, out of memory, internal) for a pipeline, resource or submission.
    Wgpu(String),
    /// The caller's data was inconsistent (sizes, indices, counts); checked before reaching wgpu.
    InvalidInput(String),
    /// Waiting for the device or mapping a buffer back failed.
    Readback(String),
    /// Something asked of the device is over one of its limits; checked before creating it.
    Limit {
        /// What was being created, with its size.
        what: String,
        /// The amount asked (pixels per side, bytes, count: as `what` says).
        asked: u64,
        /// The device's limit.
        limit: u64,
        /// The limit's name in wgpu's `Limits` (and WebGPU's).
        name: &'static str,
    },
    /// The device cannot do what was asked (a missing feature or format).
    Unsupported(String),
    /// The device ran out of memory creating or running something.
    OutOfMemory(String),
    /// The device was lost (a driver reset, a hang the driver stopped, or `destroy`); nothing more
    /// can run on it.
    DeviceLost(String),
}

impl fmt::Display for GpuError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            GpuError::NoAdapter(why) => write!(
                f,
                "no GPU adapter found ({why}); install a Vulkan driver (on Debian/Ubuntu: \
                 apt-get install mesa-vulkan-drivers libvulkan1) or set {GPU_ENV}=off to skip GPU work"
            ),
            GpuError::Device(why) => write!(f, "could not create a GPU device: {why}"),
            GpuError::Wgpu(why) => write!(f, "GPU error: {why}"),
            GpuError::InvalidInput(why) => write!(f, "invalid GPU input: {why}"),
            GpuError::Readback(why) => write!(f, "GPU readback failed: {why}"),
            GpuError::Limit { what, asked, limit, name } => {
                write!(f, "{what}: {asked} is over the device's limit of {limit} ({name})")
            }
            GpuError::Unsupported(why) => write!(f, "not supported by the GPU: {why}"),
            GpuError::OutOfMemory(why) => write!(f, "the GPU ran out of memory: {why}"),
            GpuError::DeviceLost(why) => write!(f, "the GPU device was lost: {why}"),
        }
    }
}

impl std::error::Error for GpuError {}

/// Whether GPU work is expected: false only when the user turned it off with `PATINA_GPU=off`.
pub fn adapter_required() -> bool {
    std::env::var_os(GPU_ENV).is_none_or(|v| !v.eq_ignore_ascii_case("off"))
}

/// The device for tests that need a GPU: `None` when `PATINA_GPU=off`, otherwise the process's
/// one shared `Gpu`, opened by the first test that asks.
///
/// One device per test process, not one per test: opening a device costs more than most GPU
/// tests, and render pipelines kept by one test (see `Gpu::kept_pipelines`) serve the next. Sharing
/// is safe because wgpu's error scopes are thread-local, so a test running beside another catches
/// only its own errors. A test that counts pipelines or loses the device takes its own from
/// [`own_for_tests`].
///
/// # Panics
/// When no adapter can be opened and the GPU is not turned off: a test that silently skipped on a
/// machine without a driver would hide the missing driver.
pub fn for_tests() -> Option<&'static Gpu> {
    static SHARED: std::sync::OnceLock<Gpu> = std::sync::OnceLock::new();
    adapter_required().then(|| SHARED.get_or_init(open_for_tests))
}

/// A device of the test's own, not shared with the other tests of the process: `None` when
/// `PATINA_GPU=off`.
///
/// # Panics
/// As [`for_tests`], when no adapter can be opened.
pub fn own_for_tests() -> Option<Gpu> {
    adapter_required().then(open_for_tests)
}

fn open_for_tests() -> Gpu {
    match Gpu::new() {
        Ok(gpu) => gpu,
        Err(e) => panic!("\n\n*** GPU tests need an adapter and none could be opened ***\n{e}\n\n"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gpu_can_be_shared_between_threads() {
        fn send_sync<T: Send + Sync>() {}
        send_sync::<Gpu>();
    }

    #[test]
    fn no_adapter_message_is_one_actionable_line() {
        let text = GpuError::NoAdapter("NotFound".into()).to_string();
        assert!(!text.contains('\n'));
        assert!(text.contains("mesa-vulkan-drivers") && text.contains("libvulkan1"));
        assert!(text.contains("PATINA_GPU=off"));
    }
}
