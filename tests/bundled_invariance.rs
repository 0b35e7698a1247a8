//! Issue 30, item 3, on the bundled faces: each written differently — rotated 30° about a
//! tilted axis, ×10 and moved by 1 000 units, renumbered and its triangles reversed in order;
//! and ×0.001 — with its unit stated, makes the same expressions: every ARKit target within 2 %
//! RMS of its largest motion, the same near-singular ratio within 10 %. (The test faces made
//! from MediaPipe are held to the same in `closed_mouths_and_eyes` and `shape_symmetry`.)
//!
//! Not held yet: ICT 2500, rotated ×10 and moved, differs by 5.2 % (mouthShrugUpper). The front
//! repair that opens its pressed lips takes each vertex's largest push, and two equal pushes
//! are chosen between by rounding; a continuous choice fixes it (1.2 %) but moves three ICT 2500
//! results past their bounds (`docs/journal.md`, 2026-11-28 night).

mod closed_common;
mod support;

use closed_common::{RawFace, assert_invariant, rotated_scaled_moved};
use glam::{DAffine3, DVec3};

fn raw(name: &str) -> RawFace {
    let mesh = face_prep::load_face(&support::asset(name)).unwrap();
    (mesh.vertices, mesh.triangles)
}

fn bundled_face_is_invariant(name: &str) {
    let face = raw(name);
    assert_invariant(name, "rotated x10 moved", &face, rotated_scaled_moved());
    assert_invariant(
        name,
        "x0.001",
        &face,
        DAffine3::from_scale(DVec3::splat(0.001)),
    );
}

#[test]
fn mediapipe_is_invariant_to_how_the_file_is_written() {
    bundled_face_is_invariant(support::FACES[0]);
}

#[test]
fn lee_perry_smith_is_invariant_to_how_the_file_is_written() {
    bundled_face_is_invariant(support::FACES[2]);
}

#[test]
fn ict_13k_is_invariant_to_how_the_file_is_written() {
    bundled_face_is_invariant(support::FACES[3]);
}
