//! ICT-FaceKit's captured expressions on its whole head (`tests/data/calibration/ict_head_deltas/`)
//! and facebem's targets compared with them, target by target: the cosine of the two
//! displacement fields on the narrow face rigged alone and on the whole head (issue 32).
//!
//! ```no_run
//! let rows = facebem::report::captures::head_and_narrow_face(std::path::Path::new(".")).unwrap();
//! for r in &rows {
//!     println!("{} {:?} {:.2}", r.name, r.narrow_face, r.whole_head);
//! }
//! ```

use std::collections::HashMap;
use std::path::Path;

use face_prep::parts::{PartKind, Scene, find_parts, front_face};
use glam::DVec3;

use crate::export::GltfParams;
use crate::export::gltf::named_targets;
use crate::report::measure::cosine;
use crate::{Control, PipelineParams, build_face_model};

/// One target compared with its capture.
#[derive(Clone, Debug, PartialEq)]
pub struct Row {
    /// The ARKit name.
    pub name: String,
    /// Cosine on the narrow face rigged alone (`None`: the face alone has no such target).
    pub narrow_face: Option<f64>,
    /// Cosine on the whole head, every vertex but the eyeballs' (the captures do not turn them).
    pub whole_head: f64,
    /// The largest motion on the whole head (eyeballs left out), mm.
    pub head_largest_mm: f64,
    /// The captured largest motion, mm.
    pub captured_largest_mm: f64,
    /// The largest motion of the skin (the lids, not the lashes riding on them), mm.
    pub skin_largest_mm: f64,
    /// The captured largest motion of the skin, mm.
    pub captured_skin_largest_mm: f64,
    /// Cosine on the lid parts alone (lashes, occlusion layers, tear film); `None` without
    /// them.
    pub lid_parts: Option<f64>,
}

/// The ICT file stems of an ARKit name (`_L`/`_R`; browInnerUp and cheekPuff in two halves;
/// the jaw's and the mouth's sideways moves are directions and keep their names).
///
/// ```
/// use facebem::report::captures::ict_stems;
/// assert_eq!(ict_stems("mouthSmileLeft"), ["mouthSmile_L"]);
/// assert_eq!(ict_stems("cheekPuff"), ["cheekPuff_L", "cheekPuff_R"]);
/// assert_eq!(ict_stems("mouthLeft"), ["mouthLeft"]);
/// ```
pub fn ict_stems(name: &str) -> Vec<String> {
    if matches!(name, "jawLeft" | "jawRight" | "mouthLeft" | "mouthRight") {
        vec![name.to_string()]
    } else if let Some(stem) = name.strip_suffix("Left") {
        vec![format!("{stem}_L")]
    } else if let Some(stem) = name.strip_suffix("Right") {
        vec![format!("{stem}_R")]
    } else if name == "browInnerUp" || name == "cheekPuff" {
        vec![format!("{name}_L"), format!("{name}_R")]
    } else {
        vec![name.to_string()]
    }
}

/// The captured field of ARKit `name` on `n` head vertices, mm, from the folder `dir`
/// (`None` when ICT has no such shape).
pub fn captured(dir: &Path, name: &str, n: usize) -> std::io::Result<Option<Vec<DVec3>>> {
    let mut field = vec![DVec3::ZERO; n];
    for stem in ict_stems(name) {
        let path = dir.join(format!("{stem}.txt"));
        if !path.exists() {
            return Ok(None);
        }
        for line in std::fs::read_to_string(&path)?
            .lines()
            .filter(|l| !l.starts_with('#'))
        {
            let w: Vec<f64> = line
                .split_whitespace()
                .filter_map(|x| x.parse().ok())
                .collect();
            if let [i, x, y, z] = w[..]
                && i >= 0.0
                && (i as usize) < n
            {
                field[i as usize] += DVec3::new(x, y, z);
            }
        }
    }
    Ok(Some(field))
}

