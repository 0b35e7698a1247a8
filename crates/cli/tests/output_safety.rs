//! Outputs never destroy inputs (issue 13) and are checked before any computation (issue 12):
//! same-path and hard-link outputs, symlinks, devices and FIFOs at `-o`, wrong extensions,
//! missing folders, unknown muscle names, negative numbers, file modes.

#![cfg(unix)]

use std::os::unix::fs::PermissionsExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};
use std::sync::OnceLock;

fn facebem_sh(script_args: &[&str], umask: &str) -> Output {
    // `sh -c 'umask U; exec facebem "$@"'` runs facebem under a known umask.
    Command::new("sh")
        .arg("-c")
        .arg(format!("umask {umask}; exec \"$0\" \"$@\""))
        .arg(env!("CARGO_BIN_EXE_facebem"))
        .args(script_args)
        .output()
        .unwrap()
}

fn facebem(args: &[&str]) -> Output {
    facebem_sh(args, "022")
}

fn face() -> PathBuf {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .join("assets/mediapipe_canonical_4loop.obj")
}

fn s(p: &Path) -> &str {
    p.to_str().unwrap()
}

/// A rig of the default face, computed once.
fn rig() -> &'static (tempfile::TempDir, PathBuf) {
    static RIG: OnceLock<(tempfile::TempDir, PathBuf)> = OnceLock::new();
    RIG.get_or_init(|| {
        let dir = tempfile::tempdir().unwrap();
        let rig = dir.path().join("face.rig");
        let out = facebem(&["rig", s(&face()), "-o", s(&rig)]);
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        (dir, rig)
    })
}

/// Exit 1, one line, containing every needle, and nothing computed first.
fn assert_refused(out: &Output, needles: &[&str]) {
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    let lines: Vec<&str> = err.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "{err:?}");
    for n in needles {
        assert!(lines[0].contains(n), "{:?} lacks {n:?}", lines[0]);
    }
    let said = String::from_utf8_lossy(&out.stdout);
    assert!(!said.contains("computing its rig first"), "{said}");
}

#[test]
fn output_equal_to_an_input_is_refused_and_the_input_kept() {
    let (_d, rig) = rig();
    let dir = tempfile::tempdir().unwrap();
    let copy = dir.path().join("c.rig");
    std::fs::copy(rig, &copy).unwrap();
    let before = std::fs::read(&copy).unwrap();
    // The same path, and a hard link named with the right extension.
    let link = dir.path().join("link.obj");
    std::fs::hard_link(&copy, &link).unwrap();
    let obj = dir.path().join("face.obj");
    std::fs::copy(face(), &obj).unwrap();
    let obj_before = std::fs::read(&obj).unwrap();
    for args in [
        vec!["pose", s(&copy), "-o", s(&link)],
        vec!["export", s(&copy), "--gltf", s(&copy)],
        vec!["rig", s(&obj), "-o", s(&obj)],
        vec!["muscles", s(&copy), "-o", s(&copy)],
        vec!["pose", s(&copy), "-o", s(&copy)],
    ] {
        let out = facebem(&args);
        let err = String::from_utf8_lossy(&out.stderr);
        assert_eq!(out.status.code(), Some(1), "{args:?}: {err}");
        assert!(err.lines().count() == 1, "{args:?}: {err}");
    }
    let out = facebem(&["pose", s(&copy), "-o", s(&link)]);
    assert_refused(&out, &["is the input", "would be destroyed"]);
    let same_obj = facebem(&["pose", s(&obj), "-o", s(&obj)]);
    assert_refused(&same_obj, &["is the input"]);
    assert_eq!(std::fs::read(&copy).unwrap(), before);
    assert_eq!(std::fs::read(&obj).unwrap(), obj_before);
}

#[test]
fn symlink_fifo_and_device_at_the_output_are_left_untouched() {
    let (_d, rig) = rig();
    let dir = tempfile::tempdir().unwrap();
    let target = dir.path().join("target.obj");
    std::fs::write(&target, b"precious").unwrap();
    let link = dir.path().join("link.obj");
    std::os::unix::fs::symlink(&target, &link).unwrap();
    let out = facebem(&["pose", s(rig), "-o", s(&link)]);
    assert_refused(&out, &["symbolic link"]);
    assert!(
        std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink()
    );
    assert_eq!(std::fs::read(&target).unwrap(), b"precious");

    let fifo = dir.path().join("fifo.obj");
    let made = Command::new("mkfifo").arg(&fifo).status().unwrap();
    assert!(made.success());
    let out = facebem(&["pose", s(rig), "-o", s(&fifo)]);
    assert_refused(&out, &["FIFO"]);
    // A FIFO given as INPUT is refused without blocking on it.
    let fifo_in = dir.path().join("fifo_in.obj");
    assert!(
        Command::new("mkfifo")
            .arg(&fifo_in)
            .status()
            .unwrap()
            .success()
    );
    let out = facebem(&["info", s(&fifo_in)]);
    assert_refused(&out, &["not a regular file"]);

    // A device node (the shell's /dev/null is one); named .glb so the extension passes.
    let dev = dir.path().join("null.glb");
    std::os::unix::fs::symlink("/dev/null", &dev).unwrap();
    let out = facebem(&["export", s(rig), "--gltf", s(&dev)]);
    assert_refused(&out, &["symbolic link"]);
    let out = facebem(&["export", s(rig), "--gltf", "/dev/null"]);
    assert_refused(&out, &["must end in .glb or .gltf"]);
    let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert_eq!(names.len(), 5, "only the five files made here: {names:?}");
}

