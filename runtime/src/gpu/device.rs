//! Opening the adapter and device, catching wgpu's errors, and reading buffers back.

use super::GpuError;
use std::sync::{Arc, Mutex, mpsc};

/// A wgpu device and queue, with the texture format chosen for sampled textures.
pub struct Gpu {
    pub(super) adapter: wgpu::Adapter,
    pub(super) device: wgpu::Device,
    pub(super) queue: wgpu::Queue,
    /// `Rgba32Float` when the device can filter it, else `Rgba16Float`.
    pub(super) texture_format: wgpu::TextureFormat,
    /// Errors raised outside any error scope (the default handler would panic).
    uncaptured: Arc<Mutex<Option<String>>>,
    /// Why the device was lost, once it has been.
    lost: Arc<Mutex<Option<String>>>,
    /// Render pipelines of fingerprinted draws, made once and reused.
    pub(super) pipelines: super::pipeline::Pipelines,
}

impl Gpu {
    /// The backends [`Gpu::new`] asks wgpu for when `WGPU_BACKEND` does not name them: every
    /// native backend this build of wgpu has (Vulkan always; Metal, DX12 and GL with the runtime's
    /// `metal`, `dx12` and `gl` features), never wgpu's no-op backend.
    pub fn default_backends() -> wgpu::Backends {
        wgpu::Backends::all() & wgpu::Instance::enabled_backend_features() & !wgpu::Backends::NOOP
    }

    /// Opens the first adapter wgpu offers among [`Gpu::default_backends`] (or the backends
    /// `WGPU_BACKEND` names) and a device with the adapter's best limits, then wraps it as
    /// [`Gpu::from_device`] does.
    pub fn new() -> Result<Gpu, GpuError> {
        let mut desc = wgpu::InstanceDescriptor::new_without_display_handle();
        desc.backends = wgpu::Backends::from_env().unwrap_or_else(Gpu::default_backends);
        desc.flags = wgpu::InstanceFlags::default().with_env();
        let instance = wgpu::Instance::new(desc);
        let options = wgpu::RequestAdapterOptions {
            power_preference: wgpu::PowerPreference::None,
            force_fallback_adapter: false,
            compatible_surface: None,
            ..Default::default()
        };
        let adapter = pollster::block_on(instance.request_adapter(&options))
            .map_err(|e| GpuError::NoAdapter(e.to_string()))?;
        Gpu::from_adapter(adapter)
    }

