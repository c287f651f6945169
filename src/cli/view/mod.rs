//! `patina view`: a window showing a scene, rendered by the runtime's renderer at the window's
//! size and copied to the screen ([`present`]); dragging orbits the camera and scrolling zooms
//! ([`orbit`]); edits to the scene, its shaders or their includes render it again, as
//! `patina watch` does ([`super::live`]), and `D` shows where the GPU and the CPU reference differ.

mod orbit;
mod present;

use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::Arc;
use std::time::{Duration, Instant};

use patina::{Camera, FileWatcher};
use patina_runtime::gpu::{self, Gpu};
use patina_runtime::image::{Image, Thresholds, compare};
use patina_runtime::render::{self, Backend};
use patina_runtime::scene::Scene;
use winit::application::ApplicationHandler;
use winit::dpi::{PhysicalPosition, PhysicalSize};
use winit::event::{ElementState, MouseButton, MouseScrollDelta, WindowEvent};
use winit::event_loop::{ActiveEventLoop, ControlFlow, EventLoop};
use winit::keyboard::{Key, NamedKey};
use winit::window::{Window, WindowId};

use super::bench::parse_size;
use super::live::{LiveScene, Reporter, failure};
use super::{BackendChoice, LoweringChoice};
use orbit::Orbit;
use present::Presenter;

/// Arguments of `patina view`.
#[derive(clap::Args, Debug)]
pub struct ViewArgs {
    /// The scene file (TOML).
    scene: PathBuf,
    /// The renderer whose picture is shown.
    #[arg(long, value_enum, default_value_t = BackendChoice::Gpu)]
    backend: BackendChoice,
    /// Compile every parameter dynamic (as uniforms) instead of binding the scene's values.
    #[arg(long)]
    dynamic: bool,
    /// How the GPU module writes the built-ins: `fast` (WGSL's own) or `exact` (the CPU
    /// reference's bits).
    #[arg(long, value_enum, default_value_t = LoweringChoice::Fast)]
    lowering: LoweringChoice,
    /// The window's size in pixels (default: the scene's output size); the scene is rendered at
    /// the window's size, also after it is resized.
    #[arg(long, value_name = "WxH")]
    size: Option<String>,
    /// A directory to search for the shaders' `#include` files (after each shader's own folder
    /// and the scene's `include` list; repeat for more).
    #[arg(short = 'I', value_name = "DIR")]
    include: Vec<PathBuf>,
}

/// How often the event loop looks for changed files while it has nothing else to do.
const POLL: Duration = Duration::from_millis(20);

/// The difference picture is `|gpu - cpu|` times this: the gallery's failing threshold (0.004)
/// becomes a visible 0.04.
const DIFF_SCALE: f32 = 10.0;

pub fn run(args: ViewArgs) -> Result<ExitCode, String> {
    let size = args.size.as_deref().map(parse_size).transpose()?;
    // Read once before any window opens, so that a missing or malformed scene is one error line.
    let scene = Scene::load(&args.scene).map_err(|e| e.to_string())?;
    let size = size.unwrap_or((scene.output.width, scene.output.height));
    check_display()?;
    let event_loop = EventLoop::new().map_err(|e| format!("cannot open a window: {e}"))?;
    let mut app = App { args, size, camera: scene.camera(), viewer: None, error: None };
    event_loop.run_app(&mut app).map_err(|e| format!("the window's event loop failed: {e}"))?;
    match app.error {
        Some(error) => Err(error),
        None => Ok(ExitCode::SUCCESS),
    }
}

/// On X11 systems, fails with one line when there is no display to open a window on (winit's
/// own error for it is long and names no remedy).
fn check_display() -> Result<(), String> {
    let x11 = cfg!(all(unix, not(any(target_os = "macos", target_os = "ios", target_os = "android"))));
    if x11 && std::env::var_os("DISPLAY").is_none_or(|d| d.is_empty()) {
        return Err("no display: DISPLAY is not set (`patina view` needs an X server; \
                    `patina watch` renders to a PNG without one)"
            .into());
    }
    Ok(())
}

/// The event loop's handler: the viewer, once the loop lets a window be made.
struct App {
    args: ViewArgs,
    size: (u32, u32),
    /// The scene's camera when it was first read: the orbit's start.
    camera: Camera,
    viewer: Option<Viewer>,
    /// Why the viewer stopped, when it failed.
    error: Option<String>,
}

impl App {
    fn fail(&mut self, event_loop: &ActiveEventLoop, error: String) {
        self.error.get_or_insert(error);
        event_loop.exit();
    }
}

impl ApplicationHandler for App {
    fn resumed(&mut self, event_loop: &ActiveEventLoop) {
        if self.viewer.is_some() {
            return;
        }
        match Viewer::open(event_loop, &self.args, self.size, self.camera) {
            Ok(viewer) => self.viewer = Some(viewer),
            Err(e) => self.fail(event_loop, e),
        }
    }

    fn window_event(&mut self, event_loop: &ActiveEventLoop, _: WindowId, event: WindowEvent) {
        if let Some(viewer) = &mut self.viewer
            && let Err(e) = viewer.handle(event_loop, event)
        {
            self.fail(event_loop, e);
        }
    }