#[test]
fn wrong_extension_missing_folder_and_unknown_names_fail_before_computing() {
    let (_d, rig) = rig();
    let dir = tempfile::tempdir().unwrap();
    let d = dir.path();
    let face = face();
    let missing = d.join("missing_dir/x.rig");
    let cases: Vec<(Vec<String>, Vec<&str>)> = vec![
        (
            vec![
                "export".into(),
                s(rig).into(),
                "--gltf".into(),
                s(&d.join("out.obj")).into(),
            ],
            vec!["must end in .glb or .gltf"],
        ),
        (
            vec![
                "pose".into(),
                s(rig).into(),
                "-o".into(),
                s(&d.join("p.glb")).into(),
            ],
            vec!["must end in .obj"],
        ),
        (
            vec![
                "rig".into(),
                s(&face).into(),
                "-o".into(),
                s(&missing).into(),
            ],
            vec!["missing_dir", "does not exist"],
        ),
        (
            vec![
                "rig".into(),
                s(&face).into(),
                "-o".into(),
                s(&d.join("x.obj")).into(),
            ],
            vec!["must end in .rig"],
        ),
        (
            vec![
                "muscles".into(),
                s(&face).into(),
                "-o".into(),
                s(&d.join("m.txt")).into(),
            ],
            vec!["must end in .muscles"],
        ),
        (
            vec![
                "pose".into(),
                s(&face).into(),
                "--set".into(),
                "buccinator=0.5".into(),
                "-o".into(),
                s(&d.join("p.obj")).into(),
            ],
            vec!["unknown muscle \"buccinator\""],
        ),
        (
            vec![
                "pose".into(),
                s(&face).into(),
                "--preset".into(),
                "grumpy".into(),
                "-o".into(),
                s(&d.join("p.obj")).into(),
            ],
            vec!["unknown preset"],
        ),
        (
            vec![
                "export".into(),
                s(&face).into(),
                "--gltf".into(),
                s(&d.join("nope/x.glb")).into(),
            ],
            vec!["does not exist"],
        ),
    ];
    for (args, needles) in cases {
        let args: Vec<&str> = args.iter().map(String::as_str).collect();
        assert_refused(&facebem(&args), &needles);
    }
    assert_eq!(std::fs::read_dir(d).unwrap().count(), 0);
}

#[test]
fn negative_numbers_reach_the_range_check() {
    let dir = tempfile::tempdir().unwrap();
    let out = facebem(&[
        "rig",
        s(&face()),
        "-o",
        s(&dir.path().join("x.rig")),
        "--poisson",
        "-1",
    ]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(
        err.contains("--poisson -1.0 is out of range: must be in [0, 0.49]"),
        "{err}"
    );
    assert!(!err.contains("-- -1"), "{err}");
}

#[test]
fn new_files_get_the_umask_mode_and_replaced_files_keep_theirs() {
    let (_d, rig) = rig();
    let dir = tempfile::tempdir().unwrap();
    let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
    let pose = dir.path().join("p.obj");
    let glb = dir.path().join("e.glb");
    let muscles = dir.path().join("m.muscles");
    assert!(facebem(&["pose", s(rig), "-o", s(&pose)]).status.success());
    assert!(
        facebem(&["export", s(rig), "--gltf", s(&glb)])
            .status
            .success()
    );
    assert!(
        facebem(&["muscles", s(rig), "-o", s(&muscles)])
            .status
            .success()
    );
    for p in [&pose, &glb, &muscles, rig] {
        assert_eq!(mode(p), 0o644, "{}", p.display());
    }
    let strict = facebem_sh(&["pose", s(rig), "-o", s(&dir.path().join("q.obj"))], "077");
    assert!(strict.status.success());
    assert_eq!(mode(&dir.path().join("q.obj")), 0o600);
    // An existing file keeps its mode when replaced.
    std::fs::set_permissions(&pose, std::fs::Permissions::from_mode(0o640)).unwrap();
    assert!(
        facebem(&["pose", s(rig), "--preset", "happy", "-o", s(&pose)])
            .status
            .success()
    );
    assert_eq!(mode(&pose), 0o640);
    // No temporary file is left behind.
    for e in std::fs::read_dir(dir.path()).unwrap() {
        let name = e.unwrap().file_name();
        assert!(!name.to_string_lossy().ends_with(".tmp"), "{name:?}");
    }
}

/// Regression (found piping `facebem export face.obj --gltf f.glb | head -1`): a reader that
/// closes stdout early made `println!` panic ("failed printing to stdout: Broken pipe", exit
/// 101). Now the report stops and the command goes on: success, the file written in full.
/// Writing to a full stdout (/dev/full) is one line and exit code 1.
#[test]
fn a_closed_or_full_stdout_is_no_panic() {
    let dir = tempfile::tempdir().unwrap();
    let glb = dir.path().join("f.glb");
    let mut child = Command::new(env!("CARGO_BIN_EXE_facebem"))
        .arg("export")
        .arg(face())
        .arg("--gltf")
        .arg(&glb)
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    drop(child.stdout.take());
    let out = child.wait_with_output().unwrap();
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{:?}: {stderr}", out.status);
    assert!(!stderr.contains("panicked"), "{stderr}");
    assert_eq!(&std::fs::read(&glb).unwrap()[..4], b"glTF");

    let Ok(dev_full) = std::fs::File::create("/dev/full") else {
        eprintln!("SKIPPED the full-stdout half: this machine has no /dev/full");
        return;
    };
    let full = Command::new(env!("CARGO_BIN_EXE_facebem"))
        .arg("info")
        .arg(face())
        .stdout(dev_full)
        .output()
        .unwrap();
    let stderr = String::from_utf8_lossy(&full.stderr);
    assert_eq!(full.status.code(), Some(1), "{stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "{stderr}");
    assert!(stderr.starts_with("error: writing to stdout"), "{stderr}");
}
