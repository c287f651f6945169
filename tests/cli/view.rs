//! `patina view` in a virtual X server (Xvfb, the window drawn by whatever Vulkan driver there is:
//! lavapipe on a machine without a GPU): a screenshot of the window matches `patina render` of the
//! scene within the gallery's thresholds, editing the shader changes the next screenshot, and an
//! error keeps the old picture and prints the diagnostic. Also how long an edit takes to reach the
//! screen, and the one-line errors without a display or a scene.
//!
//! Xvfb keeps its screen in a file (`-fbdir`), an XWD image read here directly. The test fails
//! when Xvfb is missing, unless `PATINA_VIEW=off` says to skip it.

use std::io::{BufRead, BufReader};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::mpsc;
use std::time::{Duration, Instant};

use patina_runtime::image::{Image, Thresholds, compare};

use crate::support::{patina, scratch_dir};

/// The window's size, and the screen's (larger, so that the whole window is on it).
const WINDOW: (u32, u32) = (160, 120);
const SCREEN: &str = "640x480x24";

/// How long any one expected line or picture may take (a debug build compiling on lavapipe).
const TIMEOUT: Duration = Duration::from_secs(60);

/// A child process killed when the test ends, passing or not.
struct Killed(Child);

impl Drop for Killed {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

/// A virtual X server with its screen in `dir`; `None` when `PATINA_VIEW=off`.
fn xvfb(dir: &Path) -> Option<(Killed, String)> {
    if std::env::var_os("PATINA_VIEW").is_some_and(|v| v.eq_ignore_ascii_case("off")) {
        eprintln!("PATINA_VIEW=off: skipping the window test");
        return None;
    }
    // A display number of this process's own, past any taken (their sockets are in /tmp/.X11-unix).
    for n in (100 + std::process::id() % 800..).take(50) {
        let socket = PathBuf::from(format!("/tmp/.X11-unix/X{n}"));
        if socket.exists() || Path::new(&format!("/tmp/.X{n}-lock")).exists() {
            continue;
        }
        let child = match Command::new("Xvfb")
            .args([&format!(":{n}"), "-screen", "0", SCREEN, "-nolisten", "tcp", "-fbdir"])
            .arg(dir)
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::null())
            .spawn()
        {
            Ok(child) => child,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => panic!(
                "\n\n*** the window test needs Xvfb: install the `xvfb` package (apt-get install xvfb), \
                 or set PATINA_VIEW=off to skip it ***\n\n"
            ),
            Err(e) => panic!("cannot start Xvfb: {e}"),
        };
        let mut server = Killed(child);
        let deadline = Instant::now() + Duration::from_secs(10);
        while Instant::now() < deadline {
            if socket.exists() && dir.join("Xvfb_screen0").exists() {
                return Some((server, format!(":{n}")));
            }
            if server.0.try_wait().ok().flatten().is_some() {
                break; // Lost a race for the number: try the next.
            }
            std::thread::sleep(Duration::from_millis(20));
        }
    }
    panic!("Xvfb did not start on any display number tried");
}

/// The top-left `width` x `height` of Xvfb's screen (an XWD file: big-endian header, then the
/// colour map, then the pixels), opaque.
fn screenshot(fb: &Path, (width, height): (u32, u32)) -> Image {
    let bytes = std::fs::read(fb).expect("Xvfb's screen file");
    let field = |i: usize| u32::from_be_bytes(bytes[4 * i..4 * i + 4].try_into().unwrap());
    let (header_size, byte_order, bits_per_pixel, bytes_per_line) =
        (field(0), field(7), field(11), field(12));
    let (masks, colours) = ([field(14), field(15), field(16)], field(19));
    assert_eq!(bits_per_pixel, 32, "Xvfb's screen is 32 bits a pixel at depth 24");
    let start = header_size as usize + 12 * colours as usize;
    let mut image = Image::new(width, height, [0.0, 0.0, 0.0, 1.0]);
    for y in 0..height {
        for x in 0..width {
            let at = start + y as usize * bytes_per_line as usize + 4 * x as usize;
            let word: [u8; 4] = bytes[at..at + 4].try_into().unwrap();
            let pixel = if byte_order == 0 { u32::from_le_bytes(word) } else { u32::from_be_bytes(word) };
            let channel = |mask: u32| ((pixel & mask) >> mask.trailing_zeros()) as f32 / 255.0;
            image.set(x, y, [channel(masks[0]), channel(masks[1]), channel(masks[2]), 1.0]);
        }
    }
    image
}

