//! A whole head (issue 32): `facebem info` lists the parts it finds in ICT-FaceKit's generic
//! head (`assets/heads/`); `facebem export` writes it back with the morph targets on every part
//! (its front face rigged, the rig carried to the rest); `pose` poses it whole; `sheet` draws
//! it whole; `rig` refuses it with one line that says why, writing nothing.

use std::path::{Path, PathBuf};
use std::process::Command;

#[path = "../../../tests/support/gltf_targets.rs"]
mod gltf_targets;
#[path = "../../../tests/support/mod.rs"]
mod support;

fn head() -> PathBuf {
    Path::new(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/../../assets/heads/ict_generic_head.obj"
    ))
    .to_path_buf()
}

fn facebem(args: &[&str], cache: &Path) -> std::process::Output {
    Command::new(env!("CARGO_BIN_EXE_facebem"))
        .args(args)
        .env("XDG_CACHE_HOME", cache)
        .output()
        .unwrap()
}

#[test]
fn info_lists_the_parts_of_a_head_and_every_command_refuses_it_in_one_line() {
    let out = tempfile::tempdir().unwrap();
    let head = head();
    let head = head.to_str().unwrap();
    let info = facebem(&["info", head], out.path());
    assert_eq!(info.status.code(), Some(1));
    let stdout = String::from_utf8_lossy(&info.stdout);
    for line in [
        "skin: 1 component, 14062 vertices",
        "eyeball (subject's left): 2 components, 1570 vertices",
        "eyeball (subject's right): 2 components, 1570 vertices",
        "upper teeth: 16 components",
        "lower teeth: 16 components",
        "gums and tongue: 1 component, 2977 vertices",
        "lid parts (lashes, occlusion, tear film)",
        "front face cut from the skin: ",
        "triangles, 4 openings",
    ] {
        assert!(stdout.contains(line), "{line:?} missing from:\n{stdout}");
    }
    assert!(!stdout.contains("other"), "{stdout}");
    let rig = out.path().join("head.rig");
    for args in [
        vec!["info", head],
        vec!["rig", head, "-o", rig.to_str().unwrap()],
    ] {
        let run = facebem(&args, out.path());
        assert_eq!(run.status.code(), Some(1), "{args:?}");
        let stderr = String::from_utf8_lossy(&run.stderr);
        assert_eq!(stderr.lines().count(), 1, "{stderr}");
        assert!(stderr.contains("a head or avatar of 42 parts"), "{stderr}");
    }
    assert!(!rig.exists());
    // The same in JSON: every component with its part, and every vertex in one.
    let json = facebem(&["info", "--json", head], out.path());
    let report: serde_json::Value = serde_json::from_slice(&json.stdout).unwrap();
    let components = report["components"].as_array().unwrap();
    assert_eq!(components.len(), 42);
    let vertices: u64 = components
        .iter()
        .map(|c| c["vertices"].as_u64().unwrap())
        .sum();
    assert_eq!(vertices, 26_719);
    let teeth = components
        .iter()
        .filter(|c| c["part"].as_str().unwrap().ends_with("teeth"))
        .count();
    assert_eq!(teeth, 32);
}

/// Skin vertices (OBJ `v` lines 0–14 061 of ICT's head) and the part ranges (assets/heads).
const SKIN: std::ops::Range<usize> = 0..14_062;
const UPPER_TEETH: std::ops::RangeInclusive<usize> = 17_039..=19_246;
const LOWER_TEETH: std::ops::RangeInclusive<usize> = 19_247..=21_450;
const EYEBALLS: std::ops::RangeInclusive<usize> = 21_451..=24_590;