/// A field on the rig's vertices (cm, ICT's unit) as mm on the input file's vertices, through
/// the face's `input_to_vertex` (zero where an input vertex has no rig vertex): the frame the
/// captures are given in.
///
/// ```
/// use facebem::report::captures::on_input_vertices_mm;
/// use glam::DVec3;
/// let mm = on_input_vertices_mm(&[Some(1), None], &[DVec3::ZERO, DVec3::X]);
/// assert_eq!(mm, [DVec3::new(10.0, 0.0, 0.0), DVec3::ZERO]);
/// ```
pub fn on_input_vertices_mm(input_to_vertex: &[Option<u32>], field_cm: &[DVec3]) -> Vec<DVec3> {
    input_to_vertex
        .iter()
        .map(|v| v.map_or(DVec3::ZERO, |v| 10.0 * field_cm[v as usize]))
        .collect()
}

/// Rigs the narrow face and the whole head of the repository at `root` and compares every
/// ARKit target with its capture (the assets are in cm; fields compared in mm).
pub fn head_and_narrow_face(
    root: &Path,
) -> Result<Vec<Row>, Box<dyn std::error::Error + Send + Sync>> {
    let captures = root.join("tests/data/calibration/ict_head_deltas");
    let params = PipelineParams::default();
    let narrow = face_prep::load_face(&root.join("assets/ict_narrow_face_4loop.obj"))?;
    let model = build_face_model(&narrow, &params, &Control::new())?;
    let narrow_fields: HashMap<String, Vec<DVec3>> =
        named_targets(&model.basis, &model.gltf_params(&GltfParams::default()))?
            .targets
            .into_iter()
            .map(|(name, field)| (name, on_input_vertices_mm(&narrow.input_to_vertex, &field)))
            .collect();
    let scene = Scene::read(
        &root.join("assets/heads/ict_generic_head.obj"),
        &Default::default(),
    )?;
    let parts = find_parts(&scene)?;
    let front = front_face(&scene, &parts)?;
    let mesh = face_prep::FaceMesh::from_triangles(&front.positions, &front.triangles)?;
    let head_params = PipelineParams {
        outline_is_cut: true,
        ..params.clone()
    };
    let model = build_face_model(&mesh, &head_params, &Control::new())?;
    let head = crate::transfer::head::carry_to_head(
        &scene,
        &parts,
        &front,
        &model.mesh,
        &model.rig,
        &model.basis,
    );
    let plain = model.gltf_params(&GltfParams::default());
    let gltf = GltfParams {
        named_fields: head.named_fields_for(plain.names),
        ..plain
    };
    let n = scene.positions.len();
    let mut eyeball = vec![false; n];
    let (mut skin, mut lid_part) = (vec![false; n], vec![false; n]);
    for (c, k) in parts.components.iter().zip(&parts.kinds) {
        let flag = match k {
            PartKind::Eyeball(_) => &mut eyeball,
            PartKind::Skin => &mut skin,
            PartKind::LidPart => &mut lid_part,
            _ => continue,
        };
        c.vertices.iter().for_each(|&v| flag[v as usize] = true);
    }
    let only = |f: &[DVec3], flag: &[bool]| -> Vec<DVec3> {
        f.iter()
            .zip(flag)
            .map(|(d, &on)| if on { *d } else { DVec3::ZERO })
            .collect()
    };
    // Every vertex but the eyeballs' (the captures do not turn them).
    let not_eyeball: Vec<bool> = eyeball.iter().map(|&e| !e).collect();
    let keep = |f: &[DVec3]| only(f, &not_eyeball);
    let largest = |f: &[DVec3]| f.iter().map(|d| d.length()).fold(0.0, f64::max);
    let mut rows = Vec::new();
    for (name, field) in named_targets(&head.basis, &gltf)?.targets {
        let Some(capture) = captured(&captures, &name, n)? else {
            continue;
        };
        let capture = keep(&capture);
        let ours = keep(&field.iter().map(|d| 10.0 * *d).collect::<Vec<_>>());
        rows.push(Row {
            narrow_face: narrow_fields
                .get(&name)
                .map(|f| cosine(f, &capture[..f.len().min(n)])),
            whole_head: cosine(&ours, &capture),
            head_largest_mm: largest(&ours),
            captured_largest_mm: largest(&capture),
            skin_largest_mm: largest(&only(&ours, &skin)),
            captured_skin_largest_mm: largest(&only(&capture, &skin)),
            lid_parts: lid_part
                .contains(&true)
                .then(|| cosine(&only(&ours, &lid_part), &only(&capture, &lid_part))),
            name,
        });
    }
    Ok(rows)
}