/// `patina view` of `scene` on `display` at the window's size, with `more` arguments; its stderr.
fn view(scene: &Path, display: &str, more: &[&str]) -> (Killed, Lines) {
    let size = format!("{}x{}", WINDOW.0, WINDOW.1);
    let mut view = Killed(
        Command::new(env!("CARGO_BIN_EXE_patina"))
            .args(["view", &scene.display().to_string(), "--size", &size])
            .args(more)
            .env("DISPLAY", display)
            .env("NODEVICE_SELECT", "1")
            .stdin(Stdio::null())
            .stdout(Stdio::null())
            .stderr(Stdio::piped())
            .spawn()
            .expect("the patina binary runs"),
    );
    let lines = Lines::new(&mut view.0);
    (view, lines)
}

/// `patina render` of `scene`, opaque (the window shows colour without alpha).
fn rendered(scene: &Path, more: &[&str]) -> Image {
    let png = scene.with_extension("png");
    let (scene, output) = (scene.display().to_string(), png.display().to_string());
    let out = patina(&[&["render", scene.as_str(), "-o", output.as_str()], more].concat());
    assert!(out.status.success(), "patina render: {}", String::from_utf8_lossy(&out.stderr));
    let mut image = Image::read_png(&png).expect("the rendered PNG");
    image.pixels.iter_mut().for_each(|p| p[3] = 1.0);
    image
}

/// `patina view`'s stderr, line by line as it comes, each with when it came.
struct Lines {
    received: mpsc::Receiver<(Instant, String)>,
    log: Vec<String>,
}

impl Lines {
    fn new(child: &mut Child) -> Lines {
        let stderr = child.stderr.take().expect("stderr is piped");
        let (lines, received) = mpsc::channel();
        std::thread::spawn(move || {
            for line in BufReader::new(stderr).lines().map_while(Result::ok) {
                if lines.send((Instant::now(), line)).is_err() {
                    break;
                }
            }
        });
        Lines { received, log: Vec::new() }
    }

    /// Waits for a line containing `text`; when it came.
    fn until(&mut self, text: &str) -> Instant {
        let deadline = Instant::now() + TIMEOUT;
        while let Some(left) = deadline.checked_duration_since(Instant::now()) {
            match self.received.recv_timeout(left) {
                Ok((at, line)) => {
                    let found = line.contains(text);
                    self.log.push(line);
                    if found {
                        return at;
                    }
                }
                Err(_) => break,
            }
        }
        panic!(
            "`patina view` printed no line with {text:?} within {TIMEOUT:?}; it printed:\n{}",
            self.log.join("\n")
        );
    }
}

/// Waits until the window shows `expected` (the server may draw a presented frame a moment
/// later), failing with the comparison.
fn shows(fb: &Path, expected: &Image, what: &str, lines: &Lines) -> Image {
    let thresholds = Thresholds::default();
    let deadline = Instant::now() + Duration::from_secs(5);
    loop {
        let shot = screenshot(fb, WINDOW);
        let c = compare(&shot, expected, &thresholds).expect("same sizes");
        if c.passes(&thresholds) {
            return shot;
        }
        if Instant::now() > deadline {
            panic!(
                "the window does not show {what}: {c:?}\n`patina view` printed:\n{}",
                lines.log.join("\n")
            );
        }
        std::thread::sleep(Duration::from_millis(50));
    }
}

/// The plastic scene of the examples at the window's size, with its shaders beside it.
fn scene(dir: &Path) -> PathBuf {
    let examples = Path::new(env!("CARGO_MANIFEST_DIR")).join("examples");
    for shader in ["plastic.sl", "lights.sl"] {
        std::fs::copy(examples.join("shaders").join(shader), dir.join(shader)).expect("copy a shader");
    }
    let text = std::fs::read_to_string(examples.join("scenes/plastic.toml")).expect("the plastic scene");
    let text = text
        .replace("../shaders/", "")
        .replace("width = 320", &format!("width = {}", WINDOW.0))
        .replace("height = 240", &format!("height = {}", WINDOW.1));
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, text).unwrap();
    scene
}