#[test]
fn a_head_exports_with_the_targets_on_every_part() {
    let out = tempfile::tempdir().unwrap();
    let glb = out.path().join("head.glb");
    let run = facebem(
        &[
            "export",
            head().to_str().unwrap(),
            "--gltf",
            glb.to_str().unwrap(),
        ],
        out.path(),
    );
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    support::assert_valid(&glb);
    // One mesh per part, each with its OBJ materials and every target.
    let (json, _) = {
        let bytes = std::fs::read(&glb).unwrap();
        let (j, b) = face_prep::gltf_read::split_glb(&bytes).unwrap();
        (
            serde_json::from_slice::<serde_json::Value>(j).unwrap(),
            b.map(<[u8]>::len),
        )
    };
    let meshes: Vec<(String, Vec<String>)> = json["meshes"]
        .as_array()
        .unwrap()
        .iter()
        .map(|m| {
            let materials = m["primitives"].as_array().unwrap().iter().map(|p| {
                json["materials"][p["material"].as_u64().unwrap() as usize]["name"]
                    .as_str()
                    .unwrap()
                    .to_string()
            });
            (m["name"].as_str().unwrap().to_string(), materials.collect())
        })
        .collect();
    let expected = [
        ("skin", vec!["M_Face", "M_BackHead"]),
        ("eyeball_left", vec!["M_ScleraLeft", "M_IrisLeft"]),
        ("eyeball_right", vec!["M_ScleraRight", "M_IrisRight"]),
        ("upper_teeth", vec!["M_Teeth"]),
        ("lower_teeth", vec!["M_Teeth"]),
        ("gums_and_tongue", vec!["M_GumsTongue"]),
        (
            "lid_parts",
            vec![
                "M_LacrimalFluid",
                "M_EyeBlend",
                "M_EyeOcclusion",
                "M_EyeLashes",
            ],
        ),
    ];
    assert_eq!(meshes.len(), expected.len(), "{meshes:?}");
    for ((name, materials), (want, want_materials)) in meshes.iter().zip(&expected) {
        assert_eq!(name, want);
        assert_eq!(materials, want_materials, "{name}");
    }
    for m in json["meshes"].as_array().unwrap() {
        assert_eq!(
            m["extras"]["targetNames"],
            json["meshes"][0]["extras"]["targetNames"]
        );
    }
    let targets = gltf_targets::read(&glb);
    let v = support::obj_v_lines(&head());
    assert_eq!(v.len(), 26_719);
    for name in [
        "jawOpen",
        "mouthSmileLeft",
        "eyeBlinkRight",
        "browInnerUp",
        "aa",
    ] {
        assert!(targets.positions.contains_key(name), "{name}");
    }
    let mm = |d: [f32; 3]| 1000.0 * (d[0].powi(2) + d[1].powi(2) + d[2].powi(2)).sqrt();
    // The back of the head (more than 1.5 interocular distances, 9.3 cm, behind the eyes'
    // centres at z = 8) stays within 1 mm in every target; upper teeth and eyeballs stay.
    let mut back = 0.0f32;
    for (name, field) in &targets.positions {
        for i in SKIN.filter(|&i| v[i][2] < 8.0 - 9.3) {
            back = back.max(mm(field[i]));
        }
        for i in UPPER_TEETH {
            assert_eq!(field[i], [0.0; 3], "{name}: vertex {i}");
        }
        // The eyeballs turn in the gaze targets only (tests/head_gaze_tongue.rs).
        if !name.starts_with("eyeLook") && !name.starts_with("look") {
            for i in EYEBALLS {
                assert_eq!(field[i], [0.0; 3], "{name}: vertex {i}");
            }
        }
    }
    assert!(back < 1.0, "the back of the head moves {back} mm");
    // jawOpen turns the lower teeth as one body with the mandible: pairwise distances kept to
    // 0.05 mm, the incisors' tips lowered by more than 5 mm; a smile leaves them.
    let open = &targets.positions["jawOpen"];
    let lower: Vec<usize> = LOWER_TEETH.step_by(37).collect();
    let at = |i: usize, d: [f32; 3]| [0, 1, 2].map(|k| v[i][k] / 100.0 + f64::from(d[k]));
    for &a in &lower {
        for &b in &lower {
            let (p, q) = (at(a, [0.0; 3]), at(b, [0.0; 3]));
            let (pp, qq) = (at(a, open[a]), at(b, open[b]));
            let dist = |x: [f64; 3], y: [f64; 3]| {
                ((x[0] - y[0]).powi(2) + (x[1] - y[1]).powi(2) + (x[2] - y[2]).powi(2)).sqrt()
            };
            assert!((dist(p, q) - dist(pp, qq)).abs() < 5e-5, "{a} {b}");
        }
    }
    let lowest_drop = LOWER_TEETH
        .map(|i| -open[i][1])
        .fold(f32::INFINITY, f32::min);
    assert!(
        lowest_drop * 1000.0 > 5.0,
        "lower teeth lowered by {lowest_drop} m at least"
    );
    let smile = &targets.positions["mouthSmileLeft"];
    assert!(LOWER_TEETH.clone().all(|i| smile[i] == [0.0; 3]));
    seam_is_no_steeper_than_the_face(&targets, &v);
}

