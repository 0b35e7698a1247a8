//! Issue 30, item 1: a face that is mirror-symmetric in shape gets mirror-symmetric responses
//! whatever its triangulation.

mod support;

use face_prep::MuscleKind;
use facebem::copy::simplify::SimplifyPath;
use facebem::report::measure::{FaceLandmarks, SurfacePoint};
use facebem::{Control, FaceModel, PipelineParams, build_face_model};
use glam::DVec3;

fn load(name: &str) -> face_prep::FaceMesh {
    face_prep::LoadOptions::default()
        .load(&support::asset(name))
        .unwrap()
}

/// Largest RMS difference between each left control's shell response and its right partner's
/// mirrored, as a fraction of the larger response's RMS, over the front elements of a rig
/// solved on a mirror-symmetric shell (canonical frame, element centroids paired by mirror
/// image).
fn shell_asymmetry(m: &FaceModel) -> (f64, String) {
    let shell = &m.rig.shell;
    let centroid = |t: [u32; 3]| t.iter().map(|&v| shell.vertices[v as usize]).sum::<DVec3>() / 3.0;
    let centroids: Vec<DVec3> = shell.triangles.iter().map(|&t| centroid(t)).collect();
    let mirror_of: Vec<usize> = centroids
        .iter()
        .map(|p| {
            let q = DVec3::new(-p.x, p.y, p.z);
            (0..centroids.len())
                .min_by(|&a, &b| {
                    centroids[a]
                        .distance_squared(q)
                        .total_cmp(&centroids[b].distance_squared(q))
                })
                .unwrap()
        })
        .collect();
    let mirrored = |d: DVec3| DVec3::new(-d.x, d.y, d.z);
    let (mut worst, mut which) = (0.0f64, String::new());
    for kind in MuscleKind::ALL
        .into_iter()
        .filter(|k| k.side() == face_prep::Side::Left)
    {
        let response =
            |k: MuscleKind| &m.shell_element_response[m.basis.muscle_index(k.id()).unwrap()];
        let (l, r) = (response(kind), response(kind.mirror()));
        let n = centroids.len() as f64;
        let diff = ((0..centroids.len())
            .map(|e| (l[e] - mirrored(r[mirror_of[e]])).length_squared())
            .sum::<f64>()
            / n)
            .sqrt();
        let rms = |f: &[DVec3]| (f.iter().map(|d| d.length_squared()).sum::<f64>() / n).sqrt();
        let ratio = diff / rms(l).max(rms(r));
        if ratio > worst {
            (worst, which) = (ratio, kind.id().to_string());
        }
    }
    (worst, which)
}

/// The mirror partner of every vertex of a mirror-meshed face (`facebem::copy::simplify::
/// mirror_map` in the face's canonical frame, interocular units): by the mesh, not by distance
/// alone (ICT's rolled-in lips cross at the corners, where the nearest vertex to a mirror image
/// can be on the other lip).
fn partners(mesh: &face_prep::FaceMesh) -> Vec<usize> {
    let (v, t) = (&mesh.vertices, &mesh.triangles);
    let loops = face_prep::topology::validate(v, t).unwrap();
    let (canonical_from_input, l) = face_prep::orient::canonical_frame(v, t, &loops).unwrap();
    let c = |lp: &[u32]| face_prep::orient::loop_centroid(v, lp);
    let iod = c(&l.eye_l).distance(c(&l.eye_r));
    let p: Vec<DVec3> = v
        .iter()
        .map(|&q| canonical_from_input.transform_point3(q) / iod)
        .collect();
    facebem::copy::simplify::mirror_map(&p, t)
        .expect("a mirror-meshed face")
        .into_iter()
        .map(|w| w as usize)
        .collect()
}