    /// Opens a device on `adapter` (one the caller chose, e.g. for a window's surface) with the
    /// features and limits [`Gpu::new`] asks for, and wraps it as [`Gpu::from_device`] does.
    pub fn from_adapter(adapter: wgpu::Adapter) -> Result<Gpu, GpuError> {
        // Float32 filtering lets textures keep full precision; blending on Rgba32Float targets
        // needs its own feature. Both are optional: without them we degrade or report errors.
        let wanted = wgpu::Features::FLOAT32_FILTERABLE | wgpu::Features::FLOAT32_BLENDABLE;
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("patina"),
            required_features: adapter.features() & wanted,
            required_limits: adapter.limits(),
            ..Default::default()
        }))
        .map_err(|e| GpuError::Device(e.to_string()))?;
        Ok(Gpu::from_device(adapter, device, queue))
    }

    /// Wraps a device the caller opened, so that Patina draws with the caller's own device and
    /// queue (`adapter` is the one `device` came from; it names the device and is not otherwise
    /// used).
    ///
    /// Whatever the device was created with is used as it is: sampled textures are
    /// `Rgba32Float` when it has [`wgpu::Features::FLOAT32_FILTERABLE`], else `Rgba16Float`;
    /// float targets blend only with [`wgpu::Features::FLOAT32_BLENDABLE`]; renders and
    /// dispatches are checked against its limits. Ask for those features (as [`Gpu::new`] does)
    /// for results equal to the runtime's own device.
    ///
    /// This replaces the device's uncaptured-error handler and its device-lost callback: errors
    /// outside Patina's error scopes would otherwise panic, and a lost device is reported as
    /// [`GpuError::DeviceLost`]. An error the caller's own work raises outside an error scope
    /// comes back from the next Patina call on this `Gpu`, as a [`GpuError::Wgpu`].
    pub fn from_device(adapter: wgpu::Adapter, device: wgpu::Device, queue: wgpu::Queue) -> Gpu {
        let uncaptured = Arc::new(Mutex::new(None));
        let sink = Arc::clone(&uncaptured);
        device.on_uncaptured_error(Arc::new(move |e: wgpu::Error| {
            if let Ok(mut slot) = sink.lock() {
                slot.get_or_insert_with(|| e.to_string());
            }
        }));
        let lost = Arc::new(Mutex::new(None));
        let sink = Arc::clone(&lost);
        device.set_device_lost_callback(move |reason, message| {
            if let Ok(mut slot) = sink.lock() {
                slot.get_or_insert_with(|| format!("{message} ({reason:?})"));
            }
        });
        let texture_format = if device.features().contains(wgpu::Features::FLOAT32_FILTERABLE) {
            wgpu::TextureFormat::Rgba32Float
        } else {
            wgpu::TextureFormat::Rgba16Float
        };
        Gpu { adapter, device, queue, texture_format, uncaptured, lost, pipelines: Default::default() }
    }

    /// The adapter the device came from.
    pub fn adapter(&self) -> &wgpu::Adapter {
        &self.adapter
    }

    /// The device Patina draws with (the caller's own after [`Gpu::from_device`]).
    pub fn device(&self) -> &wgpu::Device {
        &self.device
    }

    /// The device's queue.
    pub fn queue(&self) -> &wgpu::Queue {
        &self.queue
    }

    /// Destroys the device, as a driver reset would lose it: what runs on this `Gpu` afterwards
    /// fails with [`GpuError::DeviceLost`]. For tests of that path.
    #[doc(hidden)]
    pub fn lose_device_for_tests(&self) {
        self.device.destroy();
    }

    /// How many render pipelines this device keeps for reuse (see `Draw::fingerprint`).
    pub fn kept_pipelines(&self) -> usize {
        self.pipelines.len()
    }

    /// How many render pipelines this device has made, kept or not (pipeline creation is most
    /// of a small render's time: tests count it).
    pub fn pipelines_made(&self) -> usize {
        self.pipelines.made()
    }

    /// The device's limits, which renders and dispatches are checked against.
    pub fn limits(&self) -> wgpu::Limits {
        self.device.limits()
    }

    /// `Err(DeviceLost)` once the device is lost: wgpu's own errors after that name no cause.
    pub(super) fn check_alive(&self) -> Result<(), GpuError> {
        // wgpu calls the device-lost callback from a poll; a failed poll says nothing more.
        let _ = self.device.poll(wgpu::PollType::Poll);
        let lost = match self.lost.lock() {
            Ok(slot) => slot.clone(),
            Err(_) => Some("a previous device-lost handler panicked".to_string()),
        };
        lost.map_or(Ok(()), |why| Err(GpuError::DeviceLost(why)))
    }

    /// One line naming the adapter, its backend and device type, e.g. `llvmpipe (LLVM 15) (Vulkan, Cpu)`.
    pub fn adapter_description(&self) -> String {
        let info = self.adapter.get_info();
        format!("{} ({:?}, {:?})", info.name, info.backend, info.device_type)
    }

    /// Runs `f` inside validation, out-of-memory and internal error scopes and turns the first error
    /// wgpu reports (inside the scopes or, earlier, outside them) into `GpuError::Wgpu`.
    pub(super) fn scoped<T>(&self, f: impl FnOnce() -> T) -> Result<T, GpuError> {
        self.check_alive()?;
        let oom = self.device.push_error_scope(wgpu::ErrorFilter::OutOfMemory);
        let internal = self.device.push_error_scope(wgpu::ErrorFilter::Internal);
        let validation = self.device.push_error_scope(wgpu::ErrorFilter::Validation);
        let value = f();
        // Scopes form a stack: pop the innermost first.
        let errors = [
            pollster::block_on(validation.pop()),
            pollster::block_on(internal.pop()),
            pollster::block_on(oom.pop()),
        ];
        if let Some(e) = errors.into_iter().flatten().next() {
            self.check_alive()?;
            return Err(match e {
                wgpu::Error::OutOfMemory { .. } => GpuError::OutOfMemory(e.to_string()),
                e => GpuError::Wgpu(e.to_string()),
            });
        }
        self.take_uncaptured()?;
        Ok(value)
    }

    fn take_uncaptured(&self) -> Result<(), GpuError> {
        self.check_alive()?;
        let message = match self.uncaptured.lock() {
            Ok(mut slot) => slot.take(),
            Err(_) => Some("a previous GPU error handler panicked".to_string()),
        };
        message.map_or(Ok(()), |m| Err(GpuError::Wgpu(m)))
    }

    /// A buffer holding `bytes` padded with zeros to a multiple of `align` bytes (at least `align`).
    pub(super) fn buffer_with(&self, bytes: &[u8], align: usize, usage: wgpu::BufferUsages) -> wgpu::Buffer {
        let len = bytes.len().div_ceil(align).max(1) * align;
        let mut padded = Vec::with_capacity(len);
        padded.extend_from_slice(bytes);
        padded.resize(len, 0);
        // Written through the queue, not mapped at creation: wgpu's `create_buffer_init` panics
        // when the device is lost, where this reports an error to the scope around it.
        let buffer = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: None,
            size: len as u64,
            usage: usage | wgpu::BufferUsages::COPY_DST,
            mapped_at_creation: false,
        });
        self.queue.write_buffer(&buffer, 0, &padded);
        buffer
    }

    /// Waits for the queue, maps `buffer` (created with `MAP_READ`) and copies its contents out.
    pub(super) fn read_buffer(&self, buffer: &wgpu::Buffer) -> Result<Vec<u8>, GpuError> {
        let (tx, rx) = mpsc::channel();
        buffer.map_async(wgpu::MapMode::Read, .., move |r| {
            // The receiver outlives the poll below; a failed send only means we already gave up.
            let _ = tx.send(r);
        });
        // A lost device fails the wait or the mapping; say so rather than how the wait failed.
        let readback = |e: String| self.check_alive().err().unwrap_or(GpuError::Readback(e));
        self.device.poll(wgpu::PollType::wait_indefinitely()).map_err(|e| readback(e.to_string()))?;
        rx.recv().map_err(|e| readback(e.to_string()))?.map_err(|e| readback(e.to_string()))?;
        let bytes = buffer.get_mapped_range(..).map_err(|e| GpuError::Readback(e.to_string()))?.to_vec();
        buffer.unmap();
        self.take_uncaptured()?;
        Ok(bytes)
    }
}
