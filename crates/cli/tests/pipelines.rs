//! The command line in pipelines (issue 34, item 6): `--json` reports of `rig`, `info` and
//! `export` that parse and name what was written; the rig cache shared with the viewer (a
//! face mesh's second export loads its rig instead of solving again; `--no-cache`); shell
//! completions. Each test has its own cache folder (`XDG_CACHE_HOME`).

#[path = "../../../tests/support/mod.rs"]
mod support;

use std::path::Path;
use std::process::{Command, Output};

fn facebem(cache: &Path, args: &[&str]) -> Output {
    let out = Command::new(env!("CARGO_BIN_EXE_facebem"))
        .args(args)
        .env("XDG_CACHE_HOME", cache)
        .output()
        .expect("run facebem");
    assert!(
        out.status.success(),
        "facebem {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

/// The single JSON object `--json` prints.
fn json_of(out: &Output) -> serde_json::Value {
    let text = String::from_utf8_lossy(&out.stdout);
    assert_eq!(
        text.trim_end().lines().count(),
        1,
        "one line of JSON: {text}"
    );
    serde_json::from_str(&text).unwrap_or_else(|e| panic!("{e}: {text}"))
}

#[test]
fn a_second_export_of_a_face_mesh_reuses_the_rig_cache() {
    let dir = tempfile::tempdir().unwrap();
    let cache = dir.path().join("cache");
    let face = support::asset(support::FACES[0]);
    let face = face.to_str().unwrap();
    let glb = |n: &str| dir.path().join(n).to_str().unwrap().to_string();
    let (a, b, c) = (glb("a.glb"), glb("b.glb"), glb("c.glb"));

    let first = json_of(&facebem(&cache, &["export", face, "--gltf", &a, "--json"]));
    assert_eq!(first["rigSource"]["from"], "computed", "{first}");
    let cached = first["rigSource"]["cacheFile"]
        .as_str()
        .unwrap()
        .to_string();
    assert!(
        Path::new(&cached).starts_with(cache.join("facebem")),
        "{cached}"
    );
    assert!(Path::new(&cached).is_file());

    let second = json_of(&facebem(&cache, &["export", face, "--gltf", &b, "--json"]));
    assert_eq!(second["rigSource"]["from"], "cache", "{second}");
    assert_eq!(second["rigSource"]["cacheFile"], cached.as_str());
    println!(
        "export of the default face: {:.2} s computing its rig, {:.3} s with the cached rig",
        first["seconds"]["total"], second["seconds"]["total"]
    );
    // The same file either way.
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&b).unwrap());

    // --no-cache: computed again, not saved.
    let third = json_of(&facebem(
        &cache,
        &["export", face, "--gltf", &c, "--json", "--no-cache"],
    ));
    assert_eq!(third["rigSource"]["from"], "computed");
    assert!(third["rigSource"]["cacheFile"].is_null());
    assert_eq!(std::fs::read(&a).unwrap(), std::fs::read(&c).unwrap());

    // A different rig option is another cache entry.
    let thesis = json_of(&facebem(
        &cache,
        &[
            "export",
            face,
            "--gltf",
            &c,
            "--json",
            "--muscle-model",
            "thesis",
        ],
    ));
    assert_eq!(thesis["rigSource"]["from"], "computed");
    assert_ne!(thesis["rigSource"]["cacheFile"], cached.as_str());

    // The text report says where the rig came from.
    let text = facebem(&cache, &["export", face, "--gltf", &b]);
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(text.contains("rig loaded from the cache"), "{text}");
}

#[test]
fn json_reports_parse_and_name_what_was_written() {
    let dir = tempfile::tempdir().unwrap();
    let cache = dir.path().join("cache");
    let face_path = support::asset(support::FACES[0]);
    let face = face_path.to_str().unwrap();
    let rig = dir.path().join("d.rig");
    let rig_s = rig.to_str().unwrap();

    let r = json_of(&facebem(&cache, &["rig", face, "-o", rig_s, "--json"]));
    let (mesh, _) = facebem::input::read_face(&face_path).unwrap();
    assert_eq!(r["command"], "rig");
    assert_eq!(r["output"], rig_s);
    assert_eq!(r["frontTriangles"], mesh.triangles.len());
    assert_eq!(
        r["controls"].as_array().unwrap().len(),
        face_prep::MuscleKind::ALL.len(),
        "{r}"
    );
    assert_eq!(r["untrustworthy"], serde_json::json!([]));
    assert!(r["seconds"]["solve"].as_f64().unwrap() > 0.0);
    assert_eq!(r["unit"], "cm");

    let glb = dir.path().join("f.glb");
    let e = json_of(&facebem(
        &cache,
        &["export", rig_s, "--gltf", glb.to_str().unwrap(), "--json"],
    ));
    assert_eq!(e["rigSource"]["from"], "rig file");
    assert_eq!(e["bytes"], std::fs::metadata(&glb).unwrap().len());
    let targets: Vec<String> = e["targets"]
        .as_array()
        .unwrap()
        .iter()
        .map(|t| t.as_str().unwrap().to_string())
        .collect();
    assert_eq!(targets, support::glb_target_names(&glb));
    assert!(targets.iter().any(|t| t == "mouthSmileLeft"));
    assert_eq!(
        e["sameAs"],
        serde_json::json!([
            ["blinkLeft", "eyeBlinkLeft"],
            ["blinkRight", "eyeBlinkRight"]
        ])
    );
    let left_out = e["leftOut"].as_array().unwrap();
    assert!(left_out.iter().any(|p| p[0] == "tongueOut"), "{e}");

    for (file, kind) in [(rig_s, "rig file"), (face, "face mesh")] {
        let i = json_of(&facebem(&cache, &["info", file, "--json"]));
        assert_eq!(i["kind"], kind);
        assert_eq!(i["triangles"], mesh.triangles.len());
        assert_eq!(i["unit"], "cm");
        let names = i["names"].as_array().unwrap();
        assert!(names.iter().any(|n| n == "jawOpen"), "{i}");
        let not_modelled = i["notModelled"].as_array().unwrap();
        assert!(not_modelled.iter().any(|n| n[0] == "eyeLookUpLeft"), "{i}");
        assert_eq!(i["rig"].is_object(), kind == "rig file");
    }
}

#[test]
fn completions_for_each_shell() {
    let dir = tempfile::tempdir().unwrap();
    for shell in ["bash", "zsh", "fish", "elvish", "powershell"] {
        let out = facebem(dir.path(), &["completions", shell]);
        let text = String::from_utf8_lossy(&out.stdout);
        for word in ["export", "naming", "compress", "no-cache", "json"] {
            assert!(text.contains(word), "{shell} completion lacks {word}");
        }
    }
    let bad = Command::new(env!("CARGO_BIN_EXE_facebem"))
        .args(["completions", "tcsh"])
        .output()
        .unwrap();
    assert_eq!(bad.status.code(), Some(2));
}