/// Left field against the mirrored right field of every paired control, on a face whose
/// vertices are mirror-symmetric (`mirror_of`, from [`partners`] of the face it was made from): the largest RMS difference as a fraction of the
/// larger field's RMS, and the largest difference at the mouth corners and brows in mm.
fn asymmetry(m: &FaceModel, mirror_of: &[usize]) -> (f64, f64, String) {
    let lm = FaceLandmarks::of(m).expect("four loops");
    let c = lm.canonical_points(&m.mesh.vertices);
    // The mouth corners, and the brow points' nearest vertices with their mirror partners:
    // between vertices, a field is interpolated over the user's own triangles, which differ
    // from side to side (on MediaPipe's coarse brow, by up to 1.6 mm under the corrugator).
    let nearest = |p: SurfacePoint| {
        let k = (0..3)
            .max_by(|&a, &b| p.weights[a].total_cmp(&p.weights[b]))
            .unwrap();
        p.corners[k] as usize
    };
    let pairs: Vec<(usize, usize)> = [
        lm.mouth_corner_l as usize,
        nearest(lm.brow_point_l),
        nearest(lm.brow_inner_point_l),
        lm.mouth_corner_r as usize,
        nearest(lm.brow_point_r),
        nearest(lm.brow_inner_point_r),
    ]
    .into_iter()
    .map(|v| (v, mirror_of[v]))
    .collect();
    let mirrored = |d: DVec3| DVec3::new(-d.x, d.y, d.z);
    let (mut worst_rms, mut worst_mm, mut which) = (0.0f64, 0.0f64, String::new());
    for kind in MuscleKind::ALL
        .into_iter()
        .filter(|k| k.side() == face_prep::Side::Left)
    {
        let field = |k: MuscleKind| -> Vec<DVec3> {
            let i = m.basis.muscle_index(k.id()).unwrap();
            m.basis.displacements[i]
                .iter()
                .map(|&d| lm.canonical_mm(-d))
                .collect()
        };
        let (l, r) = (field(kind), field(kind.mirror()));
        let rms =
            |f: &dyn Fn(usize) -> f64| ((0..c.len()).map(f).sum::<f64>() / c.len() as f64).sqrt();
        let diff = rms(&|v| (l[v] - mirrored(r[mirror_of[v]])).length_squared());
        let larger = rms(&|v| l[v].length_squared()).max(rms(&|v| r[v].length_squared()));
        if diff / larger > worst_rms {
            worst_rms = diff / larger;
            which = kind.id().to_string();
        }
        for &(vl, vr) in &pairs {
            worst_mm = worst_mm.max((l[vl] - mirrored(r[vr])).length());
        }
    }
    (worst_rms, worst_mm, which)
}

/// Test face (a) of issue 30: a bundled face with about a third of its interior edges flipped
/// at random (seed 1: the same vertices, other diagonals), symmetric in shape, not in its
/// triangles. It is built as its mirror-meshed stand-in (its left half cut along the midplane
/// and mirrored), settled there, and carried to its own vertices, so every paired control's
/// shell response mirrors its partner's within 1 % RMS, and its field at the vertices within
/// 5 % RMS of the larger field and 1 mm at the mouth corners and brows. On its own triangles
/// (before) the pairs differed by up to 77 % RMS at the vertices before settling, and 66 %
/// with the response settled on the stand-in but the settling on its own triangles.
#[test]
fn a_retriangulated_face_gets_mirror_symmetric_responses() {
    let orig = load("mediapipe_canonical_4loop.obj");
    let mesh = support::retriangulated(&orig, 1);
    assert_ne!(mesh.triangles, orig.triangles);
    let m = build_face_model(&mesh, &PipelineParams::default(), &Control::new()).unwrap();
    assert_eq!(m.report.simplify_path, Some(SimplifyPath::Symmetrized));
    let (shell, which) = shell_asymmetry(&m);
    let (vertices, landmarks_mm, worst) = asymmetry(&m, &partners(&orig));
    eprintln!(
        "retriangulated MediaPipe: shell {shell:.4} ({which}); after settling, vertices {vertices:.3} ({worst}), landmarks {landmarks_mm:.2} mm"
    );
    assert!(shell <= 0.01, "{which}: {shell:.4}");
    assert!(vertices <= 0.05, "{worst}: {vertices:.4}");
    assert!(landmarks_mm <= 1.0, "{landmarks_mm:.3} mm");
    // The bundled face, mirror-meshed, keeps its own triangles.
    let bundled = build_face_model(&orig, &PipelineParams::default(), &Control::new()).unwrap();
    assert_eq!(bundled.report.simplify_path, None);
    let (shell, which) = shell_asymmetry(&bundled);
    assert!(shell <= 0.01, "bundled {which}: {shell:.4}");
}

