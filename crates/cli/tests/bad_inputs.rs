//! The regression corpus of hostile and broken files (`tests/bad_inputs/`, issue 13): each
//! gives the exit status and one-line message `EXPECTED.tsv` names, and writes nothing.

use std::path::{Path, PathBuf};
use std::process::Command;

fn corpus() -> PathBuf {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("tests/bad_inputs")
}

fn listing(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

struct Row {
    file: String,
    exit: i32,
    needle: String,
}

fn rows() -> Vec<Row> {
    let text = std::fs::read_to_string(corpus().join("EXPECTED.tsv")).unwrap();
    text.lines()
        .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
        .map(|l| {
            let mut parts = l.splitn(3, '\t');
            let file = parts.next().unwrap().to_owned();
            let exit = parts.next().expect(l).trim().parse().expect(l);
            let needle = parts.next().unwrap_or("").to_owned();
            Row { file, exit, needle }
        })
        .collect()
}

fn run(row: &Row) -> Result<(), String> {
    let dir = tempfile::tempdir().unwrap();
    let input = dir.path().join(&row.file);
    std::fs::copy(corpus().join(&row.file), &input).map_err(|e| format!("copy: {e}"))?;
    let before = listing(dir.path());
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_facebem"));
    let out_rig = dir.path().join("out.rig");
    if row.file.ends_with(".muscles") {
        let face = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
            .join("assets/mediapipe_canonical_4loop.obj");
        cmd.arg("rig")
            .arg(&face)
            .arg("--muscles")
            .arg(&input)
            .arg("-o")
            .arg(&out_rig);
    } else {
        cmd.arg("info").arg(&input);
    }
    let out = cmd.output().map_err(|e| format!("spawn: {e}"))?;
    let stderr = String::from_utf8_lossy(&out.stderr);
    let code = out.status.code();
    if code != Some(row.exit) {
        return Err(format!("exit {code:?}, expected {}: {stderr}", row.exit));
    }
    if row.exit != 0 {
        let lines: Vec<&str> = stderr.lines().collect();
        if lines.len() != 1 || !lines[0].starts_with("error: ") {
            return Err(format!("not a one-line error: {stderr:?}"));
        }
        if !lines[0].contains(&row.needle) {
            return Err(format!("message lacks {:?}: {}", row.needle, lines[0]));
        }
        if lines[0].len() > 600 {
            return Err(format!("message of {} bytes", lines[0].len()));
        }
        if listing(dir.path()) != before {
            return Err(format!("wrote files: {:?}", listing(dir.path())));
        }
    }
    Ok(())
}

#[test]
fn every_corpus_file_fails_as_expected_and_writes_nothing() {
    let rows = rows();
    assert!(rows.len() >= 40, "{} rows", rows.len());
    let listed: Vec<&str> = rows.iter().map(|r| r.file.as_str()).collect();
    for name in listing(&corpus()) {
        let data = !(name.ends_with(".md") || name.ends_with(".tsv") || name.ends_with(".py"));
        assert!(
            !data || listed.contains(&name.as_str()),
            "{name} has no row in EXPECTED.tsv"
        );
    }
    let failures: Vec<String> = rows
        .iter()
        .filter_map(|r| run(r).err().map(|e| format!("{}: {e}", r.file)))
        .collect();
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

#[test]
fn input_limits_are_overridable_from_the_command_line() {
    let face = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .join("assets/mediapipe_canonical_4loop.obj");
    let run = |args: &[&str]| {
        let out = Command::new(env!("CARGO_BIN_EXE_facebem"))
            .arg("info")
            .arg(&face)
            .args(args)
            .output()
            .unwrap();
        (
            out.status.code(),
            String::from_utf8_lossy(&out.stderr).into_owned(),
        )
    };
    let (code, err) = run(&["--max-input-triangles", "100"]);
    assert_eq!(code, Some(1), "{err}");
    assert!(
        err.contains("input too large: 468 positions, the limit is 100"),
        "{err}"
    );
    let (code, err) = run(&["--max-input-mb", "0"]);
    assert_eq!(code, Some(1), "{err}");
    assert!(
        err.contains("input too large: 25774 file bytes, the limit is 0"),
        "{err}"
    );
    let (code, err) = run(&["--max-input-triangles", "852"]);
    assert_eq!(code, Some(0), "{err}");
}

#[test]
fn muscle_limit_is_overridable_from_the_command_line() {
    let face = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .join("assets/mediapipe_canonical_4loop.obj");
    let dir = tempfile::tempdir().unwrap();
    let muscles = dir.path().join("two.muscles");
    std::fs::write(
        &muscles,
        "[Name]\nm0\n[Size]\n1\n[Data]\n0\n[Name]\nm1\n[Size]\n1\n[Data]\n1\n",
    )
    .unwrap();
    let out_rig = dir.path().join("out.rig");
    let out = Command::new(env!("CARGO_BIN_EXE_facebem"))
        .arg("rig")
        .arg(&face)
        .arg("--muscles")
        .arg(&muscles)
        .arg("-o")
        .arg(&out_rig)
        .args(["--max-muscles", "1"])
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&out.stderr);
    assert_eq!(out.status.code(), Some(1), "{err}");
    assert!(err.contains("line 7: more than 1 muscles"), "{err}");
    assert!(!out_rig.exists());
}

fn mediapipe() -> PathBuf {
    Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."))
        .join("assets/mediapipe_canonical_4loop.obj")
}

/// The MediaPipe face's lines with a `vt` and a `vn` per `v` (after the `v` lines) and every
/// corner `i/i/i`, then `edit` applied.
fn textured_mediapipe(edit: impl FnOnce(&mut Vec<String>)) -> String {
    let text = std::fs::read_to_string(mediapipe()).unwrap();
    let n = text.lines().filter(|l| l.starts_with("v ")).count();
    let mut lines: Vec<String> = Vec::new();
    for l in text.lines() {
        if let Some(corners) = l.strip_prefix("f ") {
            let c: Vec<String> = corners
                .split_whitespace()
                .map(|i| format!("{i}/{i}/{i}"))
                .collect();
            lines.push(format!("f {}", c.join(" ")));
            continue;
        }
        lines.push(l.to_owned());
    }
    let after_v = lines.iter().rposition(|l| l.starts_with("v ")).unwrap() + 1;
    let extra = (0..n)
        .map(|i| format!("vt {} 0.5", i as f64 / n as f64))
        .chain((0..n).map(|_| "vn 0 0 1".to_owned()));
    lines.splice(after_v..after_v, extra);
    edit(&mut lines);
    lines.join("\n") + "\n"
}

/// Runs `facebem` with `args` in `dir`; returns the exit code and stderr.
fn facebem(dir: &Path, args: &[&str]) -> (Option<i32>, String) {
    let out = Command::new(env!("CARGO_BIN_EXE_facebem"))
        .current_dir(dir)
        .args(args)
        .output()
        .unwrap();
    (
        out.status.code(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

/// Asserts exit 1 with one line `error: …` containing `needle`, and that `dir` holds nothing
/// but `inputs`.
fn assert_refused(dir: &Path, args: &[&str], needle: &str, inputs: usize) {
    let (code, err) = facebem(dir, args);
    assert_eq!(code, Some(1), "{args:?}: {err}");
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 1, "{args:?}: {err}");
    assert!(
        lines[0].starts_with("error: ") && lines[0].contains(needle),
        "{args:?}: {err}"
    );
    assert_eq!(
        listing(dir).len(),
        inputs,
        "{args:?} wrote {:?}",
        listing(dir)
    );
}

/// Writes `text` as `name` in a new temp dir; `info` and `rig` on it must both fail with
/// `needle` and write nothing.
fn assert_face_refused(name: &str, text: &str, needle: &str) {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join(name), text).unwrap();
    assert_refused(dir.path(), &["info", name], needle, 1);
    assert_refused(dir.path(), &["rig", name, "-o", "out.rig"], needle, 1);
}

#[test]
fn cli_textured_face_is_accepted() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(dir.path().join("face.obj"), textured_mediapipe(|_| {})).unwrap();
    let (code, err) = facebem(dir.path(), &["info", "face.obj"]);
    assert_eq!(code, Some(0), "{err}");
}

#[test]
fn cli_refuses_obj_with_nan_texture_coordinate() {
    let text = textured_mediapipe(|lines| {
        let i = lines.iter().position(|l| l.starts_with("vt ")).unwrap() + 10;
        lines[i] = "vt nan nan".to_owned();
    });
    let line = text.lines().position(|l| l == "vt nan nan").unwrap() + 1;
    let needle =
        format!("face.obj: OBJ line {line}: \"vt nan nan\" holds a number that is not finite");
    assert_face_refused("face.obj", &text, &needle);
}

#[test]
fn cli_refuses_obj_with_infinite_normal() {
    let text = textured_mediapipe(|lines| {
        let i = lines.iter().position(|l| l.starts_with("vn ")).unwrap() + 3;
        lines[i] = "vn inf 0 1".to_owned();
    });
    let line = text.lines().position(|l| l == "vn inf 0 1").unwrap() + 1;
    let needle = format!("OBJ line {line}: \"vn inf 0 1\" holds a number that is not finite");
    assert_face_refused("face.obj", &text, &needle);
}

#[test]
fn cli_refuses_obj_with_non_finite_or_zero_w() {
    let text = std::fs::read_to_string(mediapipe()).unwrap();
    // Line 9 is the 6th `v` line.
    let with_w = |w: &str| {
        let mut lines: Vec<String> = text.lines().map(str::to_owned).collect();
        lines[8] = format!("{} {w}", lines[8]);
        lines.join("\n") + "\n"
    };
    assert_face_refused(
        "face.obj",
        &with_w("inf"),
        "OBJ line 9: \"v 0.000000 0.365669 7.242870 inf\" holds a number that is not finite",
    );
    assert_face_refused(
        "face.obj",
        &with_w("0"),
        "OBJ line 9: \"v 0.000000 0.365669 7.242870 0\" has w = 0",
    );
}

#[test]
fn cli_refuses_gltf_with_nan_texture_coordinate() {
    // The corpus file: a triangle whose TEXCOORD_0 (accessor 2) has a NaN in element 1.
    let dir = tempfile::tempdir().unwrap();
    std::fs::copy(
        corpus().join("gltf_texcoord_nan.gltf"),
        dir.path().join("face.gltf"),
    )
    .unwrap();
    let needle = "face.gltf: glTF error: accessor 2 (TEXCOORD_0): element 1 is not finite";
    assert_refused(dir.path(), &["info", "face.gltf"], needle, 1);
    assert_refused(
        dir.path(),
        &["rig", "face.gltf", "-o", "out.rig"],
        needle,
        1,
    );
}

#[test]
fn cli_refuses_obj_vertex_defined_after_its_face() {
    // The last `v` line (v 468) moved to the end: the faces using it come before it.
    let text = std::fs::read_to_string(mediapipe()).unwrap();
    let mut lines: Vec<&str> = text.lines().collect();
    let last_v = lines.iter().rposition(|l| l.starts_with("v ")).unwrap();
    let v = lines.remove(last_v);
    lines.push(v);
    let first_use = lines
        .iter()
        .position(|l| l.starts_with("f ") && l.split_whitespace().any(|c| c == "468"))
        .unwrap()
        + 1;
    let needle = format!(
        "OBJ line {first_use}: face corner \"468\" refers to a `v` line that does not come before \
         the face (there are 467 above it)"
    );
    assert_face_refused("face.obj", &(lines.join("\n") + "\n"), &needle);
}

#[test]
fn cli_refuses_muscle_file_with_duplicate_names() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("dup.muscles"),
        "[Name]\nfrontalis_l\n[Size]\n1\n[Data]\n0\n[Name]\nm\n[Size]\n1\n[Data]\n1\n\
         [Name]\nFrontalis L\n[Size]\n1\n[Data]\n2\n",
    )
    .unwrap();
    let face = mediapipe();
    let args = [
        "rig",
        face.to_str().unwrap(),
        "--muscles",
        "dup.muscles",
        "-o",
        "out.rig",
    ];
    let needle = "muscle file dup.muscles: line 14: muscle \"Frontalis L\" has the same name as the \
                  muscle at line 2 (both are \"frontalis_l\"); muscle names must be unique";
    assert_refused(dir.path(), &args, needle, 1);
}

#[test]
fn cli_reads_muscle_file_with_utf8_bom_and_exports_it() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("bom.muscles"),
        "\u{feff}[Name]\r\nm0\r\n[Size]\r\n1\r\n[Data]\r\n0\r\n[Name]\r\nm1\r\n[Size]\r\n1\r\n[Data]\r\n1\r\n",
    )
    .unwrap();
    let face = mediapipe();
    let (code, err) = facebem(
        dir.path(),
        &[
            "rig",
            face.to_str().unwrap(),
            "--muscles",
            "bom.muscles",
            "-o",
            "bom.rig",
        ],
    );
    assert_eq!(code, Some(0), "{err}");
    // What is accepted exports: a pose moving the muscle named on the BOM's line, and glTF.
    let (code, err) = facebem(
        dir.path(),
        &["pose", "bom.rig", "--set", "m0=-1", "-o", "pose.obj"],
    );
    assert_eq!(code, Some(0), "{err}");
    let (code, err) = facebem(dir.path(), &["export", "bom.rig", "--gltf", "bom.glb"]);
    assert_eq!(code, Some(0), "{err}");
    assert!(dir.path().join("pose.obj").is_file() && dir.path().join("bom.glb").is_file());
}
