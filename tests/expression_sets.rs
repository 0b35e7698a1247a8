//! ARKit- and VRM-named expressions on real faces: the GLB holds exactly the names the rig's
//! controls can make (first, in the standards' order, validator clean), each target is its
//! slider combination, the left-out names are listed with the reason, and "Left" is the
//! subject's own left (+x in the canonical frame) as ARKit and VRM define it.
//!
//! The expected counts follow from which controls the rig has, so they tighten by themselves as
//! jaw, eyelid and further muscle controls land; with every agreed control the GLB must hold 43
//! ARKit and 14 VRM names (the target).

mod support;

use std::sync::OnceLock;

use facebem::expressions::{self, AGREED_CONTROL_IDS, NameSet, NameSets, arkit, vrm};
use facebem::report::measure::{FaceLandmarks, cosine};
use facebem::{Control, FaceModel, PipelineParams, build_face_model};
use glam::DVec3;

static MODELS: [OnceLock<FaceModel>; 4] = [const { OnceLock::new() }; 4];

/// The model of bundled face `face` ([`support::FACES`]), with its OBJ layout.
fn model(face: usize) -> &'static FaceModel {
    MODELS[face].get_or_init(|| {
        let (mesh, obj) = facebem::input::read_face(&support::asset(support::FACES[face])).unwrap();
        let mut m = build_face_model(&mesh, &PipelineParams::default(), &Control::new()).unwrap();
        m.obj_source = obj;
        m
    })
}

/// Whether the rig has at least one control of `e` (or `e` needs none).
fn makeable(e: &expressions::NamedExpression, ids: &[String]) -> bool {
    let controls = e.controls();
    controls.is_empty() || controls.iter().any(|c| ids.iter().any(|i| i == c))
}

fn extras(doc: &gltf::Document) -> serde_json::Value {
    let mesh = doc.meshes().next().unwrap();
    serde_json::from_str(mesh.extras().as_ref().unwrap().get()).unwrap()
}

/// Names left out of a file as repeats of a written target (`sameAs`, `negativeOf`) or as all
/// zero (`leftOutTargets`).
fn repeats(x: &serde_json::Value) -> Vec<String> {
    let mut out: Vec<String> = ["sameAs", "negativeOf"]
        .iter()
        .flat_map(|k| x[*k].as_object().into_iter().flatten())
        .map(|(n, _)| n.clone())
        .collect();
    for (n, why) in x["leftOutTargets"].as_object().into_iter().flatten() {
        if why.as_str().unwrap().starts_with("all zero") {
            out.push(n.clone());
        }
    }
    out
}

