//! Near-singular off-diagonal blocks: a collocation point very close to an element (gap down to
//! 1e-4 of the element) and knife-edge wedges (down to 0.2°), against an independent brute-force
//! reference computed here.

#![allow(clippy::needless_range_loop)] // 3×3 block loops read better with indices

use bem_core::kernels::{Block, kelvin_t, kelvin_u};
use bem_core::quadrature::{TriangleIntegrals, triangle_integrals};
use bem_core::{
    BoundaryCondition, Control, LinearSystem, Loads, Material, QuadratureParams, SolveParams,
    SurfaceMesh, shapes,
};
use glam::DVec3;

/// Gauss–Legendre nodes and weights on [0, 1] (Newton on P_n).
fn gauss_legendre_01(n: usize) -> Vec<(f64, f64)> {
    let mut out = Vec::with_capacity(n);
    for i in 0..n {
        let mut x = (std::f64::consts::PI * (i as f64 + 0.75) / (n as f64 + 0.5)).cos();
        let mut dp = 1.0;
        for _ in 0..100 {
            let (mut p0, mut p1) = (1.0, x);
            for k in 2..=n {
                let p2 = ((2 * k - 1) as f64 * x * p1 - (k - 1) as f64 * p0) / k as f64;
                p0 = p1;
                p1 = p2;
            }
            dp = n as f64 * (x * p1 - p0) / (x * x - 1.0);
            let dx = p1 / dp;
            x -= dx;
            if dx.abs() < 1e-16 {
                break;
            }
        }
        let w = 2.0 / ((1.0 - x * x) * dp * dp);
        out.push((0.5 * (x + 1.0), 0.5 * w));
    }
    out
}

/// Breakpoints on [0, 1] graded geometrically (ratio 2) toward `at`, from `scale` outward.
fn graded(at: f64, scale: f64) -> Vec<f64> {
    let mut points = vec![0.0, 1.0, at];
    let mut s = scale.max(1e-14);
    while s < 1.0 {
        for x in [at - s, at + s] {
            if x > 0.0 && x < 1.0 {
                points.push(x);
            }
        }
        s *= 2.0;
    }
    points.sort_by(f64::total_cmp);
    points.dedup_by(|a, b| (*a - *b).abs() < 1e-15);
    points
}

/// Brute-force `(∫T, ∫U)` over the triangle for load point `p`: the triangle is split at the
/// projection `f` of `p` into three signed triangles (f, a, b), each mapped to the unit square by
/// `q = f + u ((a − f) + v (b − a))` (Jacobian ∝ u, which removes the near-singularity's
/// area factor), and integrated with `order`-point Gauss–Legendre on panels graded
/// geometrically toward u = 0 (scale gap / edge distance) and toward the foot of f on the side
/// (scale: distance from f to the side's line), evaluating the Kelvin kernels point by point.
fn reference(c: [DVec3; 3], p: DVec3, m: &Material, order: usize) -> (Block, Block) {
    let gl = gauss_legendre_01(order);
    let normal = (c[1] - c[0]).cross(c[2] - c[0]).normalize();
    let gap = (p - c[0]).dot(normal);
    let f = p - gap * normal;
    let mut h = [[0.0; 3]; 3];
    let mut g = [[0.0; 3]; 3];
    for k in 0..3 {
        let (a, b) = (c[k], c[(k + 1) % 3]);
        let twice_area = (a - f).cross(b - f).dot(normal); // signed
        let side = b - a;
        let len2 = side.length_squared();
        let foot = ((f - a).dot(side) / len2).clamp(0.0, 1.0);
        let height = (twice_area / len2.sqrt()).abs();
        if height < 1e-15 * len2.sqrt() {
            continue; // f on this side's line: the signed triangle has no area
        }
        let far = (a - f).length().max((b - f).length());
        let us = graded(0.0, 0.25 * gap.abs().max(1e-300) / far);
        let vs = graded(foot, 0.25 * height / len2.sqrt());
        for uw in us.windows(2) {
            for vw in vs.windows(2) {
                let (du, dv) = (uw[1] - uw[0], vw[1] - vw[0]);
                for &(x, wx) in &gl {
                    let u = uw[0] + du * x;
                    for &(y, wy) in &gl {
                        let v = vw[0] + dv * y;
                        let q = f + u * ((a - f) + v * side);
                        let w = wx * du * wy * dv * u * twice_area;
                        let t = kelvin_t(q - p, normal, m);
                        let uu = kelvin_u(q - p, m);
                        for i in 0..3 {
                            for j in 0..3 {
                                h[i][j] += w * t[i][j];
                                g[i][j] += w * uu[i][j];
                            }
                        }
                    }
                }
            }
        }
    }
    (h, g)
}

