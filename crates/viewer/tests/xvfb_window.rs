//! A real window: starts Xvfb and the `viewer` binary on it, waits until the face is drawn,
//! screenshots the screen with ImageMagick's `import -window root`, checks the face is visible
//! and that the app closes cleanly by itself (`--exit-after-ready`).
//!
//! Needs `xvfb xauth imagemagick` (apt) and Vulkan lavapipe (`mesa-vulkan-drivers libvulkan1`).
//! Set `FACEBEM_SKIP_XVFB=1` to skip on a machine without them; CI must not set it.

use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::time::{Duration, Instant};

/// Kills the child we started (Xvfb) when the test ends, even on failure.
struct KillOnDrop(Child);

impl Drop for KillOnDrop {
    fn drop(&mut self) {
        let _ = self.0.kill();
        let _ = self.0.wait();
    }
}

fn wait_for(what: &str, limit: Duration, mut done: impl FnMut() -> bool) {
    let start = Instant::now();
    while !done() {
        assert!(
            start.elapsed() < limit,
            "gave up waiting for {what} after {limit:?}"
        );
        std::thread::sleep(Duration::from_millis(50));
    }
}

#[test]
fn real_window_under_xvfb_shows_the_face_and_closes_cleanly() {
    if std::env::var_os("FACEBEM_SKIP_XVFB").is_some() {
        eprintln!("FACEBEM_SKIP_XVFB set: skipping the Xvfb window test");
        return;
    }
    let dir = tempfile::tempdir().unwrap();
    let (_xvfb, display) = start_xvfb();

    let runtime = private_runtime_dir(dir.path());
    let ready = dir.path().join("ready");
    let mut viewer = Command::new(env!("CARGO_BIN_EXE_viewer"))
        .arg("--ready-file")
        .arg(&ready)
        .args(["--exit-after-ready", "3"])
        .env("DISPLAY", &display)
        .env_remove("WAYLAND_DISPLAY")
        .env("XDG_RUNTIME_DIR", &runtime)
        .env("XDG_CACHE_HOME", dir.path().join("cache"))
        .env(
            "WGPU_BACKEND",
            std::env::var("WGPU_BACKEND").unwrap_or("vulkan".into()),
        )
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("start the viewer binary");
    let started = Instant::now();
    let mut exited = None;
    wait_for(
        "the viewer to draw the face",
        Duration::from_secs(300),
        || {
            if let Ok(Some(status)) = viewer.try_wait() {
                exited = Some(status);
                return true;
            }
            ready.exists()
        },
    );
    assert!(exited.is_none(), "the viewer exited early: {exited:?}");

    let shot = dir.path().join("shot.png");
    let import = Command::new("import")
        .args(["-display", &display, "-window", "root"])
        .arg(&shot)
        .status()
        .expect("ImageMagick `import` not found: apt-get install imagemagick");
    assert!(import.success(), "import failed: {import}");

    let status = loop {
        if let Some(s) = viewer.try_wait().unwrap() {
            break s;
        }
        assert!(
            started.elapsed() < Duration::from_secs(300),
            "the viewer did not close"
        );
        std::thread::sleep(Duration::from_millis(50));
    };
    let mut stderr = String::new();
    if let Some(mut e) = viewer.stderr.take() {
        use std::io::Read;
        let _ = e.read_to_string(&mut stderr);
    }
    assert!(
        status.success(),
        "viewer exit status {status}; stderr:\n{stderr}"
    );

    let img = image::open(&shot).unwrap().to_rgba8();
    assert_eq!(img.dimensions(), (1280, 800));
    // The window is 1280×800 at the top-left (no window manager). The viewport lies right of
    // the 300-pt control panel; its background is BACKGROUND, the face is skin coloured.
    let (bg, face, total) = face_coloured_pixels(&img);
    assert!(
        face * 10 > total,
        "only {face} of {total} sampled viewport pixels are face-coloured (background {bg:?})"
    );
}

/// Starts Xvfb on a free display and waits for its socket; returns the process (killed when
/// dropped) and the `DISPLAY` value.
fn start_xvfb() -> (KillOnDrop, String) {
    // Xvfb picks a free display itself and writes its number to the pipe (-displayfd).
    let mut xvfb = Command::new("Xvfb")
        .args([
            "-displayfd",
            "1",
            "-screen",
            "0",
            "1280x800x24",
            "-nolisten",
            "tcp",
        ])
        .stdout(Stdio::piped())
        .stderr(Stdio::null())
        .spawn()
        .expect("Xvfb not found: apt-get install xvfb xauth imagemagick (or FACEBEM_SKIP_XVFB=1)");
    let stdout = xvfb.stdout.take().expect("piped stdout");
    let xvfb = KillOnDrop(xvfb);
    let mut line = String::new();
    std::io::BufRead::read_line(&mut std::io::BufReader::new(stdout), &mut line)
        .expect("read the display number from Xvfb");
    let display_number: u32 = line.trim().parse().expect("Xvfb printed a display number");
    let display = format!(":{display_number}");
    let socket = format!("/tmp/.X11-unix/X{display_number}");
    wait_for("the Xvfb socket", Duration::from_secs(30), || {
        Path::new(&socket).exists()
    });
    (xvfb, display)
}

/// A private `XDG_RUNTIME_DIR` (mode 0700, as the spec requires) under `dir`.
fn private_runtime_dir(dir: &Path) -> PathBuf {
    let runtime = dir.join("runtime");
    std::fs::create_dir(&runtime).unwrap();
    #[cfg(unix)]
    {
        use std::os::unix::fs::PermissionsExt;
        std::fs::set_permissions(&runtime, std::fs::Permissions::from_mode(0o700)).unwrap();
    }
    runtime
}

/// Samples the viewport of the screenshot: the background colour (right edge of the window),
/// how many sampled pixels differ from it and are skin coloured, and how many were sampled.
fn face_coloured_pixels(img: &image::RgbaImage) -> ([u8; 4], usize, usize) {
    let bg = img.get_pixel(1270, 400).0;
    let mut face = 0;
    let mut total = 0;
    for y in (100..700).step_by(2) {
        for x in (420..1260).step_by(2) {
            total += 1;
            let p = img.get_pixel(x, y).0;
            let differs = p.iter().zip(bg).take(3).any(|(a, b)| a.abs_diff(b) > 10);
            let skin = p[0] > p[2] + 30 && p[0] > 90;
            if differs && skin {
                face += 1;
            }
        }
    }
    (bg, face, total)
}
