//! Human-readable summary of a face, its rig and (if computed) its model, for `facebem info`.

use std::fmt::Write;
use std::path::Path;

use face_prep::{Box2, ElementTag, FaceMesh, FaceRig};

use crate::FaceModel;

/// Multi-line summary: sizes, loops, feature boxes (canonical frame), muscles, skull, and for a
/// computed model its parameters, precompute figures and largest displacement per muscle.
pub fn describe(path: &Path, mesh: &FaceMesh, rig: &FaceRig, model: Option<&FaceModel>) -> String {
    let mut s = String::new();
    let kind = if model.is_some() { "rig" } else { "face mesh" };
    let _ = writeln!(s, "{} ({kind})", path.display());
    let _ = writeln!(
        s,
        "  face: {} vertices, {} triangles",
        mesh.vertices.len(),
        mesh.triangles.len()
    );
    if rig.face_triangle_count != mesh.triangles.len() {
        let _ = writeln!(
            s,
            "  simulated on a reduced copy (rolled-in parts peeled, large faces simplified): {} vertices, {} triangles",
            rig.face_vertex_count, rig.face_triangle_count
        );
    }
    let _ = writeln!(s, "  {}", rig.unit_choice().describe());
    let count = |tag| rig.shell.tags.iter().filter(|t| **t == tag).count();
    let _ = writeln!(
        s,
        "  shell: {} vertices, {} elements ({} front, {} back, {} rim), {} DOFs",
        rig.shell.vertices.len(),
        rig.shell.triangles.len(),
        count(ElementTag::Front),
        count(ElementTag::Back),
        count(ElementTag::Rim),
        3 * rig.shell.triangles.len()
    );
    for w in model.map(|m| m.report.warnings()).unwrap_or_default() {
        let _ = writeln!(s, "  WARNING: {w}");
    }
    if let Some(line) = &mesh.lip_line {
        let _ = writeln!(
            s,
            "  mouth: closed in the neutral (the lips meet along {} vertices, corner to corner); \
             cut open along that line, {} lower-lip vertices added",
            line.upper.len(),
            line.lower.len()
        );
    }
    if mesh.mouth_bag_vertices > 0 {
        let _ = writeln!(
            s,
            "  mouth: opens into a closed mouth bag; its {} vertices are taken off the simulated \
             face and each follows the lip vertex nearest along the bag",
            mesh.mouth_bag_vertices
        );
    }
    let closed = crate::model::closed_eyes(mesh, rig.canonical_from_input);
    if closed.iter().any(|&c| c) || !mesh.lid_lines.is_empty() {
        let which = match closed {
            [true, true] => "both",
            [true, false] => "the left",
            [false, true] => "the right",
            [false, false] => "neither",
        };
        let cut: Vec<String> = mesh
            .lid_lines
            .iter()
            .map(|l| l.upper.len().to_string())
            .collect();
        let _ = writeln!(
            s,
            "  eyes: closed in the neutral ({which}; lid lines cut open: {}); blink, lid raise \
             and squint leave a closed eye as it is",
            if cut.is_empty() {
                "none, the lids touch".to_string()
            } else {
                format!("{} vertices", cut.join(" and "))
            }
        );
    }
    let l = &rig.loops;
    let _ = writeln!(
        s,
        "  loops (vertices): face {}, eye L {}, eye R {}, mouth {}",
        l.face.len(),
        l.eye_l.len(),
        l.eye_r.len(),
        l.mouth.len()
    );
    let _ = writeln!(
        s,
        "  feature boxes (canonical x-y, face size {:.4}):",
        rig.face_size
    );
    let b = &rig.boxes;
    for (name, bx) in [
        ("face", &b.face),
        ("eye L", &b.eye_l),
        ("eye R", &b.eye_r),
        ("mouth", &b.mouth),
        ("nose", &b.nose),
        ("skull", &b.skull),
    ] {
        let _ = writeln!(s, "    {name:<6} {}", fmt_box(bx));
    }
    let _ = writeln!(s, "  skull: {} fixed elements", rig.skull.len());
    let _ = writeln!(s, "  muscles: {}", rig.muscles.len());
    for (k, m) in rig.muscles.iter().enumerate() {
        let id = m.kind.map_or(m.name.as_str(), |k| k.id());
        let _ = write!(
            s,
            "    {id:<30} front {:>3}, back {:>3} elements",
            m.front_chain.len(),
            m.back_chain.len()
        );
        if let Some(field) = model.and_then(|m| m.basis.displacements.get(k)) {
            let max = field.iter().map(|d| d.length()).fold(0.0, f64::max);
            let _ = write!(
                s,
                ", max vertex displacement {:.2} mm",
                max * rig.mm_per_unit()
            );
        }
        s.push('\n');
    }
    if let Some(m) = model {
        let r = &m.report;
        let _ = writeln!(
            s,
            "  solve: nu {}, {} DOFs; prep {:.2} s, BEM {:.2} s, transfer {:.2} s",
            m.params.poisson, r.dofs, r.prep_seconds, r.solve_seconds, r.transfer_seconds
        );
    }
    s
}

fn fmt_box(b: &Box2) -> String {
    format!(
        "x {:>9.4} .. {:>9.4}   y {:>9.4} .. {:>9.4}",
        b.min.x, b.max.x, b.min.y, b.max.y
    )
}