fn rel_diff(a: &Block, b: &Block) -> f64 {
    let mut num = 0.0;
    let mut den = 0.0;
    for i in 0..3 {
        for j in 0..3 {
            num += (a[i][j] - b[i][j]).powi(2);
            den += b[i][j].powi(2);
        }
    }
    (num / den).sqrt()
}

/// Checks one block against the reference (which must itself be converged); returns the errors.
fn check(c: [DVec3; 3], p: DVec3, params: &QuadratureParams, what: &str) -> (f64, f64, f64) {
    let m = Material::new(0.45, 1.0).expect("material");
    let (h_ref, g_ref) = reference(c, p, &m, 12);
    let (h_fine, g_fine) = reference(c, p, &m, 20);
    let self_check = rel_diff(&h_ref, &h_fine).max(rel_diff(&g_ref, &g_fine));
    assert!(
        self_check < 1e-9,
        "{what}: reference not converged ({self_check:e})"
    );
    let TriangleIntegrals {
        h,
        g,
        estimated_error,
    } = triangle_integrals(c, p, &m, params).expect("valid triangle");
    let (eh, eg) = (rel_diff(&h, &h_fine), rel_diff(&g, &g_fine));
    eprintln!("{what}: H {eh:.2e} G {eg:.2e} (estimate {estimated_error:.1e})");
    (eh, eg, estimated_error)
}

/// A scalene triangle in a general orientation, longest edge 1.3.
fn scalene() -> [DVec3; 3] {
    let e1 = DVec3::new(0.8, 0.36, -0.48).normalize();
    let e2 = e1.cross(DVec3::new(0.1, 0.9, 0.3)).normalize();
    let o = DVec3::new(0.3, -1.2, 2.0);
    [[0.0, 0.0], [1.3, 0.0], [0.4, 0.9]].map(|[x, y]| o + x * e1 + y * e2)
}

#[test]
fn blocks_stay_within_1e_minus_4_down_to_a_gap_of_1e_minus_4_of_the_element() {
    let c = scalene();
    let n = (c[1] - c[0]).cross(c[2] - c[0]).normalize();
    let longest = 1.3;
    let centroid = (c[0] + c[1] + c[2]) / 3.0;
    let near_edge = 0.49 * (c[0] + c[1]) + 0.02 * c[2]; // just inside side 0-1
    let near_vertex = 0.96 * c[2] + 0.02 * (c[0] + c[1]);
    let beyond_edge = 0.5 * (c[0] + c[1]) - 0.05 * (c[2] - 0.5 * (c[0] + c[1])); // outside
    let params = QuadratureParams::default();
    for (name, at) in [
        ("centroid", centroid),
        ("near an edge", near_edge),
        ("near a vertex", near_vertex),
        ("beyond an edge", beyond_edge),
    ] {
        for gap in [1e-1, 1e-2, 1e-3, 1e-4] {
            for side in [1.0, -1.0] {
                let p = at + side * gap * longest * n;
                let what = format!("{name}, gap {gap:e} ({side:+})");
                let (eh, eg, estimate) = check(c, p, &params, &what);
                assert!(eh <= 1e-4 && eg <= 1e-4, "{what}: H {eh:e} G {eg:e}");
                assert!(
                    estimate <= params.tolerance,
                    "{what}: estimate {estimate:e}"
                );
            }
        }
    }
}

/// The test can fail: with the former fixed depth cap of 8 the same blocks are far off (the
/// issue measured 2.3 % at a gap of 1.6e-3 and 1400 % at 1.6e-4).
#[test]
fn the_former_depth_cap_of_8_fails_the_same_blocks() {
    let c = scalene();
    let n = (c[1] - c[0]).cross(c[2] - c[0]).normalize();
    let centroid = (c[0] + c[1] + c[2]) / 3.0;
    let capped = QuadratureParams {
        max_depth: 8,
        tolerance: 1e-12, // depth limited by the cap alone
        ..QuadratureParams::default()
    };
    let (eh, eg, estimate) = check(c, centroid + 1e-4 * 1.3 * n, &capped, "cap 8, gap 1e-4");
    assert!(eh.max(eg) > 1e-2, "H {eh:e} G {eg:e}");
    // and the estimate knows it
    assert!(estimate > 1e-2, "estimate {estimate:e}");
}

/// Two triangles sharing an edge and folded to a dihedral angle `angle` (a knife edge: the
/// shell's front and back meet like this at every eye and mouth contour).
fn wedge(angle_deg: f64) -> ([DVec3; 3], [DVec3; 3]) {
    let t = angle_deg.to_radians();
    let (a, b) = (DVec3::ZERO, DVec3::new(1.0, 0.0, 0.0));
    let top = DVec3::new(0.4, 0.9, 0.0);
    let folded = DVec3::new(0.55, 0.85 * t.cos(), 0.85 * t.sin());
    // opposite orientations, like the two faces of a thin solid
    ([a, b, top], [b, a, folded])
}

