//! Issue 32: facebem's targets on ICT-FaceKit's whole head against its captured expressions
//! (`tests/data/calibration/ict_head_deltas/`), by the cosine of the displacement fields,
//! next to the same on the narrow face rigged alone (`facebem::report::captures`; the table:
//! `cargo run --release -p facebem-tools --bin head_cosines`).

use facebem::report::captures::{Row, head_and_narrow_face};

fn row<'a>(rows: &'a [Row], name: &str) -> &'a Row {
    rows.iter().find(|r| r.name == name).unwrap()
}

/// Issue 33's calibration on the narrow face (`src/expressions/arkit.rs`; the table:
/// `cargo run --release -p facebem-tools --bin fit_recipes`): the fitted recipes and the lip
/// seal bring the mean cosine of the 43 targets from 0.595 to 0.737, none is negative (the rolls were −0.52 and
/// −0.24), the targets that matched already lose at most 0.02, and the ones the fit mended
/// keep their gain.
fn narrow_face_recipes_match_the_captures(rows: &[Row]) {
    let narrow: Vec<(&str, f64)> = rows
        .iter()
        .filter_map(|r| r.narrow_face.map(|c| (r.name.as_str(), c)))
        .collect();
    assert_eq!(narrow.len(), 43);
    let mean = narrow.iter().map(|(_, c)| c).sum::<f64>() / narrow.len() as f64;
    assert!(mean >= 0.76, "mean cosine {mean}");
    assert!(narrow.iter().all(|&(_, c)| c > 0.0), "{narrow:?}");
    let at_least = |name: &str, bound: f64| {
        let c = row(rows, name).narrow_face.unwrap();
        assert!(c >= bound, "{name}: cosine {c} under {bound}");
    };
    // Matched before the fit (hand-made recipes: 0.86, 0.85, 0.91, 0.87, 0.94, 0.94), less 0.02.
    for (stem, bound) in [
        ("mouthSmile", 0.84),
        ("mouthFrown", 0.83),
        ("mouthStretch", 0.89),
        ("eyeBlink", 0.85),
        ("eyeWide", 0.92),
    ] {
        at_least(&format!("{stem}Left"), bound);
        at_least(&format!("{stem}Right"), bound);
    }
    at_least("jawOpen", 0.92);
    // Mended by the fit (before: 0.08, 0.10, 0.31, −0.24, −0.52, 0.52, 0.38, 0.67).
    at_least("cheekPuff", 0.6);
    for stem in [
        "mouthPress",
        "noseSneer",
        "mouthDimple",
        "eyeSquint",
        "mouthUpperUp",
    ] {
        let bound = if stem == "mouthPress" { 0.5 } else { 0.55 };
        at_least(&format!("{stem}Left"), bound);
        at_least(&format!("{stem}Right"), bound);
    }
    at_least("mouthRollLower", 0.4);
    at_least("mouthRollUpper", 0.55);
    // The lip seal (before: the muscle recipe, 0.46; now 0.95).
    at_least("mouthClose", 0.9);
    // The cheek raiser (orbicularis_oculi_malar) and the squint's medial pull (before: 0.45,
    // 0.57; now 0.80, 0.72).
    for (stem, bound) in [("cheekSquint", 0.78), ("eyeSquint", 0.7)] {
        at_least(&format!("{stem}Left"), bound);
        at_least(&format!("{stem}Right"), bound);
    }
}