#[test]
fn glb_holds_the_arkit_and_vrm_names_the_rig_can_make_first() {
    let m = model(0);
    let ids = m.muscle_ids();
    let dir = tempfile::tempdir().unwrap();
    let glb = dir.path().join("face.glb");
    let params = facebem::export::GltfParams {
        names: NameSets::ALL,
        ..Default::default()
    };
    m.write_gltf(&glb, &params).unwrap();
    support::assert_valid(&glb);
    let (doc, buffers, _) = gltf::import(&glb).unwrap();
    let x = extras(&doc);
    let repeated = repeats(&x);
    let names: Vec<&str> = x["targetNames"]
        .as_array()
        .unwrap()
        .iter()
        .map(|n| n.as_str().unwrap())
        .collect();

    // Expected, from the tables and the rig's controls alone.
    // (every ARKit name is written; a VRM one that repeats another is left out, and said).
    let expect_arkit: Vec<&str> = arkit::EXPRESSIONS
        .iter()
        .filter(|e| makeable(e, ids))
        .map(|e| e.name)
        .collect();
    let expect_vrm: Vec<&str> = vrm::EXPRESSIONS
        .iter()
        .filter(|e| makeable(e, ids) && !repeated.iter().any(|r| r == e.name))
        .map(|e| e.name)
        .collect();
    let got_arkit: Vec<&str> = names
        .iter()
        .copied()
        .filter(|n| arkit::NAMES.contains(n))
        .collect();
    let got_vrm: Vec<&str> = names
        .iter()
        .copied()
        .filter(|n| vrm::NAMES.contains(n))
        .collect();
    println!(
        "{}: {} ARKit-named and {} VRM-named targets of {} in all",
        support::FACES[0],
        got_arkit.len(),
        got_vrm.len(),
        names.len()
    );
    assert_eq!(got_arkit, expect_arkit);
    assert_eq!(got_vrm, expect_vrm);
    // ARKit first, then VRM, then facebem's own (every one of which has a `_`).
    let first_own = got_arkit.len() + got_vrm.len();
    assert_eq!(names[..got_arkit.len()], got_arkit[..]);
    assert_eq!(names[got_arkit.len()..first_own], got_vrm[..]);
    assert!(names[first_own..].iter().all(|n| n.contains('_')));
    let mut unique = names.clone();
    unique.sort_unstable();
    unique.dedup();
    assert_eq!(unique.len(), names.len(), "duplicate target names");
    // The ten thesis muscles alone make 17 ARKit and 9 VRM names; more controls, more names.
    assert!(got_arkit.len() >= 17 && got_vrm.len() >= 9);
    if AGREED_CONTROL_IDS
        .iter()
        .all(|c| ids.iter().any(|i| i == c))
    {
        assert!(got_arkit.len() >= 43 && got_vrm.len() + repeated_vrm(&repeated) == 14);
    }

    // Every other name of the 52 + 18 is listed as left out, with the reason, or as the
    // repeat of a written target; exactly one of these.
    let left_out = x["leftOutTargets"].as_object().unwrap();
    for n in arkit::NAMES.iter().chain(&vrm::NAMES) {
        let listed = [
            names.contains(n),
            left_out.contains_key(*n),
            x["sameAs"].get(*n).is_some() || x["negativeOf"].get(*n).is_some(),
        ];
        assert_eq!(
            listed.iter().filter(|l| **l).count(),
            1,
            "{n} must be exported, left out or a repeat: {listed:?}"
        );
    }
    // The default face's VRM blinks are its ARKit blinks, and VRM neutral is the base mesh.
    assert_eq!(x["sameAs"]["blinkLeft"], "eyeBlinkLeft");
    assert!(repeated.iter().any(|r| r == "neutral"));
    assert!(
        left_out["eyeLookUpLeft"]
            .as_str()
            .unwrap()
            .contains("no eyeballs")
    );
    // Partial ones name their missing controls.
    for (name, missing) in x["partialTargets"].as_object().into_iter().flatten() {
        let e = expressions::find(name).unwrap();
        for c in missing.as_array().unwrap() {
            let c = c.as_str().unwrap();
            assert!(e.controls().contains(&c) && !ids.iter().any(|i| i == c));
        }
    }

    // Each named target is its slider combination's displacement, in metres (f32).
    let prim = doc.meshes().next().unwrap().primitives().next().unwrap();
    let reader = prim.reader(|b| Some(&buffers[b.index()]));
    let targets: Vec<Vec<[f32; 3]>> = reader
        .read_morph_targets()
        .map(|(p, _, _)| p.unwrap().collect())
        .collect();
    let metres = m.metres_per_unit();
    for (k, name) in names[..first_own].iter().enumerate() {
        let r = expressions::find(name).unwrap().resolve(ids).unwrap();
        let posed = m.pose(&r.sliders).unwrap();
        for (i, w) in m.mesh.input_to_vertex.iter().enumerate() {
            let d = w.map_or(DVec3::ZERO, |w| {
                (posed[w as usize] - m.mesh.vertices[w as usize]) * metres
            });
            let got = glam::Vec3::from(targets[k][i]).as_dvec3();
            assert!((got - d).length() < 1e-7, "{name} vertex {i}: {got} vs {d}");
        }
    }
}

