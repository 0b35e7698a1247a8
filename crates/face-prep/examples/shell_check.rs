//! Self-intersections of a face's input front surface and of its default shell, and what the
//! front repair did: `cargo run --release -p face-prep --example shell_check -- FACE.obj...`.

use face_prep::shell::intersecting_pairs;
use face_prep::{FaceRig, RigParams, load_face};
use std::collections::BTreeMap;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let paths: Vec<String> = std::env::args().skip(1).collect();
    if paths.is_empty() {
        return Err("usage: shell_check FACE...".into());
    }
    for path in paths {
        let face = load_face(path.as_ref())?;
        let rig = FaceRig::build(&face, &RigParams::default())?;
        let canon: Vec<_> = face
            .vertices
            .iter()
            .map(|&p| rig.canonical_from_input.transform_point3(p))
            .collect();
        let input = intersecting_pairs(&canon, &face.triangles);
        let s = &rig.shell;
        let mut kinds: BTreeMap<String, usize> = BTreeMap::new();
        for p in s.self_intersections() {
            let k = format!("{:?}-{:?}", s.tags[p[0] as usize], s.tags[p[1] as usize]);
            *kinds.entry(k).or_default() += 1;
        }
        let r = s.front_repair;
        println!(
            "{path}: face size {:.4}; input front/front pairs {}; shell pairs {} {kinds:?}; \
             front repair: {} rounds, {} vertices moved, max {:.4} ({:.3}% of face size)",
            rig.face_size,
            input.len(),
            kinds.values().sum::<usize>(),
            r.rounds,
            r.moved_vertices,
            r.max_displacement,
            100.0 * r.max_displacement / rig.face_size
        );
    }
    Ok(())
}