#[test]
fn the_whole_head_moves_like_the_captures() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let rows = head_and_narrow_face(root).unwrap();
    for r in &rows {
        eprintln!(
            "{:<22} narrow {:>5}  head {:.2}  largest {:.1} mm (captured {:.1})  lid parts {:>5}",
            r.name,
            r.narrow_face.map_or("—".into(), |x| format!("{x:.2}")),
            r.whole_head,
            r.head_largest_mm,
            r.captured_largest_mm,
            r.lid_parts.map_or("—".into(), |x| format!("{x:.2}"))
        );
    }
    assert_eq!(
        rows.len(),
        51,
        "every ARKit name ICT captured (all but tongueOut, 4 halves summed)"
    );
    narrow_face_recipes_match_the_captures(&rows);
    // The gaze: the lids follow as captured (cosine ≥ 0.7, the lid skin's largest motion
    // within 30 % of the captured one; the lashes, which turn with the lids about the eye's
    // centre, are measured below).
    for name in facebem::transfer::gaze::ARKIT_GAZE.map(|g| g.0) {
        let r = row(&rows, name);
        assert!(r.whole_head >= 0.7, "{name}: cosine {}", r.whole_head);
        let ratio = r.skin_largest_mm / r.captured_skin_largest_mm;
        assert!(
            (0.7..=1.3).contains(&ratio),
            "{name}: {ratio} of the captured motion"
        );
    }
    // The lashes and the other lid parts ride on the lids, turned with them about the eye's
    // centre (`facebem::transfer::lid_riders`): in the blinks they move as captured (cosine
    // over the lid parts alone ≥ 0.94; 0.90 on the lashes when each vertex followed the
    // nearest skin and the cards folded, with their largest motion 11.4 mm against the
    // captured 17.8).
    for name in ["eyeBlinkLeft", "eyeBlinkRight"] {
        let r = row(&rows, name);
        let lid_parts = r.lid_parts.unwrap();
        assert!(
            lid_parts >= 0.94,
            "{name}: lid parts' cosine {lid_parts:.3}"
        );
    }
    // The mouth's lining moves with the lips (reached along the skin, so the inside of each
    // lip takes its own lip's motion) and, in the jaw targets, with the mandible it lines:
    // smile, stretch, frown, upper-lip raise and the jaw on the whole head are within 0.05 of
    // the narrow face; jawOpen above 0.93 (0.92 with the lining fading to zero instead).
    for name in [
        "browOuterUpLeft",
        "browOuterUpRight",
        "noseSneerLeft",
        "noseSneerRight",
        "mouthUpperUpLeft",
        "mouthUpperUpRight",
        "jawForward",
        "mouthSmileLeft",
        "mouthSmileRight",
        "mouthStretchLeft",
        "mouthStretchRight",
        "mouthFrownLeft",
        "mouthFrownRight",
    ] {
        let r = row(&rows, name);
        let narrow = r.narrow_face.unwrap();
        assert!(
            r.whole_head > narrow - 0.05,
            "{name}: head {} narrow {narrow}",
            r.whole_head
        );
    }
    assert!(row(&rows, "jawOpen").whole_head > 0.93);
    // Left and right alike: the front face is built on its mirror-meshed stand-in (its outline
    // is facebem's own cut, `PipelineParams::outline_is_cut`); on the head's own triangles
    // mouthLowerDown was 0.57 left and 0.65 right.
    for r in rows.iter().filter(|r| r.name.ends_with("Left")) {
        let right = row(&rows, &r.name.replace("Left", "Right"));
        assert!(
            (r.whole_head - right.whole_head).abs() < 0.01,
            "{}: {} against {}",
            r.name,
            r.whole_head,
            right.whole_head
        );
    }
    // Not yet everywhere (issue 32's note): at most 8 targets lower on the whole head than on
    // the narrow face by more than 0.05 (8 now: mouthLeft/Right, mouthLowerDown and the rolls,
    // the lips' inside, scored on the head's mouth socket only; cheekSquint, which the cheek
    // raiser lifted on both, the narrow face more: head 0.50 → 0.72, held below), none by more
    // than 0.1 but the rolls. The rolls' fitted recipes curl the lips on the face (narrow 0.42 /
    // 0.60) more than the socket follows them (head 0.12 / 0.38; before the fit −0.30 / −0.57).
    let worse: Vec<(&str, f64)> = rows
        .iter()
        .filter_map(|r| r.narrow_face.map(|n| (r.name.as_str(), r.whole_head - n)))
        .filter(|&(_, d)| d < -0.05)
        .collect();
    eprintln!("lower by more than 0.05: {worse:?}");
    assert!(worse.len() <= 8, "{worse:?}");
    let roll = |n: &str| n.starts_with("mouthRoll");
    assert!(
        worse.iter().all(|&(n, d)| d > -0.1 || roll(n) && d > -0.35),
        "{worse:?}"
    );
    // What the fitted recipes, the lip seal and the cheek raiser mended holds on the whole head
    // too (before: mouthClose 0.35, cheekPuff 0.00, mouthPress 0.17, noseSneer 0.34, the rolls
    // −0.30 / −0.57; cheekSquint 0.50 and eyeSquint 0.68 before the cheek raiser).
    for (name, bound) in [
        ("mouthClose", 0.85),
        ("cheekPuff", 0.6),
        ("mouthPressLeft", 0.45),
        ("cheekSquintLeft", 0.68),
        ("eyeSquintLeft", 0.77),
        ("noseSneerLeft", 0.65),
        ("mouthRollLower", 0.05),
        ("mouthRollUpper", 0.3),
    ] {
        let head = row(&rows, name).whole_head;
        assert!(head >= bound, "{name}: head cosine {head} under {bound}");
    }
}