#[test]
fn names_option_picks_the_sets() {
    let m = model(0);
    let dir = tempfile::tempdir().unwrap();
    for (names, set) in [("arkit", NameSet::Arkit), ("vrm", NameSet::Vrm)] {
        let glb = dir.path().join(format!("{names}.glb"));
        let params = facebem::export::GltfParams {
            names: NameSets::parse(names).unwrap(),
            animation: true,
            ..Default::default()
        };
        m.write_gltf(&glb, &params).unwrap();
        support::assert_valid(&glb);
        let (doc, _, _) = gltf::import(&glb).unwrap();
        let x = extras(&doc);
        let got: Vec<&str> = x["targetNames"]
            .as_array()
            .unwrap()
            .iter()
            .map(|n| n.as_str().unwrap())
            .collect();
        let repeated = repeats(&x);
        let expected: Vec<&str> = expressions::of_set(set)
            .iter()
            .filter(|e| makeable(e, m.muscle_ids()) && !repeated.iter().any(|r| r == e.name))
            .map(|e| e.name)
            .collect();
        assert_eq!(got, expected);
        // Without facebem's presets the clips are the VRM expressions (none for ARKit).
        let clips: Vec<String> = doc
            .animations()
            .map(|a| a.name().unwrap_or_default().to_string())
            .collect();
        let want: Vec<&str> = if set == NameSet::Vrm {
            expected
                .iter()
                .copied()
                .filter(|n| *n != "neutral")
                .collect()
        } else {
            vec![]
        };
        assert_eq!(clips, want);
    }
}

/// How many of `repeated` are VRM names.
fn repeated_vrm(repeated: &[String]) -> usize {
    repeated
        .iter()
        .filter(|r| vrm::NAMES.contains(&r.as_str()))
        .count()
}

/// Canonical displacement, mm, of vertex `v` for a named expression at full weight.
fn motion_mm(m: &FaceModel, lm: &FaceLandmarks, name: &str, v: u32) -> Option<DVec3> {
    let r = expressions::find(name)?.resolve(m.muscle_ids())?;
    let posed = m.pose(&r.sliders).unwrap();
    Some(lm.canonical_mm(posed[v as usize] - m.mesh.vertices[v as usize]))
}

/// ARKit's and VRM's "Left" is the subject's own left: facebem's `_l`, +x in the canonical
/// frame. On real faces, `mouthSmileLeft` moves the +x mouth corner far more than the −x one,
/// `browOuterUpLeft` the +x brow; the Right names the other way round. Where the rig has the
/// controls, `jawLeft` moves the chin toward +x and `eyeBlinkLeft`/`blinkLeft` close the +x eye.
fn left_is_the_subjects_left(face: usize) {
    let m = model(face);
    let lm = FaceLandmarks::of(m).unwrap();
    let pairs = [
        (
            "mouthSmileLeft",
            "mouthSmileRight",
            lm.mouth_corner_l,
            lm.mouth_corner_r,
        ),
        ("browOuterUpLeft", "browOuterUpRight", lm.brow_l, lm.brow_r),
    ];
    for (left, right, v_l, v_r) in pairs {
        let on_l = motion_mm(m, &lm, left, v_l).unwrap().length();
        let on_r = motion_mm(m, &lm, left, v_r).unwrap().length();
        println!("{left}: +x landmark {on_l:.2} mm, -x landmark {on_r:.2} mm");
        assert!(on_l > 1.0 && on_l > 4.0 * on_r, "{left}: {on_l} vs {on_r}");
        let on_r2 = motion_mm(m, &lm, right, v_r).unwrap().length();
        let on_l2 = motion_mm(m, &lm, right, v_l).unwrap().length();
        assert!(
            on_r2 > 1.0 && on_r2 > 4.0 * on_l2,
            "{right}: {on_r2} vs {on_l2}"
        );
    }
    // The smile corner moves up (+y) and out (+x on the left).
    let d = motion_mm(m, &lm, "mouthSmileLeft", lm.mouth_corner_l).unwrap();
    assert!(d.x > 0.0 && d.y > 0.0, "{d}");
    // Controls that may not exist yet: checked once they do.
    let chin = lm
        .loops
        .mouth
        .iter()
        .copied()
        .min_by(|&a, &b| {
            let y = |v: u32| {
                lm.canonical_from_input
                    .transform_point3(m.mesh.vertices[v as usize])
                    .y
            };
            y(a).total_cmp(&y(b))
        })
        .unwrap();
    if let (Some(l), Some(r)) = (
        motion_mm(m, &lm, "jawLeft", chin),
        motion_mm(m, &lm, "jawRight", chin),
    ) {
        assert!(l.x > 0.0 && r.x < 0.0, "jawLeft {l}, jawRight {r}");
    }
    let eye_motion = |name: &str, eye: &[u32]| -> Option<f64> {
        Some(
            eye.iter()
                .map(|&v| motion_mm(m, &lm, name, v).map(|d| d.length()))
                .collect::<Option<Vec<f64>>>()?
                .into_iter()
                .fold(0.0, f64::max),
        )
    };
    for name in ["eyeBlinkLeft", "blinkLeft"] {
        if let (Some(l), Some(r)) = (
            eye_motion(name, &lm.loops.eye_l),
            eye_motion(name, &lm.loops.eye_r),
        ) {
            assert!(
                l > 1.0 && l > 4.0 * r,
                "{name}: +x eye {l} mm, -x eye {r} mm"
            );
        }
    }
}