/// What `facebem info` can still say about a mesh whose rig cannot be built: its size and the
/// boundary loops it has (edges, perimeter, bounding box in the input frame).
///
/// ```
/// let mesh = facebem::input::default_face().unwrap();
/// let text = facebem::report::describe::describe_loops("face.obj".as_ref(), &mesh);
/// assert!(text.contains("4 boundary loops"), "{text}");
/// ```
pub fn describe_loops(path: &Path, mesh: &FaceMesh) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "{} (face mesh)", path.display());
    let _ = writeln!(
        s,
        "  face: {} vertices, {} triangles",
        mesh.vertices.len(),
        mesh.triangles.len()
    );
    if let Ok(loops) = face_prep::topology::validate(&mesh.vertices, &mesh.triangles) {
        let _ = writeln!(s, "  {} boundary loops:", loops.len());
        let summaries = face_prep::topology::loop_summaries(&mesh.vertices, &loops);
        for (i, (l, sum)) in loops.iter().zip(&summaries).enumerate().take(10) {
            let perimeter = face_prep::orient::loop_perimeter(&mesh.vertices, l);
            let _ = writeln!(
                s,
                "    loop {i}: perimeter {}, {sum}",
                face_prep::error::sig6(perimeter)
            );
        }
        if loops.len() > 10 {
            let _ = writeln!(s, "    and {} more", loops.len() - 10);
        }
    }
    s
}

/// What `facebem info` says of a file holding several parts (a head or an avatar, issue 32):
/// each part found ([`face_prep::parts::find_parts`]) with its vertices, triangles and the
/// names the file gives it, and the head's directions.
///
/// ```
/// use face_prep::parts::{Scene, find_parts};
/// let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\ng skin\nf 1 2 3\n";
/// let scene = Scene::from_obj(obj, &Default::default()).unwrap();
/// let parts = find_parts(&scene).unwrap();
/// let text = facebem::report::describe::describe_parts("head.obj".as_ref(), &scene, &parts);
/// assert!(text.contains("skin: 1 component, 3 vertices, 1 triangles (skin)"), "{text}");
/// ```
pub fn describe_parts(
    path: &Path,
    scene: &face_prep::parts::Scene,
    parts: &face_prep::parts::HeadParts,
) -> String {
    use face_prep::parts::PartKind;
    let mut s = String::new();
    let _ = writeln!(
        s,
        "{} (head or avatar: {} vertices, {} triangles, {} connected components)",
        path.display(),
        scene.positions.len(),
        scene.triangles.len(),
        parts.components.len()
    );
    let order = [
        PartKind::Skin,
        PartKind::Eyeball(face_prep::parts::Side::Left),
        PartKind::Eyeball(face_prep::parts::Side::Right),
        PartKind::UpperTooth,
        PartKind::LowerTooth,
        PartKind::GumsAndTongue,
        PartKind::LidPart,
        PartKind::Other,
    ];
    for kind in order {
        let members: Vec<usize> = (0..parts.kinds.len())
            .filter(|&i| parts.kinds[i] == kind)
            .collect();
        if members.is_empty() {
            continue;
        }
        let vertices: usize = members
            .iter()
            .map(|&i| parts.components[i].vertices.len())
            .sum();
        let triangles: usize = members
            .iter()
            .map(|&i| parts.components[i].triangles.len())
            .sum();
        let mut labels: Vec<&str> = members
            .iter()
            .flat_map(|&i| &parts.components[i].triangles)
            .map(|&t| scene.labels[scene.triangle_label[t as usize] as usize].as_str())
            .collect();
        labels.sort_unstable();
        labels.dedup();
        let shown = labels
            .iter()
            .take(4)
            .copied()
            .collect::<Vec<_>>()
            .join(", ");
        let more = labels.len().saturating_sub(4);
        let more = if more > 0 {
            format!(" and {more} more")
        } else {
            String::new()
        };
        let n = members.len();
        let _ = writeln!(
            s,
            "  {}: {n} component{}, {vertices} vertices, {triangles} triangles ({shown}{more})",
            kind.describe(),
            if n == 1 { "" } else { "s" },
        );
    }
    match (parts.eyeballs, parts.frame) {
        (Some([l, r]), Some(f)) => {
            let _ = writeln!(
                s,
                "  eyeballs: radius {} and {}, centres {} apart; the subject's left is ({:.3}, {:.3}, {:.3}), up ({:.3}, {:.3}, {:.3}), forward ({:.3}, {:.3}, {:.3})",
                face_prep::error::sig6(l.radius),
                face_prep::error::sig6(r.radius),
                face_prep::error::sig6(l.centre.distance(r.centre)),
                f.left.x,
                f.left.y,
                f.left.z,
                f.up.x,
                f.up.y,
                f.up.z,
                f.forward.x,
                f.forward.y,
                f.forward.z,
            );
        }
        _ => {
            let _ = writeln!(
                s,
                "  no eyeballs found (two closed spheres of an eye's size)"
            );
        }
    }
    match face_prep::parts::front_face(scene, parts) {
        Ok(face) => {
            let loops = face_prep::topology::validate(&face.positions, &face.triangles)
                .map_or_else(
                    |e| format!("not a valid face: {e}"),
                    |l| format!("{} openings", l.len()),
                );
            let _ = writeln!(
                s,
                "  front face cut from the skin: {} vertices, {} triangles, {loops}",
                face.positions.len(),
                face.triangles.len()
            );
        }
        Err(e) => {
            let _ = writeln!(s, "  front face: {e}");
        }
    }
    s
}