    fn about_to_wait(&mut self, event_loop: &ActiveEventLoop) {
        if let Some(viewer) = &mut self.viewer
            && let Err(e) = viewer.poll_files()
        {
            self.fail(event_loop, e);
        }
        event_loop.set_control_flow(ControlFlow::WaitUntil(Instant::now() + POLL));
    }
}

/// What the window shows.
#[derive(Copy, Clone, Debug, PartialEq, Eq)]
enum Mode {
    /// The chosen backend's picture.
    Picture,
    /// `|gpu - cpu|` times [`DIFF_SCALE`].
    Difference,
}

/// The window, the scene kept prepared across edits, and the camera.
struct Viewer {
    window: Arc<Window>,
    presenter: Presenter,
    /// The device that renders (the presenter's own), unless `PATINA_GPU=off`.
    gpu: Option<Gpu>,
    backend: Backend,
    live: LiveScene,
    watcher: FileWatcher,
    reporter: Reporter,
    orbit: Orbit,
    mode: Mode,
    /// Why the picture must be rendered again: the files changed since the last render, or
    /// `Some(empty)` for a change of camera, size or mode; `None` when the picture is current.
    stale: Option<Vec<PathBuf>>,
    /// Whether the next render's outcome is printed even when it succeeds (after an edit or a
    /// change of mode, not after every step of a drag).
    tell: bool,
    /// The cursor's last position while the left button is held.
    drag: Option<PhysicalPosition<f64>>,
    cursor: PhysicalPosition<f64>,
    /// Pictures presented so far; whether the latest picture is still to be presented.
    frames: u64,
    unshown: bool,
}

impl Viewer {
    fn open(
        event_loop: &ActiveEventLoop,
        args: &ViewArgs,
        (width, height): (u32, u32),
        camera: Camera,
    ) -> Result<Viewer, String> {
        let title = format!("patina view {}", args.scene.display());
        let attributes =
            Window::default_attributes().with_title(title).with_inner_size(PhysicalSize::new(width, height));
        let window =
            Arc::new(event_loop.create_window(attributes).map_err(|e| format!("cannot open a window: {e}"))?);
        let (presenter, device) = Presenter::open(event_loop, Arc::clone(&window))?;
        let gpu = match gpu::adapter_required() {
            true => Some(device),
            false => {
                eprintln!(
                    "note: {}=off: rendering on the CPU (the window is still drawn by the GPU)",
                    gpu::GPU_ENV
                );
                None
            }
        };
        let backend = match (args.backend, &gpu) {
            (BackendChoice::Gpu, Some(_)) => Backend::Gpu,
            _ => Backend::Cpu,
        };
        if let Some(gpu) = &gpu {
            eprintln!("drawing on {}", gpu.adapter_description());
        }
        eprintln!(
            "drag to orbit, scroll to zoom, R resets the camera, D toggles the GPU-vs-CPU difference, Esc quits"
        );
        let options = render::Options { specialize: !args.dynamic, lowering: args.lowering.into() };
        let mut watcher = FileWatcher::new().map_err(|e| e.to_string())?;
        // Watch the scene before the first render, so that an edit made during it is not missed.
        watcher.set([args.scene.clone()], []).map_err(|e| e.to_string())?;
        window.request_redraw();
        Ok(Viewer {
            window,
            presenter,
            gpu,
            backend,
            live: LiveScene::new(args.scene.clone(), args.include.clone(), options),
            watcher,
            reporter: Reporter::default(),
            orbit: Orbit::new(camera),
            mode: Mode::Picture,
            stale: Some(Vec::new()),
            tell: true,
            drag: None,
            cursor: PhysicalPosition::new(0.0, 0.0),
            frames: 0,
            unshown: false,
        })
    }

    /// Renders again, from now on, for `changed` files (none: a change of view).
    fn invalidate(&mut self, changed: Vec<PathBuf>, tell: bool) {
        self.stale.get_or_insert_with(Vec::new).extend(changed);
        self.tell |= tell;
        self.window.request_redraw();
    }