#[test]
fn left_is_the_subjects_left_mediapipe() {
    left_is_the_subjects_left(0);
}

#[test]
fn left_is_the_subjects_left_ict_2500() {
    left_is_the_subjects_left(1);
}

/// Names that also exist among the captured ICT expressions (`tests/data/calibration`, ICT's
/// `_L`/`_R` = ARKit's `Left`/`Right`), with the captures whose sum is that name: ARKit's
/// `browInnerUp` and VRM's `blink` are both sides, ICT captures each side.
const ICT_SHARED: [(&str, &[&str]); 11] = [
    ("mouthSmileLeft", &["mouthSmile_L"]),
    ("mouthSmileRight", &["mouthSmile_R"]),
    ("browOuterUpLeft", &["browOuterUp_L"]),
    ("browOuterUpRight", &["browOuterUp_R"]),
    ("browInnerUp", &["browInnerUp_L", "browInnerUp_R"]),
    ("jawOpen", &["jawOpen"]),
    ("eyeBlinkLeft", &["eyeBlink_L"]),
    ("eyeBlinkRight", &["eyeBlink_R"]),
    ("blink", &["eyeBlink_L", "eyeBlink_R"]),
    ("blinkLeft", &["eyeBlink_L"]),
    ("blinkRight", &["eyeBlink_R"]),
];

/// Cosine similarity of the whole displacement field of every name shared with the captured
/// ICT expressions, on the 13k-triangle ICT face (`-- --nocapture` prints the table). The
/// smiles must reach 0.7 (they are the zygomaticus, held to that in anatomical_muscles.rs);
/// the others are reported (names the rig cannot make yet say so).
#[test]
fn ict_captured_expressions_cosine_table() {
    let m = model(3);
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data/calibration");
    let captured = |name: &str| -> Vec<DVec3> {
        let c = face_prep::load_face(&dir.join(format!("ict_narrow_face_{name}.obj"))).unwrap();
        assert_eq!(c.vertices.len(), m.mesh.vertices.len());
        c.vertices
            .iter()
            .zip(&m.mesh.vertices)
            .map(|(a, b)| *a - *b)
            .collect()
    };
    println!("| name | ICT capture(s) | cosine | largest motion rig / capture (mm) |");
    println!("|---|---|---|---|");
    let mm = m.rig.mm_per_unit();
    let largest = |f: &[DVec3]| f.iter().map(|d| d.length() * mm).fold(0.0, f64::max);
    for (name, files) in ICT_SHARED {
        let mut c = vec![DVec3::ZERO; m.mesh.vertices.len()];
        for f in files {
            for (a, b) in c.iter_mut().zip(captured(f)) {
                *a += b;
            }
        }
        let e = expressions::find(name).unwrap();
        let Some(r) = e.resolve(m.muscle_ids()) else {
            println!(
                "| {name} | {} | not in this rig (needs {}) | – |",
                files.join(" + "),
                e.controls().join(", ")
            );
            continue;
        };
        let posed = m.pose(&r.sliders).unwrap();
        let field: Vec<DVec3> = posed
            .iter()
            .zip(&m.mesh.vertices)
            .map(|(p, q)| *p - *q)
            .collect();
        let cos = cosine(&field, &c);
        let partial = if r.missing.is_empty() {
            String::new()
        } else {
            format!(" (partial: no {})", r.missing.join(", "))
        };
        println!(
            "| {name} | {} | {cos:.3}{partial} | {:.1} / {:.1} |",
            files.join(" + "),
            largest(&field),
            largest(&c)
        );
        if name.starts_with("mouthSmile") {
            assert!(cos >= 0.7, "{name}: cosine {cos:.3}");
        }
    }
}