/// A face that is not symmetric in shape keeps its own triangles: the retriangulated face with
/// one cheek vertex pushed out by 2 % of the eye distance (1.3 mm) is simulated as it is.
#[test]
fn an_asymmetric_face_keeps_its_own_triangles() {
    let mut mesh = support::retriangulated(&load("mediapipe_canonical_4loop.obj"), 1);
    let lm_iod = {
        let loops = face_prep::topology::validate(&mesh.vertices, &mesh.triangles).unwrap();
        let (_, l) =
            face_prep::orient::canonical_frame(&mesh.vertices, &mesh.triangles, &loops).unwrap();
        let c = |lp: &[u32]| face_prep::orient::loop_centroid(&mesh.vertices, lp);
        c(&l.eye_l).distance(c(&l.eye_r))
    };
    // The vertex farthest out along +x (a cheek), pushed out along its own x.
    let v = (0..mesh.vertices.len())
        .max_by(|&a, &b| mesh.vertices[a].x.total_cmp(&mesh.vertices[b].x))
        .unwrap();
    mesh.vertices[v].z += 0.02 * lm_iod;
    let prepared = facebem::prepare(&mesh, &PipelineParams::default()).unwrap();
    assert_eq!(prepared.simplify_path, None);
    // Simulated on its own (peeled) triangles: every simulated vertex is an input vertex.
    let copy = prepared.simplified.expect("peeled copy");
    for (p, &v) in copy.vertices.iter().zip(&copy.original_vertex) {
        assert_eq!(*p, mesh.vertices[v as usize]);
    }
}

/// The ICT narrow face with a third of its edges flipped (13 120 triangles, above the size
/// threshold) is simplified as a mirrored half of its stand-in, by either copy method, and the
/// copy is mirror-meshed: every copy vertex has a mirror image among the copy's vertices
/// (canonical frame, 10⁻⁶ of the eye distance).
#[test]
fn a_large_retriangulated_face_is_simplified_from_its_stand_in() {
    let mesh = support::retriangulated(&load("ict_narrow_face_4loop.obj"), 1);
    for (method, path) in [
        (
            facebem::copy::CopyMethod::Collapse,
            SimplifyPath::SymmetrizedMirrored,
        ),
        (
            facebem::copy::CopyMethod::Remesh,
            SimplifyPath::RemeshedSymmetrized,
        ),
    ] {
        let mut params = PipelineParams::default();
        params.large_face.method = method;
        let prepared = facebem::prepare(&mesh, &params).unwrap();
        assert_eq!(prepared.simplify_path, Some(path));
        let copy = prepared.simplified.expect("a copy");
        assert!(copy.triangles.len() <= 1700, "{}", copy.triangles.len());
        let to_canonical = prepared.rig.canonical_from_input;
        let c: Vec<DVec3> = copy
            .vertices
            .iter()
            .map(|&p| to_canonical.transform_point3(p))
            .collect();
        let size = c.iter().map(|p| p.length()).fold(0.0, f64::max);
        let worst = c
            .iter()
            .map(|p| {
                let q = DVec3::new(-p.x, p.y, p.z);
                c.iter()
                    .map(|r| r.distance(q))
                    .fold(f64::INFINITY, f64::min)
            })
            .fold(0.0, f64::max);
        assert!(worst <= 1e-6 * size, "{path:?}: {worst:e} of {size}");
    }
}