    fn handle(&mut self, event_loop: &ActiveEventLoop, event: WindowEvent) -> Result<(), String> {
        match event {
            WindowEvent::CloseRequested => event_loop.exit(),
            // The first `Resized` only reports the size the window was made with.
            WindowEvent::Resized(_) if self.presenter.resize() => self.invalidate(Vec::new(), false),
            WindowEvent::MouseInput { state, button: MouseButton::Left, .. } => {
                self.drag = (state == ElementState::Pressed).then_some(self.cursor);
            }
            WindowEvent::CursorMoved { position, .. } => {
                if let Some(from) = self.drag {
                    self.orbit.drag(position.x - from.x, position.y - from.y);
                    self.drag = Some(position);
                    self.invalidate(Vec::new(), false);
                }
                self.cursor = position;
            }
            WindowEvent::MouseWheel { delta, .. } => {
                let lines = match delta {
                    MouseScrollDelta::LineDelta(_, y) => y,
                    // Touchpads scroll in pixels: call a line about 40 of them.
                    MouseScrollDelta::PixelDelta(p) => p.y as f32 / 40.0,
                };
                self.orbit.scroll(lines);
                self.invalidate(Vec::new(), false);
            }
            WindowEvent::KeyboardInput { event, .. }
                if event.state == ElementState::Pressed && !event.repeat =>
            {
                match event.logical_key.as_ref() {
                    Key::Named(NamedKey::Escape) => event_loop.exit(),
                    Key::Character(c) if c.eq_ignore_ascii_case("q") => event_loop.exit(),
                    Key::Character(c) if c.eq_ignore_ascii_case("r") => {
                        self.orbit.reset();
                        self.invalidate(Vec::new(), false);
                    }
                    Key::Character(c) if c.eq_ignore_ascii_case("d") => self.toggle_difference(),
                    _ => {}
                }
            }
            WindowEvent::RedrawRequested => self.redraw()?,
            _ => {}
        }
        Ok(())
    }

    fn toggle_difference(&mut self) {
        if self.gpu.is_none() {
            eprintln!("note: no GPU to compare the CPU reference with ({}=off)", gpu::GPU_ENV);
            return;
        }
        self.mode = match self.mode {
            Mode::Picture => Mode::Difference,
            Mode::Difference => Mode::Picture,
        };
        self.invalidate(Vec::new(), true);
    }

    /// Looks for changed files (without waiting) and renders again when there are some.
    fn poll_files(&mut self) -> Result<(), String> {
        if let Some(changed) = self.watcher.wait(Duration::ZERO).map_err(|e| e.to_string())? {
            self.live.invalidate(&changed);
            self.invalidate(changed, true);
        }
        Ok(())
    }

    /// Renders the picture when it is stale, then shows the latest good one.
    fn redraw(&mut self) -> Result<(), String> {
        if let Some(changed) = self.stale.take() {
            let started = Instant::now();
            let outcome = self.render().map(|(image, summary)| {
                self.presenter.show(&image);
                self.unshown = true;
                summary
            });
            let kept = (self.frames > 0).then_some("kept the last good picture on screen");
            if self.tell || outcome.is_err() {
                self.reporter.report(&changed, outcome, kept, started);
            }
            self.tell = false;
            let (files, dirs) = self.live.to_watch(self.reporter.failing());
            self.watcher.set(files, dirs).map_err(|e| e.to_string())?;
        }
        if self.presenter.present() && self.unshown {
            self.unshown = false;
            self.frames += 1;
            // Tests and scripts wait for this line.
            eprintln!("frame {} presented", self.frames);
        }
        Ok(())
    }

    /// Loads, prepares and renders the scene from the orbit's camera at the window's size; the
    /// picture and a summary, or why not (a shader's diagnostics as `patina watch` prints them).
    fn render(&mut self) -> Result<(Image, String), String> {
        let mut scene = self.live.load()?;
        self.orbit.restart(scene.camera());
        scene.camera = self.orbit.camera();
        (scene.output.width, scene.output.height) = self.presenter.size();
        let started = Instant::now();
        let (prepared, compiled) = self.live.prepare(&scene)?;
        let compile = started.elapsed();
        let started = Instant::now();
        let (image, what) = match self.mode {
            Mode::Picture => {
                let image = render::render(&prepared, self.backend, self.gpu.as_ref()).map_err(failure)?;
                let device = match self.backend {
                    Backend::Gpu => self.gpu.as_ref().map_or_else(String::new, Gpu::adapter_description),
                    Backend::Cpu => "the CPU reference".into(),
                };
                (image, format!("rendered on {device}"))
            }
            Mode::Difference => self.difference(&prepared)?,
        };
        let summary = format!(
            "{what} ({}x{}): compile {:.1} ms ({compiled} programs compiled), render {:.1} ms",
            image.width,
            image.height,
            compile.as_secs_f64() * 1e3,
            started.elapsed().as_secs_f64() * 1e3,
        );
        Ok((image, summary))
    }

    /// The difference picture of the GPU's and the CPU reference's renders, and what the
    /// gallery's comparison says of them.
    fn difference(&self, prepared: &render::Prepared) -> Result<(Image, String), String> {
        let on_gpu = render::render(prepared, Backend::Gpu, self.gpu.as_ref()).map_err(failure)?;
        let on_cpu = render::render(prepared, Backend::Cpu, None).map_err(failure)?;
        let thresholds = Thresholds::default();
        let c = compare(&on_gpu, &on_cpu, &thresholds).map_err(|e| format!("error: {e}"))?;
        let verdict = if c.passes(&thresholds) { "within" } else { "outside" };
        let what = format!(
            "difference |gpu - cpu| x{DIFF_SCALE}: max {:.1e}, mean {:.1e}, {} of {} pixels over {} \
             ({verdict} the gallery's thresholds)",
            c.max_error, c.mean_error, c.failing_pixels, c.pixels, thresholds.fail
        );
        Ok((Image::diff_image(&on_gpu, &on_cpu, DIFF_SCALE), what))
    }
}
