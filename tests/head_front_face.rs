//! The front face cut from a whole head (issue 32, item 3, first method) rigs like a face
//! mesh: ICT-FaceKit's generic head (`assets/heads/`), its front face cut by
//! `face_prep::parts::front_face`, rigged as `facebem export` rigs it, is trusted, and its
//! happy preset lifts both mouth corners alike.

use face_prep::InputLimits;
use face_prep::parts::{Scene, find_parts, front_face};
use facebem::{Control, PipelineParams, build_face_model};

#[test]
fn the_front_face_of_the_ict_head_rigs_and_smiles() {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("assets/heads/ict_generic_head.obj");
    let scene = Scene::read(&path, &InputLimits::default()).unwrap();
    let parts = find_parts(&scene).unwrap();
    let face = front_face(&scene, &parts).unwrap();
    let mesh = face_prep::FaceMesh::from_triangles(&face.positions, &face.triangles).unwrap();
    // As `facebem export` rigs it: the outline is facebem's own cut, left out of the
    // symmetry test, so the face (mirror-symmetric in shape, not in its triangles: its eye
    // openings have 17 and 15 vertices) is built on its mirror-meshed stand-in.
    let params = PipelineParams {
        outline_is_cut: true,
        ..PipelineParams::default()
    };
    let model = build_face_model(&mesh, &params, &Control::default()).unwrap();
    assert_eq!(
        model.report.simplify_path,
        Some(facebem::copy::simplify::SimplifyPath::SymmetrizedMirrored)
    );
    let distrust = facebem::model::distrust(&model);
    assert!(distrust.is_empty(), "{distrust:?}");
    // The mouth the rig found is ICT's (its lips part at y ≈ −3.1 cm, x ±2.3 cm at the corners).
    let happy = facebem::expressions::presets::find("happy")
        .unwrap()
        .sliders_for(model.muscle_ids());
    let posed = model.pose(&happy).unwrap();
    let mm = model.rig.mm_per_unit();
    let frame = parts.frame.unwrap();
    let mut lifts = Vec::new();
    for side in [1.0, -1.0] {
        // The vertex nearest ICT's mouth corner on this side.
        let corner = glam::DVec3::new(2.3 * side, -3.1, 9.6);
        let v = (0..mesh.vertices.len())
            .min_by(|&a, &b| {
                mesh.vertices[a]
                    .distance(corner)
                    .total_cmp(&mesh.vertices[b].distance(corner))
            })
            .unwrap();
        let lift_mm = (posed[v] - mesh.vertices[v]).dot(frame.up) * mm;
        assert!(lift_mm > 2.0, "corner {side}: lifted {lift_mm} mm");
        lifts.push(lift_mm);
    }
    // Both corners alike (on the head's own triangles they were not).
    assert!((lifts[0] - lifts[1]).abs() < 0.5, "{lifts:?} mm");
}
