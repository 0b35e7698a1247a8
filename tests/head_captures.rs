//! Issue 32: facebem's targets on ICT-FaceKit's whole head against its captured expressions
//! (`tests/data/calibration/ict_head_deltas/`), by the cosine of the displacement fields,
//! next to the same on the narrow face rigged alone (`facebem::report::captures`; the table:
//! `cargo run --release -p facebem-tools --bin head_cosines`).

use facebem::report::captures::{Row, head_and_narrow_face};

fn row<'a>(rows: &'a [Row], name: &str) -> &'a Row {
    rows.iter().find(|r| r.name == name).unwrap()
}

#[test]
fn the_whole_head_moves_like_the_captures() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let rows = head_and_narrow_face(root).unwrap();
    for r in &rows {
        eprintln!(
            "{:<22} narrow {:>5}  head {:.2}  largest {:.1} mm (captured {:.1})",
            r.name,
            r.narrow_face.map_or("—".into(), |x| format!("{x:.2}")),
            r.whole_head,
            r.head_largest_mm,
            r.captured_largest_mm
        );
    }
    assert_eq!(
        rows.len(),
        47,
        "every ARKit name ICT captured (all but tongueOut, 4 halves summed)"
    );
    // The gaze: the lids follow as captured (cosine ≥ 0.7, the upper lid's largest motion
    // within 30 % of the captured one).
    for name in facebem::transfer::gaze::ARKIT_GAZE.map(|g| g.0) {
        let r = row(&rows, name);
        assert!(r.whole_head >= 0.7, "{name}: cosine {}", r.whole_head);
        let ratio = r.head_largest_mm / r.captured_largest_mm;
        assert!(
            (0.7..=1.3).contains(&ratio),
            "{name}: {ratio} of the captured motion"
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
    // Not yet everywhere (issue 32's note): at most 6 targets lower on the whole head than on
    // the narrow face by more than 0.05 (cheekPuff, mouthClose, mouthLowerDown,
    // mouthRollLower, mouthShrugLower: the lower lip and the cheek's lining), none by more
    // than 0.1.
    let worse: Vec<(&str, f64)> = rows
        .iter()
        .filter_map(|r| r.narrow_face.map(|n| (r.name.as_str(), r.whole_head - n)))
        .filter(|&(_, d)| d < -0.05)
        .collect();
    eprintln!("lower by more than 0.05: {worse:?}");
    assert!(worse.len() <= 6, "{worse:?}");
    assert!(worse.iter().all(|&(_, d)| d > -0.1), "{worse:?}");
}
