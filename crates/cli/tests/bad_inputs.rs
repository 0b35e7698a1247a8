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