/// Issue 11's flip limit: every ARKit and VRM name a face's rig makes, at full weight (the
/// corrective `mouthClose` over `jawOpen`, as ARKit defines it), turns at most 0.5 % of the front
/// triangles over, and only in the lips and lids and the folds they make (within [`LIPS_MM`] of
/// the mouth loop or [`LIDS_MM`] of an eye loop, in the front plane); issue 31's: none at the
/// lids (farther than [`LIPS_MM`] from the mouth loop). Regressions: ICT 13k's `blink` turned 50
/// lid triangles over, each `eyeBlink*` 25 (ICT 2500 9 and 6 / 3, Lee Perry-Smith 6 and 3 / 3,
/// MediaPipe 2 and 1 / 1) before the lids' orientation was kept
/// (`settle::project_at_the_lids`). Every face's brow lowering (`browDown*`, and `angry`, which
/// uses it) turned 1–6 triangles over at the corrugator's peak beside the inner canthus,
/// 12–21 mm from the eye loop, before the corrugator was relaxed in its combination; ICT 2500's
/// forehead turned one-vertex peaks of the frontalis over (`browOuterUpLeft` 1, `surprised` 5,
/// 13–17 mm above the eye loops) before the shell's vertex values were fitted linearly and the
/// forehead relaxed; its `mouthClose` turned 3 triangles 21–22 mm from the lips before the
/// lengthened directions were relaxed. Lee Perry-Smith's `noseSneer*` and `mouthUpperUp*`
/// turned 6 / 11 and 5 / 7 triangles over 13–30 mm from the lips, at the nasolabial fold and
/// the nose's wing, before the mid and lower face were relaxed
/// (`settle::beyond_lips_and_lids_fixed`; now none there). ICT 13k's `jawForward` turned 142
/// and then 81 (0.62 %) before the harmonic patch (now 38); ICT 2500's `mouthPucker` 17 (0.68 %)
/// before its two halves' sum was relaxed as one field (now 11).
fn named_targets_flip_at_most_half_a_percent(face: usize) {
    let m = model(face);
    let limit = (0.005 * m.mesh.triangles.len() as f64).floor() as usize;
    let places = FoldPlaces::of(m);
    let (mut over, mut away, mut lids) = (Vec::new(), Vec::new(), Vec::new());
    let (jaw, _) = expressions::sliders_for_name("jawOpen", m.muscle_ids()).unwrap();
    for e in arkit::EXPRESSIONS.iter().chain(&vrm::EXPRESSIONS) {
        let Some(r) = e.resolve(m.muscle_ids()) else {
            continue;
        };
        // A corrective is judged in the pose it corrects: ARKit's mouthClose is defined on top
        // of jawOpen, and alone lifts the lower lip through the upper one (ICT-FaceKit's capture
        // of it turns 412 of the narrow face's 13 120 triangles over alone, 150 with jawOpen).
        let on_jaw = expressions::corrective_base(e.name) == Some("jawOpen");
        let sliders: Vec<f64> = (r.sliders.iter().zip(&jaw))
            .map(|(a, b)| if on_jaw { a + b } else { *a })
            .collect();
        let posed = m.pose(&sliders).unwrap();
        let flipped = facebem::report::measure::flipped_triangles(
            &m.mesh.vertices,
            &posed,
            &m.mesh.triangles,
        );
        // Where each turned triangle is: beyond the lips and lids, or at the lids.
        let (mut far, mut at_lids) = (Vec::new(), Vec::new());
        for &t in &flipped {
            let (lips_mm, lids_mm) = places.distances_mm(&m.mesh.triangles[t as usize]);
            let place = format!("t{t} ({lips_mm:.1} / {lids_mm:.1} mm)");
            if lips_mm > LIPS_MM && lids_mm > LIDS_MM {
                far.push(place);
            } else if lips_mm > LIPS_MM {
                at_lids.push(place);
            }
        }
        println!(
            "{} {}: {} flips (allowed {limit}), {} away from the lips and lids, {} at the lids",
            support::FACES[face],
            e.name,
            flipped.len(),
            far.len(),
            at_lids.len()
        );
        if flipped.len() > limit {
            over.push(format!("{} {}", e.name, flipped.len()));
        }
        if !far.is_empty() {
            away.push(format!("{}: {far:?}", e.name));
        }
        if !at_lids.is_empty() {
            lids.push(format!("{}: {at_lids:?}", e.name));
        }
    }
    let face = support::FACES[face];
    assert!(
        over.is_empty(),
        "{face}: over {limit} flipped triangles: {over:?}"
    );
    assert!(
        away.is_empty(),
        "{face}: triangles turn over away from the lips and lids: {away:?}"
    );
    assert!(
        lids.is_empty(),
        "{face}: triangles turn over at the lids: {lids:?}"
    );
}