#[test]
fn knife_edge_wedges_stay_within_1e_minus_4_down_to_0_2_degrees() {
    let params = QuadratureParams::default();
    for angle in [10.0, 2.0, 1.0, 0.5, 0.2] {
        let (front, back) = wedge(angle);
        for (name, from, to) in [("front→back", front, back), ("back→front", back, front)] {
            let p = (from[0] + from[1] + from[2]) / 3.0;
            let what = format!("wedge {angle}°, {name}");
            let (eh, eg, estimate) = check(to, p, &params, &what);
            assert!(eh <= 1e-4 && eg <= 1e-4, "{what}: H {eh:e} G {eg:e}");
            assert!(
                estimate <= params.tolerance,
                "{what}: estimate {estimate:e}"
            );
        }
    }
}

/// Surfaces closer than the tolerance resolves are reported by the assembly, with the worst
/// pair, instead of silently returning a wrong block: a thin shell of two spheres 1e-6 apart.
#[test]
fn assembly_reports_unconverged_blocks_with_the_worst_pair() {
    let m = Material::new(0.45, 1.0).expect("material");
    let healthy = shapes::hollow_sphere(1.0, 1.1, 1).expect("valid");
    let n = healthy.element_count();
    let prescribed: Vec<bool> = (0..n).map(|e| e < n / 2).collect();
    let mut loads = Loads::new(n, 1);
    loads.set(0, 0, DVec3::X * 0.01).expect("set");
    let control = Control::default();
    let params = SolveParams::default();
    let system = LinearSystem::assemble(&healthy, &m, &prescribed, &loads, &params, &control)
        .expect("assemble");
    assert_eq!(system.quadrature.unconverged_blocks, 0);
    assert_eq!(system.quadrature.worst, None);

    // the same shell 1e-7 thick: every inner element sees an outer one at 1e-7 of its size
    let thin = shapes::hollow_sphere(1.0, 1.0 + 1e-7, 1).expect("valid");
    let system = LinearSystem::assemble(&thin, &m, &prescribed, &loads, &params, &control)
        .expect("assemble");
    let report = system.quadrature;
    eprintln!("shell 1e-7 thick: {report:?}");
    assert!(report.unconverged_blocks >= n, "{report:?}");
    let worst = report.worst.expect("a worst pair");
    assert!(worst.estimated_error > params.quadrature.tolerance);
    // front and back partners: the pair is an inner and an outer element
    assert!(
        (worst.row_element < n / 2) != (worst.column_element < n / 2),
        "{worst:?}"
    );
    // and the solve carries it in its report (the condition limit lifted: such a shell is
    // near-singular too)
    let mut system = system;
    system.max_condition = f64::INFINITY;
    let (_, solve_report) = system.solve_with_report(&control).expect("solve");
    assert_eq!(solve_report.quadrature, report);
}

/// The bundled-style wedge as a closed solid (a thin triangular prism tapering to a knife edge)
/// assembles and solves with its blocks converged: the knife-edge pairs no longer hit a cap.
#[test]
fn knife_edge_solid_assembles_without_unconverged_blocks() {
    // a flat tetrahedron: base triangle and an apex 0.005 above it (sharp edges all round)
    let v = vec![
        DVec3::new(0.0, 0.0, 0.0),
        DVec3::new(1.0, 0.0, 0.0),
        DVec3::new(0.3, 0.9, 0.0),
        DVec3::new(0.45, 0.3, 0.005),
    ];
    let t = vec![[0, 2, 1], [0, 1, 3], [1, 2, 3], [2, 0, 3]];
    let mesh = SurfaceMesh::new(v, t).expect("valid");
    let m = Material::new(0.45, 1.0).expect("material");
    let bcs = [
        BoundaryCondition::Displacement(DVec3::ZERO),
        BoundaryCondition::Traction(DVec3::new(0.0, 0.0, 0.01)),
        BoundaryCondition::FREE,
        BoundaryCondition::FREE,
    ];
    let prescribed: Vec<bool> = bcs.iter().map(|b| b.is_displacement()).collect();
    let mut loads = Loads::new(4, 1);
    for (e, b) in bcs.iter().enumerate() {
        loads.set(e, 0, b.value()).expect("set");
    }
    let system = LinearSystem::assemble(
        &mesh,
        &m,
        &prescribed,
        &loads,
        &SolveParams::default(),
        &Control::default(),
    )
    .expect("assemble");
    assert_eq!(
        system.quadrature.unconverged_blocks, 0,
        "{:?}",
        system.quadrature
    );
}