/// `plastic.sl` with its surface colour replaced by `colour`.
fn recoloured(original: &str, colour: &str) -> String {
    let edited = original.replace("(Cs *", &format!("(color {colour} *"));
    assert_ne!(edited, original, "plastic.sl has the expression this test edits");
    edited
}

#[test]
fn the_window_shows_the_render_follows_edits_and_keeps_the_picture_on_an_error() {
    let dir = scratch_dir("view", "window");
    let Some((_server, display)) = xvfb(&dir) else { return };
    let fb = dir.join("Xvfb_screen0");
    let scene = scene(&dir);
    let shader = dir.join("plastic.sl");
    let original = std::fs::read_to_string(&shader).unwrap();
    let (_view, mut lines) = view(&scene, &display, &[]);
    lines.until("frame 1 presented");
    let first = shows(&fb, &rendered(&scene, &[]), "`patina render` of the scene", &lines);

    // Edits, each timed from its write to the frame showing it.
    let colours =
        ["(0.2, 0.8, 0.3)", "(0.3, 0.4, 0.9)", "(0.9, 0.9, 0.2)", "(0.8, 0.2, 0.7)", "(0.2, 0.8, 0.8)"];
    let mut latencies = Vec::new();
    let mut last = None;
    for (i, colour) in colours.iter().enumerate() {
        // Apart by more than the watcher's debounce, so that each edit is its own change.
        std::thread::sleep(Duration::from_millis(300));
        let written = Instant::now();
        std::fs::write(&shader, recoloured(&original, colour)).unwrap();
        let presented = lines.until(&format!("frame {} presented", i + 2));
        latencies.push(presented - written);
        last = Some(shows(&fb, &rendered(&scene, &[]), &format!("the edit to colour {colour}"), &lines));
    }
    latencies.sort();
    eprintln!(
        "edit-to-new-frame latency: median {:.0} ms over {} edits (min {:.0}, max {:.0})",
        latencies[latencies.len() / 2].as_secs_f64() * 1e3,
        latencies.len(),
        latencies[0].as_secs_f64() * 1e3,
        latencies[latencies.len() - 1].as_secs_f64() * 1e3,
    );
    let before = last.expect("the edits were shown");
    assert_ne!(before, first, "the edits changed the picture");

    // A syntax error: the diagnostic is printed and the picture stays.
    std::fs::write(&shader, original.replace("Oi = Os;", "Oi = Os")).unwrap();
    lines.until("error[");
    lines.until("kept the last good picture on screen");
    std::thread::sleep(Duration::from_millis(500));
    assert_eq!(
        screenshot(&fb, WINDOW),
        before,
        "the picture before the error stays:\n{}",
        lines.log.join("\n")
    );
    assert!(!lines.log.iter().any(|l| l.contains(&format!("frame {} presented", colours.len() + 2))));
}

#[test]
fn the_cpu_backend_shows_the_cpu_reference() {
    let dir = scratch_dir("view", "cpu");
    let Some((_server, display)) = xvfb(&dir) else { return };
    let scene = scene(&dir);
    let (_view, mut lines) = view(&scene, &display, &["--backend", "cpu"]);
    lines.until("frame 1 presented");
    let expected = rendered(&scene, &["--backend", "cpu"]);
    shows(&dir.join("Xvfb_screen0"), &expected, "`patina render --backend cpu`", &lines);
    assert!(
        lines.log.iter().any(|l| l.contains("rendered on the CPU reference")),
        "{}",
        lines.log.join("\n")
    );
}

#[test]
fn without_a_display_one_line_and_a_failure() {
    let dir = scratch_dir("view", "no_display");
    let scene = scene(&dir);
    let out = Command::new(env!("CARGO_BIN_EXE_patina"))
        .args(["view", &scene.display().to_string()])
        .env_remove("DISPLAY")
        .env_remove("WAYLAND_DISPLAY")
        .output()
        .expect("the patina binary runs");
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("DISPLAY"), "{stderr}");
}

#[test]
fn a_missing_scene_is_one_line_and_a_failure() {
    let out = patina(&["view", "no/such/scene.toml"]);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "{stderr}");
    assert_eq!(stderr.trim().lines().count(), 1, "{stderr}");
    assert!(stderr.contains("scene.toml"), "{stderr}");
}