/// Test face (a) of issue 30 as the issue names it: the ICT narrow face (13 120 triangles)
/// with about a third of its edges flipped, built on its stand-in and carried to its own
/// vertices. Its edge-collapse copy gives a near-singular rig (ratio 53: a long triangle under
/// the lower lids' shelf clamps the back face onto the front, `docs/journal.md`), so the rig
/// is built again on the remeshed copy, which is trusted and kept, saying so. Every paired
/// control mirrors within 5 % RMS at the vertices (0.4 %) and 1 mm at the mouth corners and
/// brows (0.002 mm); on the near-singular copy the pairs differed by 12 %.
#[test]
fn the_retriangulated_ict_face_gets_mirror_symmetric_responses() {
    let orig = load("ict_narrow_face_4loop.obj");
    let mesh = support::retriangulated(&orig, 1);
    let m = build_face_model(&mesh, &PipelineParams::default(), &Control::new()).unwrap();
    // The edge-collapse copy's rig is near-singular at the lower lids; the remeshed copy's is
    // trusted, and kept, saying so.
    assert_eq!(
        m.report.simplify_path,
        Some(SimplifyPath::RemeshedSymmetrized)
    );
    assert!(m.report.copy_fallback.is_some());
    let distrust = facebem::model::distrust(&m);
    assert!(distrust.is_empty(), "{distrust:?}");
    let (vertices, landmarks_mm, worst) = asymmetry(&m, &partners(&orig));
    eprintln!(
        "retriangulated ICT 13k: vertices {vertices:.4} ({worst}), landmarks {landmarks_mm:.3} mm"
    );
    assert!(vertices <= 0.05, "{worst}: {vertices:.4}");
    assert!(landmarks_mm <= 1.0, "{landmarks_mm:.3} mm");
}

/// Issue 30, item 3, on test face (a): the flipped MediaPipe face written differently (rotated
/// about a tilted axis, ×10 with its unit stated, moved, renumbered; `support::rewritten`) is
/// built on the same stand-in and makes the same expressions: every ARKit target within 2 % RMS
/// of its largest motion, the same near-singular ratio within 10 %.
#[test]
fn a_retriangulated_face_is_invariant_to_how_the_file_is_written() {
    let mesh = support::retriangulated(&load("mediapipe_canonical_4loop.obj"), 1);
    let base = build_face_model(&mesh, &PipelineParams::default(), &Control::new()).unwrap();
    let support::Rewritten {
        mesh: other_mesh,
        new_of_old,
        input_from_original,
    } = support::rewritten(&mesh);
    let mut params = PipelineParams::default();
    params.rig.units = face_prep::units::Units::Fixed(face_prep::units::LengthUnit::Scaled(
        base.rig.mm_per_unit() / 10.0,
    ));
    let other = build_face_model(&other_mesh, &params, &Control::new()).unwrap();
    assert_eq!(other.report.simplify_path, Some(SimplifyPath::Symmetrized));
    let ratio = other.report.response_amplification / base.report.response_amplification;
    assert!(
        (0.9..=1.1).contains(&ratio),
        "near-singular ratio {ratio:.3}"
    );
    let back = input_from_original.matrix3.inverse();
    let field = support::named_field;
    let mut worst = (0.0f64, "");
    for e in facebem::expressions::arkit::EXPRESSIONS {
        let a = field(&base, e.name);
        let b = field(&other, e.name);
        let largest = a.iter().map(|d| d.length()).fold(0.0, f64::max);
        if largest == 0.0 {
            continue;
        }
        let rms = (a
            .iter()
            .enumerate()
            .map(|(old, d)| (back * b[new_of_old[old] as usize] - *d).length_squared())
            .sum::<f64>()
            / a.len() as f64)
            .sqrt();
        if rms / largest > worst.0 {
            worst = (rms / largest, e.name);
        }
    }
    eprintln!(
        "flipped MediaPipe rewritten: worst ARKit target {:.2e} of its largest motion ({}), ratio {ratio:.4}",
        worst.0, worst.1
    );
    assert!(worst.0 <= 0.02, "{}: {:.4}", worst.1, worst.0);
}

