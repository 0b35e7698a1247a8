//! Prints per-muscle diagnostics of one face (chains, mouth-corner and brow responses on the
//! simulated shell, the element where each response peaks and how thin the tissue is there):
//! `cargo run --release -p facebem-tools --bin inspect_face -- assets/face.obj`.

use face_prep::{ElementTag, MuscleKind};
use facebem::{Control, PipelineParams, build_face_model};

fn main() -> anyhow::Result<()> {
    let path = std::env::args()
        .nth(1)
        .ok_or_else(|| anyhow::anyhow!("usage: inspect_face FACE"))?;
    let (mesh, _) = facebem::input::read_face(path.as_ref())?;
    let mut params = PipelineParams::default();
    if let Some(n) = std::env::args().nth(2) {
        params.large_face.max_triangles = n.parse()?;
        params.large_face.target_triangles = n.parse()?;
    }
    if let Ok(e) = std::env::var("MAX_ERROR") {
        params.large_face.max_error = e.parse()?;
    }
    let prepared = facebem::prepare(&mesh, &params)?;
    print_copy_health(&prepared);
    if std::env::args().nth(3).is_some() {
        return Ok(());
    }
    let m = build_face_model(&mesh, &params, &Control::new())?;
    let rig = &m.rig;
    println!("face size {:.3}, boxes {:?}", rig.face_size, rig.boxes);
    let mouth: Vec<usize> = rig.loops.mouth.iter().map(|&v| v as usize).collect();
    let sv = &rig.shell.vertices;
    let left = *mouth
        .iter()
        .max_by(|&&a, &&b| sv[a].x.total_cmp(&sv[b].x))
        .unwrap();
    let right = *mouth
        .iter()
        .min_by(|&&a, &&b| sv[a].x.total_cmp(&sv[b].x))
        .unwrap();
    println!("mouth corners: left {:.3} right {:.3}", sv[left], sv[right]);
    for (k, mu) in rig.muscles.iter().enumerate() {
        let c: Vec<String> = mu
            .front_chain
            .iter()
            .map(|&e| format!("{:.2}", rig.shell.centroid(e as usize).truncate()))
            .collect();
        println!("{} front chain: {}", mu.name, c.join(" "));
        let f = &m.shell_vertex_response[k];
        println!(
            "   contract: left corner {:.4}, right corner {:.4}",
            -f[left], -f[right]
        );
        print_peak(&m, k);
    }
    let thin = (0..rig.shell.element_count())
        .filter(|&e| rig.shell.tags[e] == ElementTag::Front && gap_ratio(&rig.shell, e) < 0.1)
        .count();
    println!("front elements with gap ratio below 0.1: {thin}");
    let _ = MuscleKind::ALL;
    Ok(())
}

/// Distance from element `e`'s centroid to the nearest centroid of the other side of the shell
/// (front ↔ back), over the square root of `e`'s area: how thin the tissue is at `e` relative
/// to the element size. Infinite for rim elements.
fn gap_ratio(shell: &face_prep::Shell, e: usize) -> f64 {
    let other = match shell.tags[e] {
        ElementTag::Front => ElementTag::Back,
        ElementTag::Back => ElementTag::Front,
        // The rim, and any other kind of element: no other side.
        _ => return f64::INFINITY,
    };
    let c = shell.centroid(e);
    let [a, b, d] = shell.corners(e);
    let area = 0.5 * (b - a).cross(d - a).length();
    let nearest = (0..shell.element_count())
        .filter(|&j| shell.tags[j] == other)
        .map(|j| shell.centroid(j).distance(c))
        .fold(f64::INFINITY, f64::min);
    nearest / area.sqrt().max(f64::MIN_POSITIVE)
}

/// The element on the other side of the shell (front ↔ back) whose centroid is nearest to `e`'s.
fn nearest_other(shell: &face_prep::Shell, e: usize) -> Option<usize> {
    let other = match shell.tags[e] {
        ElementTag::Front => ElementTag::Back,
        ElementTag::Back => ElementTag::Front,
        // The rim, and any other kind of element: no other side.
        _ => return None,
    };
    let c = shell.centroid(e);
    (0..shell.element_count())
        .filter(|&j| shell.tags[j] == other)
        .min_by(|&a, &b| {
            shell
                .centroid(a)
                .distance(c)
                .total_cmp(&shell.centroid(b).distance(c))
        })
}

