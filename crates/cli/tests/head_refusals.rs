//! Files that are not a head a face can be taken from (issue 32's bad inputs): each refused by
//! `facebem export` with one line that says why, and nothing written. Built here from
//! ICT-FaceKit's generic head (`assets/heads/`).

use std::path::{Path, PathBuf};
use std::process::Command;

fn head_text() -> String {
    std::fs::read_to_string(Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/heads/ict_generic_head.obj"
    )))
    .unwrap()
}

/// Writes `text` as `name` in `dir`, exports it and returns (stderr, whether the output exists).
fn export(dir: &Path, name: &str, text: &str) -> (String, bool) {
    let input = dir.join(name);
    std::fs::write(&input, text).unwrap();
    let out: PathBuf = dir.join("out.glb");
    let run = Command::new(env!("CARGO_BIN_EXE_facebem"))
        .arg("export")
        .arg(&input)
        .arg("--gltf")
        .arg(&out)
        .env("XDG_CACHE_HOME", dir)
        .output()
        .unwrap();
    assert!(!run.status.success(), "{name} was taken");
    let err = String::from_utf8_lossy(&run.stderr).trim().to_string();
    assert_eq!(err.lines().count(), 1, "{name}: {err}");
    (err, out.exists())
}

/// The head's `v` lines moved by `dx` and its `f` lines renumbered by `offset`.
fn shifted(text: &str, dx: f64, offset: usize) -> String {
    text.lines()
        .filter_map(|l| {
            let mut w = l.split_whitespace();
            match w.next() {
                Some("v") => {
                    let c: Vec<f64> = w.map(|x| x.parse().unwrap()).collect();
                    Some(format!("v {} {} {}\n", c[0] + dx, c[1], c[2]))
                }
                Some("f") => Some(format!(
                    "f {}\n",
                    w.map(|c| {
                        let v: usize = c.split('/').next().unwrap().parse().unwrap();
                        (v + offset).to_string()
                    })
                    .collect::<Vec<_>>()
                    .join(" ")
                )),
                _ => None,
            }
        })
        .collect()
}

#[test]
fn a_head_without_eyeballs_is_refused_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let mut skip = false;
    let text: String = head_text()
        .lines()
        .filter(|l| {
            if l.starts_with("usemtl") {
                skip = l.contains("Iris") || l.contains("Sclera");
            }
            !(skip && l.starts_with("f "))
        })
        .map(|l| format!("{l}\n"))
        .collect();
    let (err, written) = export(dir.path(), "noeyes.obj", &text);
    assert!(err.contains("no eyeballs among them"), "{err}");
    assert!(!written);
}

#[test]
fn two_heads_are_refused_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let one = shifted(&head_text(), 0.0, 0);
    let two = format!("{one}{}", shifted(&head_text(), 40.0, 26_719));
    let (err, written) = export(dir.path(), "two.obj", &two);
    assert!(err.contains("two heads or two faces"), "{err}");
    assert!(!written);
}

#[test]
fn a_part_of_a_million_triangles_is_refused_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    let mut text = shifted(&head_text(), 0.0, 0);
    // A sphere of 1000 × 500 quads (a million triangles) above the head.
    let (nu, nv) = (1000usize, 500usize);
    let first = 26_719 + 1;
    for j in 0..=nv {
        let t = std::f64::consts::PI * j as f64 / nv as f64;
        for i in 0..nu {
            let p = std::f64::consts::TAU * i as f64 / nu as f64;
            text += &format!(
                "v {:.5} {:.5} {:.5}\n",
                5.0 * t.sin() * p.cos(),
                40.0 + 5.0 * t.cos(),
                5.0 * t.sin() * p.sin()
            );
        }
    }
    for j in 0..nv {
        for i in 0..nu {
            let a = first + j * nu + i;
            let b = first + j * nu + (i + 1) % nu;
            text += &format!("f {a} {b} {}\nf {b} {} {}\n", a + nu, b + nu, a + nu);
        }
    }
    let (err, written) = export(dir.path(), "hat.obj", &text);
    assert!(err.contains("a part of 1000000 triangles"), "{err}");
    assert!(!written);
}