/// Along the border of the simulated front face, the displacement of the skin just outside
/// differs from its neighbour's inside by no more than neighbours inside the face differ near
/// the border (no seam where the simulated region ends).
fn seam_is_no_steeper_than_the_face(targets: &gltf_targets::Targets, v: &[[f64; 3]]) {
    let scene = face_prep::parts::Scene::read(&head(), &Default::default()).unwrap();
    let parts = face_prep::parts::find_parts(&scene).unwrap();
    let front = face_prep::parts::front_face(&scene, &parts).unwrap();
    let mut inside = vec![false; v.len()];
    for &s in &front.scene_vertex {
        inside[s as usize] = true;
    }
    let near_border: Vec<bool> = {
        let mut near = vec![false; v.len()];
        for t in scene
            .triangles
            .iter()
            .filter(|t| t.iter().all(|&i| SKIN.contains(&(i as usize))))
        {
            if t.iter().any(|&i| inside[i as usize]) && t.iter().any(|&i| !inside[i as usize]) {
                t.iter().for_each(|&i| near[i as usize] = true);
            }
        }
        near
    };
    let (mut seam, mut face) = (0.0f32, 0.0f32);
    for field in targets.positions.values() {
        for t in scene
            .triangles
            .iter()
            .filter(|t| t.iter().all(|&i| SKIN.contains(&(i as usize))))
        {
            for (a, b) in [(t[0], t[1]), (t[1], t[2]), (t[2], t[0])] {
                let (a, b) = (a as usize, b as usize);
                let d = [0, 1, 2].map(|k| field[a][k] - field[b][k]);
                let step = 1000.0 * (d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
                // The outline only: the openings' linings lie inside the mouth and the
                // sockets, more than 5 cm from the eyes' midpoint and the mouth's corners.
                let outline = [a, b].iter().all(|&i| far_from_features(v[i]));
                if inside[a] != inside[b] && outline {
                    seam = seam.max(step);
                } else if inside[a] && inside[b] && near_border[a] && near_border[b] && outline {
                    face = face.max(step);
                }
            }
        }
    }
    eprintln!("largest step across the outline {seam} mm, between face vertices at it {face} mm");
    // The rig itself has steps of ~10 mm between neighbours under the chin in the jaw's
    // targets; the seam is no steeper than the face there, within the 0.5 mm.
    assert!(seam <= face + 0.5, "seam {seam} mm, face {face} mm");
}

/// More than 5 cm from the eyes' midpoint (0, 3.6, 8) and from the mouth's centre (0, −3.1, 9.6).
fn far_from_features(p: [f64; 3]) -> bool {
    let d = |c: [f64; 3]| {
        ((p[0] - c[0]).powi(2) + (p[1] - c[1]).powi(2) + (p[2] - c[2]).powi(2)).sqrt()
    };
    d([0.0, 3.6, 8.0]) > 5.0 && d([0.0, -3.1, 9.6]) > 5.0
}

/// The `v` lines of an OBJ text, as points.
fn obj_points(text: &str) -> Vec<[f64; 3]> {
    text.lines()
        .filter(|l| l.starts_with("v "))
        .map(|l| {
            let p: Vec<f64> = l
                .split_whitespace()
                .skip(1)
                .map(|w| w.parse().unwrap())
                .collect();
            [p[0], p[1], p[2]]
        })
        .collect()
}

/// `facebem pose` of a head poses every part, in the user's own OBJ: only `v` lines change.
/// The head's own targets are names like any other (`eyeLookUpLeft` turns the left eyeball),
/// sliders go on top of a name (jawOpen plus the left zygomaticus), and an unknown name is one
/// line with nothing written.
#[test]
fn a_head_poses_whole_in_its_own_layout() {
    let out = tempfile::tempdir().unwrap();
    let head = head();
    let input = std::fs::read_to_string(&head).unwrap();
    let rest = obj_points(&input);
    let pose = |name: &str, extra: &[&str]| {
        let file = out.path().join(format!("{name}.obj"));
        let mut args = vec!["pose", head.to_str().unwrap(), "--preset", name];
        args.extend(extra);
        args.extend(["-o", file.to_str().unwrap()]);
        let run = facebem(&args, out.path());
        (run, file)
    };
    let moved = |posed: &[[f64; 3]], range: std::ops::RangeInclusive<usize>| {
        range
            .map(|v| {
                let d: f64 = (0..3).map(|k| (posed[v][k] - rest[v][k]).powi(2)).sum();
                d.sqrt()
            })
            .fold(0.0, f64::max)
    };
    let (run, file) = pose("eyeLookUpLeft", &[]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let text = std::fs::read_to_string(&file).unwrap();
    let other = |t: &str| -> Vec<String> {
        t.lines()
            .filter(|l| !l.starts_with("v "))
            .map(str::to_owned)
            .collect()
    };
    assert_eq!(other(&text), other(&input), "only the v lines change");
    let up = obj_points(&text);
    assert_eq!(up.len(), rest.len());
    // Left eyeball first in ICT's order (21 451–23 020); cm.
    assert!(moved(&up, 21_451..=23_020) > 0.2, "the left eyeball turns");
    assert!(moved(&up, 23_021..=24_590) < 1e-9, "the right one does not");
    assert!(moved(&up, LOWER_TEETH) < 1e-9);

    let (run, file) = pose("jawOpen", &["--set", "zygomaticus_major_l=-1"]);
    assert!(
        run.status.success(),
        "{}",
        String::from_utf8_lossy(&run.stderr)
    );
    let open = obj_points(&std::fs::read_to_string(&file).unwrap());
    assert!(
        moved(&open, LOWER_TEETH) > 0.5,
        "the lower teeth go down with the jaw"
    );
    assert!(moved(&open, UPPER_TEETH) < 1e-9);

    let (run, file) = pose("noSuchFace", &[]);
    assert_eq!(run.status.code(), Some(1));
    let stderr = String::from_utf8_lossy(&run.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("unknown preset"), "{stderr}");
    assert!(!file.exists());
}

/// `sheet` draws a whole head (issue 32): its front face rigged and carried to every part, the
/// ARKit page with all 52 names in ARKit's order (the 43 the controls make, the eight gaze
/// targets and `tongueOut`), each with heat where it moves: at least 200 heat-coloured pixels
/// in the front panel of the jaw, the gaze and the tongue.
#[test]
fn a_head_draws_its_contact_sheet() {
    use facebem::report::contact_sheet::{self, SheetOptions, heat};
    let out = tempfile::tempdir().unwrap();
    let head = head();
    let png_path = out.path().join("head_arkit.png");
    let run = facebem(
        &[
            "sheet",
            head.to_str().unwrap(),
            "-o",
            png_path.to_str().unwrap(),
            "--only",
            "arkit",
        ],
        out.path(),
    );
    let stdout = String::from_utf8_lossy(&run.stdout);
    assert!(
        run.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&run.stderr)
    );
    assert!(stdout.contains("52 cells"), "{stdout}");
    assert!(!stdout.contains("left out"), "{stdout}");
    let decoder = png::Decoder::new(std::io::BufReader::new(
        std::fs::File::open(&png_path).unwrap(),
    ));
    let mut reader = decoder.read_info().unwrap();
    let mut pixels = vec![0; reader.output_buffer_size().unwrap()];
    let frame = reader.next_frame(&mut pixels).unwrap();
    assert_eq!(frame.color_type, png::ColorType::Rgb);
    let layout = contact_sheet::layout(52, &SheetOptions::default());
    assert_eq!((frame.width, frame.height), (layout.width, layout.height));
    let names = facebem::expressions::arkit::NAMES;
    for name in ["jawOpen", "eyeLookUpLeft", "eyeLookInRight", "tongueOut"] {
        let cell = names.iter().position(|n| *n == name).unwrap();
        let r = layout.panel(cell, 0);
        let mut hot = 0;
        for y in r.y + 14..r.y + r.h {
            for x in r.x..r.x + r.w {
                let i = 3 * (y as usize * frame.width as usize + x as usize);
                if heat::classify([pixels[i], pixels[i + 1], pixels[i + 2]]).is_some() {
                    hot += 1;
                }
            }
        }
        assert!(hot >= 200, "{name}: {hot} heat-coloured pixels");
    }
}