/// The simulated copy's health: shell self-intersections and the worst front triangle.
fn print_copy_health(prepared: &facebem::PreparedRig) {
    let si = prepared.rig.shell.self_intersections();
    println!(
        "simulated {} triangles, shell self-intersections: {} {:?}",
        prepared.simulated.triangles.len(),
        si.len(),
        &si[..si.len().min(10)]
    );
    for pair in si.iter().take(6) {
        let c: Vec<String> = pair
            .iter()
            .map(|&e| {
                format!(
                    "{} {:?} {:.2}",
                    e,
                    prepared.rig.shell.tags[e as usize],
                    prepared.rig.shell.centroid(e as usize)
                )
            })
            .collect();
        println!("  intersecting: {}", c.join(" x "));
    }
    let worst = prepared
        .simulated
        .triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| prepared.simulated.vertices[i as usize]);
            let area2 = (b - a).cross(c - a).length();
            let l2 = (b - a)
                .length_squared()
                .max((c - b).length_squared())
                .max((a - c).length_squared());
            area2 / l2
        })
        .fold(f64::INFINITY, f64::min);
    println!("worst front triangle 2*area/longest^2 = {worst:.2e}");
    print_short_edges(&prepared.simulated);
}

/// The copy's eight shortest edges against its median edge, and whether their ends lie on a
/// contour (a short edge at a knife edge gives a small back element against the front).
fn print_short_edges(sim: &face_prep::FaceMesh) {
    let mut edges: Vec<(f64, u32, u32)> = Vec::new();
    for t in &sim.triangles {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            if a < b {
                edges.push((
                    sim.vertices[a as usize].distance(sim.vertices[b as usize]),
                    a,
                    b,
                ));
            }
        }
    }
    edges.sort_by(|x, y| x.0.total_cmp(&y.0));
    let Some(&(median, _, _)) = edges.get(edges.len() / 2) else {
        return;
    };
    let mut uses = std::collections::HashMap::new();
    for t in &sim.triangles {
        for k in 0..3 {
            let (a, b) = (t[k].min(t[(k + 1) % 3]), t[k].max(t[(k + 1) % 3]));
            *uses.entry((a, b)).or_insert(0) += 1;
        }
    }
    let mut border = vec![false; sim.vertices.len()];
    for ((a, b), n) in uses {
        if n == 1 {
            border[a as usize] = true;
            border[b as usize] = true;
        }
    }
    for e in edges.iter().take(8) {
        println!(
            "short edge {:.4} ({:.3} of median {:.3}) {}-{} border {} {} at {:.2}",
            e.0,
            e.0 / median,
            median,
            e.1,
            e.2,
            border[e.1 as usize],
            border[e.2 as usize],
            sim.vertices[e.1 as usize]
        );
    }
}

/// Where control `k`'s response peaks on the shell and what the peak sits against.
fn print_peak(m: &facebem::FaceModel, k: usize) {
    let rig = &m.rig;
    // Where the response peaks, and how thin the tissue is there: near-singular solves
    // peak at front/back pairs that nearly coincide (gap ratio well below 0.1).
    let (e, u) = m.shell_element_response[k]
        .iter()
        .enumerate()
        .map(|(e, u)| (e, u.length()))
        .fold((0, 0.0f64), |a, b| if b.1 > a.1 { b } else { a });
    println!(
        "   largest element response {u:.3} at element {e} ({:?}, centroid {:.2}), gap ratio {:.3}",
        rig.shell.tags[e],
        rig.shell.centroid(e),
        gap_ratio(&rig.shell, e)
    );
    // What the peak sits against: the nearest element across the shell and, for a back
    // element, how deep its vertices lie below its front triangle (thin tissue, knife edges).
    if let Some(j) = nearest_other(&rig.shell, e) {
        let n = |e: usize| {
            let [a, b, d] = rig.shell.corners(e);
            (b - a).cross(d - a)
        };
        println!(
            "   nearest other-side element {j} (centroid {:.2}, area {:.4} vs {:.4}), normals' cos {:.3}",
            rig.shell.centroid(j),
            0.5 * n(j).length(),
            0.5 * n(e).length(),
            n(e).normalize().dot(n(j).normalize())
        );
        if rig.shell.tags[e] == ElementTag::Back {
            let src = rig.shell.source_triangle[e] as usize;
            let ft = rig.shell.triangles[src];
            let bt = rig.shell.triangles[e];
            let thick: Vec<String> = bt
                .iter()
                .map(|&b| {
                    let d = ft
                        .iter()
                        .map(|&f| {
                            rig.shell.vertices[f as usize].distance(rig.shell.vertices[b as usize])
                        })
                        .fold(f64::INFINITY, f64::min);
                    format!("v{b}:{d:.4}")
                })
                .collect();
            println!(
                "   source front {src} {ft:?}, back vertices' distance to it: {}",
                thick.join(" ")
            );
        }
    }
}