/// MediaPipe's face with one more triangle on the outer contour of its left side (an "ear" of
/// one edge's length, in the face's plane there): symmetric in shape but for its outline, as a
/// cut through a head's triangles leaves it.
fn with_an_ear_on_the_outline() -> face_prep::FaceMesh {
    let face = load("mediapipe_canonical_4loop.obj");
    let (v, t) = (&face.vertices, &face.triangles);
    let loops = face_prep::topology::validate(v, t).unwrap();
    let outer = loops.iter().max_by_key(|l| l.len()).unwrap();
    let x_max = v.iter().map(|p| p.x).fold(f64::NEG_INFINITY, f64::max);
    // An outline edge well on the left (+x) side, and the triangle that holds it.
    let (tri, k) = t
        .iter()
        .enumerate()
        .flat_map(|(i, _)| (0..3).map(move |k| (i, k)))
        .find(|&(i, k)| {
            let (a, b) = (t[i][k], t[i][(k + 1) % 3]);
            let on = |x: u32| outer.contains(&x);
            on(a) && on(b) && v[a as usize].x > 0.5 * x_max && v[b as usize].x > 0.5 * x_max
        })
        .unwrap();
    let [a, b, c] = [t[tri][k], t[tri][(k + 1) % 3], t[tri][(k + 2) % 3]];
    let (pa, pb, pc) = (v[a as usize], v[b as usize], v[c as usize]);
    let mid = 0.5 * (pa + pb);
    let out = (mid - pc).normalize();
    let mut vertices = v.clone();
    vertices.push(mid + out * pa.distance(pb));
    let mut triangles = t.clone();
    triangles.push([b, a, (vertices.len() - 1) as u32]);
    face_prep::FaceMesh::from_triangles(&vertices, &triangles).unwrap()
}

/// Where a face's outline is a cut facebem made through a head's triangles
/// (`PipelineParams::outline_is_cut`, a head's front face), the outline is left out of the
/// mirror-symmetry test: the face with one triangle more on its left outline is built on its
/// mirror-meshed stand-in. As the user's own outline (the default), the same triangle is part
/// of the face's shape, and the face keeps its own triangles.
#[test]
fn a_cut_outline_is_not_the_faces_shape() {
    let mesh = with_an_ear_on_the_outline();
    let own = facebem::prepare(&mesh, &PipelineParams::default()).unwrap();
    assert_eq!(own.simplify_path, None);
    let cut = PipelineParams {
        outline_is_cut: true,
        ..PipelineParams::default()
    };
    let stand_in = facebem::prepare(&mesh, &cut).unwrap();
    assert_eq!(stand_in.simplify_path, Some(SimplifyPath::Symmetrized));
    // Its interior is still tested: a cheek vertex (inside the face, not on its outline)
    // pushed out keeps the face's own triangles.
    let mut pushed = mesh.clone();
    let loops = face_prep::topology::validate(&pushed.vertices, &pushed.triangles).unwrap();
    let on_loop: std::collections::HashSet<u32> = loops.iter().flatten().copied().collect();
    let x_max = pushed.vertices.iter().map(|p| p.x).fold(f64::MIN, f64::max);
    let v = (0..pushed.vertices.len() as u32)
        .filter(|v| !on_loop.contains(v))
        .min_by(|&a, &b| {
            let d = |v: u32| (pushed.vertices[v as usize].x - 0.8 * x_max).abs();
            d(a).total_cmp(&d(b))
        })
        .unwrap();
    // 1.2 % of the face's half-width: above 1 % of the eye distance, twice the tolerance.
    pushed.vertices[v as usize].z += 0.012 * x_max;
    let prepared = facebem::prepare(&pushed, &cut).unwrap();
    assert_eq!(prepared.simplify_path, None);
}