/// Where issue 11 lets skin fold: within this distance of the mouth loop, mm (the lips and the
/// folds beside them; `facebem::settle::untangle::LIPS_MM`).
const LIPS_MM: f64 = 12.0;
/// The same for the eye loops (the lids and the folds at the canthi; wider than
/// `facebem::settle::untangle::LIDS_MM`, the band the pipeline relaxes, which stops short of the brows).
const LIDS_MM: f64 = 12.0;

/// The mouth and eye loops of a face in its canonical front plane.
struct FoldPlaces {
    canonical: Vec<DVec3>,
    mouth: Vec<glam::DVec2>,
    eyes: [Vec<glam::DVec2>; 2],
    mm_per_unit: f64,
}

impl FoldPlaces {
    fn of(m: &FaceModel) -> FoldPlaces {
        let lm = FaceLandmarks::of(m).unwrap();
        let canonical: Vec<DVec3> = lm.canonical_points(&m.mesh.vertices);
        let front = |lp: &[u32]| -> Vec<glam::DVec2> {
            lp.iter()
                .map(|&v| canonical[v as usize].truncate())
                .collect()
        };
        FoldPlaces {
            mouth: front(&lm.loops.mouth),
            eyes: [front(&lm.loops.eye_l), front(&lm.loops.eye_r)],
            canonical,
            mm_per_unit: lm.mm_per_unit,
        }
    }

    /// Distances, mm, in the front plane from a triangle's centre to the mouth loop and to the
    /// nearer eye loop.
    fn distances_mm(&self, t: &[u32; 3]) -> (f64, f64) {
        let centre = t
            .iter()
            .map(|&v| self.canonical[v as usize])
            .sum::<DVec3>()
            .truncate()
            / 3.0;
        let to = |lp: &[glam::DVec2]| {
            face_prep::muscle_model::distance_to_loop(centre, lp) * self.mm_per_unit
        };
        (to(&self.mouth), to(&self.eyes[0]).min(to(&self.eyes[1])))
    }
}

#[test]
fn named_targets_flip_at_most_half_a_percent_mediapipe() {
    named_targets_flip_at_most_half_a_percent(0);
}

#[test]
fn named_targets_flip_at_most_half_a_percent_lee_perry_smith() {
    named_targets_flip_at_most_half_a_percent(2);
}

/// Regression: `jawForward` turned 81 triangles over (0.62 %; 142 before that), at the mouth
/// corners where the upper lip's underside meets the lower lip, before the harmonic patch.
#[test]
fn named_targets_flip_at_most_half_a_percent_ict_13k() {
    named_targets_flip_at_most_half_a_percent(3);
}

/// Regressions: `mouthPucker` turned 17 triangles over (0.68 %), the sum of the sphincter's two
/// halves each relaxed on its own, before the sum was relaxed as one field (now 8); `blink`
/// turned 19 (0.76 %) before the lids were relaxed after the lid closure, then 9, and none since
/// the lids' orientation is kept; `mouthClose` turned 3 over at the nostrils, 21–22 mm from the
/// lips, before the lengthened direction of each response was relaxed too
/// (`settle::relax_each_guarded`).
#[test]
fn named_targets_flip_at_most_half_a_percent_ict_2500() {
    named_targets_flip_at_most_half_a_percent(1);
}

/// Issue 11: at full value every ARKit and VRM name the rig makes moves the face's outer
/// contour by at most 0.5 mm, except the contour's part on the jaw, which moves with the jaw
/// when the target uses a jaw control (`jawOpen`, the visemes, `mouthClose`, ...): for those the
/// contour above the jaw segment is held to 0.5 mm (above the hinge by the rig's longest contour
/// edge, as in `tests/jaw.rs`: a rim element whose centroid is in the segment reaches up to one
/// edge above it). Measured: 0.004 mm at most (ICT 13k's `jawForward`, above the jaw), 0 on
/// the other faces: the anatomical model pins the contour's vertices to the fixed rim.
fn named_targets_keep_the_contour(face: usize) {
    let m = model(face);
    let lm = FaceLandmarks::of(m).unwrap();
    let canonical = lm.canonical_points(&m.mesh.vertices);
    let seam_y = support::above_the_jaw_y(m);
    let whole: Vec<usize> = lm.loops.face.iter().map(|&v| v as usize).collect();
    let upper: Vec<usize> = whole
        .iter()
        .copied()
        .filter(|&v| canonical[v].y > seam_y)
        .collect();
    assert!(!upper.is_empty() && upper.len() < whole.len());
    let jaw_controls: Vec<usize> = ["jaw_open", "jaw_forward", "jaw_lateral"]
        .iter()
        .filter_map(|id| m.muscle_ids().iter().position(|i| i == id))
        .collect();
    assert_eq!(jaw_controls.len(), 3);
    let mut checked = 0;
    let mut worst = (0.0, "");
    for e in arkit::EXPRESSIONS.iter().chain(&vrm::EXPRESSIONS) {
        let Some(r) = e.resolve(m.muscle_ids()) else {
            continue;
        };
        let posed = m.pose(&r.sliders).unwrap();
        let uses_jaw = jaw_controls.iter().any(|&k| r.sliders[k] != 0.0);
        let held = if uses_jaw { &upper } else { &whole };
        let moved_mm = held
            .iter()
            .map(|&v| (posed[v] - m.mesh.vertices[v]).length() * lm.mm_per_unit)
            .fold(0.0, f64::max);
        assert!(
            moved_mm <= 0.5,
            "{} {}: the contour{} moves {moved_mm:.3} mm",
            support::FACES[face],
            e.name,
            if uses_jaw { " above the jaw" } else { "" }
        );
        if moved_mm > worst.0 {
            worst = (moved_mm, e.name);
        }
        checked += 1;
    }
    eprintln!(
        "{}: {checked} targets, the contour moves at most {:.3} mm ({})",
        support::FACES[face],
        worst.0,
        worst.1
    );
    assert!(checked >= 57, "{checked} targets");
}

#[test]
fn named_targets_keep_the_contour_mediapipe() {
    named_targets_keep_the_contour(0);
}

#[test]
fn named_targets_keep_the_contour_ict_2500() {
    named_targets_keep_the_contour(1);
}

#[test]
fn named_targets_keep_the_contour_lee_perry_smith() {
    named_targets_keep_the_contour(2);
}

#[test]
fn named_targets_keep_the_contour_ict_13k() {
    named_targets_keep_the_contour(3);
}
