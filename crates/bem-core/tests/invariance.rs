//! Translating or scaling a problem changes nothing: every tolerance in bem-core is relative to
//! the element size, and the assembly works relative to the mesh's own centre.

use bem_core::{
    BoundaryCondition, Control, Material, RigidModes, Solution, SolveParams, SurfaceMesh, shapes,
    solve,
};
use glam::DVec3;

/// A sheared, squashed icosphere (scalene elements), its vertices rounded to multiples of 2⁻²⁸
/// so that adding a translation of 1e7 is exact: the translated problem is then the same problem,
/// and any difference in the solution comes from bem-core, not from rounding of the input.
/// (Unrounded, the translation itself moves the vertices by up to 1e-9, about 4e-9 of an element.)
fn base_vertices() -> (Vec<DVec3>, Vec<[u32; 3]>) {
    let (v, t) = shapes::icosphere(2, 1.0);
    let grid = 2f64.powi(28);
    let v = v
        .into_iter()
        .map(|p| DVec3::new(1.4 * p.x + 0.3 * p.y, 0.8 * p.y, 0.6 * p.z + 0.2 * p.x))
        .map(|p| (p * grid).round() / grid)
        .collect();
    (v, t)
}

const TRANSLATION: DVec3 = DVec3::new(1e7, -1e7, 1e7);

/// Mixed problem on `mesh` whose geometry is `scale` × the base mesh (plus any translation):
/// lower part displacement-prescribed (a field proportional to the scale), upper part loaded by
/// tractions (scale-free), so that u/scale and t are the same for every scale.
fn mixed_bcs(base: &SurfaceMesh, scale: f64) -> Vec<BoundaryCondition> {
    (0..base.element_count())
        .map(|e| {
            let c = base.centroid(e);
            if c.z < 0.0 {
                BoundaryCondition::Displacement(
                    scale * 1e-2 * DVec3::new(c.y + 0.3 * c.z, -c.x, 0.5 * c.z),
                )
            } else {
                BoundaryCondition::Traction(1e-2 * (1.0 + c.x) * base.normal(e))
            }
        })
        .collect()
}

/// max |a − b| / max |b| over the elements.
fn rel(a: &[DVec3], b: &[DVec3]) -> f64 {
    let num = a
        .iter()
        .zip(b)
        .map(|(x, y)| (*x - *y).length())
        .fold(0.0, f64::max);
    let den = b.iter().map(|y| y.length()).fold(0.0, f64::max);
    num / den
}

fn solve_mixed(mesh: &SurfaceMesh, bcs: &[BoundaryCondition], params: &SolveParams) -> Solution {
    let m = Material::new(0.45, 1.0).expect("material");
    solve(mesh, &m, bcs, params, &Control::default()).expect("solve")
}

fn scaled(s: &Solution, scale: f64) -> Vec<DVec3> {
    s.displacement.iter().map(|u| *u / scale).collect()
}

/// Regression (issue 14): a unit sphere translated by 1e7 failed with an internal error (the
/// analytic diagonal block's absolute in-plane tolerance met the centroid's rounding at 1e7).
#[test]
fn translation_by_1e7_and_scaling_by_1e6_or_1e_minus_6_give_the_same_solution() {
    let (v, t) = base_vertices();
    let base = SurfaceMesh::new(v.clone(), t.clone()).expect("valid mesh");
    let params = SolveParams::default();
    let reference = solve_mixed(&base, &mixed_bcs(&base, 1.0), &params);

    // translated: exact input, so the element geometry is bit-identical after recentring
    let moved: Vec<DVec3> = v.iter().map(|p| *p + TRANSLATION).collect();
    assert!(
        moved.iter().zip(&v).all(|(m, p)| *m - TRANSLATION == *p),
        "the test's translation must be exact"
    );
    let translated = SurfaceMesh::new(moved, t.clone()).expect("translated mesh is valid");
    let rel_volume = (translated.volume() - base.volume()).abs() / base.volume();
    assert!(rel_volume < 1e-12, "volume changed by {rel_volume:e}");
    let s = solve_mixed(&translated, &mixed_bcs(&base, 1.0), &params);
    let (du, dt) = (
        rel(&s.displacement, &reference.displacement),
        rel(&s.traction, &reference.traction),
    );
    eprintln!("translated by 1e7: u {du:.2e}, t {dt:.2e}");
    assert!(du <= 1e-9 && dt <= 1e-9, "translation: u {du:e}, t {dt:e}");

    for scale in [1e-6, 1e6] {
        let mesh = SurfaceMesh::new(v.iter().map(|p| *p * scale).collect(), t.clone())
            .expect("scaled mesh is valid");
        let s = solve_mixed(&mesh, &mixed_bcs(&base, scale), &params);
        let (du, dt) = (
            rel(&scaled(&s, scale), &reference.displacement),
            rel(&s.traction, &reference.traction),
        );
        eprintln!("scaled by {scale:e}: u {du:.2e}, t {dt:.2e}");
        assert!(
            du <= 1e-9 && dt <= 1e-9,
            "scale {scale:e}: u {du:e}, t {dt:e}"
        );
    }
}

/// The gauge-fixed pure-traction problem (rigid modes about the area centroid) is translation
/// invariant too: pressure inside a hollow sphere, moved by 1e7.
#[test]
fn gauge_fixed_pressure_problem_is_translation_invariant() {
    let base = shapes::hollow_sphere(1.0, 2.0, 1).expect("valid mesh");
    let grid = 2f64.powi(28);
    let v: Vec<DVec3> = base
        .vertices()
        .iter()
        .map(|p| (*p * grid).round() / grid)
        .collect();
    let t = base.triangles().to_vec();
    let base = SurfaceMesh::new(v.clone(), t.clone()).expect("valid mesh");
    let half = base.element_count() / 2;
    let bcs: Vec<BoundaryCondition> = (0..base.element_count())
        .map(|e| {
            if e < half {
                BoundaryCondition::Traction(0.1 * base.normal(e))
            } else {
                BoundaryCondition::FREE
            }
        })
        .collect();
    let params = SolveParams {
        rigid_modes: RigidModes::Fix,
        ..SolveParams::default()
    };
    let reference = solve_mixed(&base, &bcs, &params);
    let moved = SurfaceMesh::new(v.iter().map(|p| *p + TRANSLATION).collect(), t)
        .expect("translated mesh is valid");
    let s = solve_mixed(&moved, &bcs, &params);
    let du = rel(&s.displacement, &reference.displacement);
    eprintln!("gauge-fixed, translated by 1e7: u {du:.2e}");
    assert!(du <= 1e-9, "u {du:e}");
}

/// Without exact input the translation itself rounds the vertices by ~1e-9: the solution then
/// differs by about that much relative to the element size, not more (no internal error, no
/// absolute tolerance tripping).
#[test]
fn unrounded_translation_by_1e7_only_costs_the_input_rounding() {
    let (v, t) = shapes::icosphere(2, 1.0);
    let base = SurfaceMesh::new(v.clone(), t.clone()).expect("valid mesh");
    let reference = solve_mixed(&base, &mixed_bcs(&base, 1.0), &SolveParams::default());
    let moved = SurfaceMesh::new(v.iter().map(|p| *p + TRANSLATION).collect(), t)
        .expect("translated mesh is valid");
    let s = solve_mixed(&moved, &mixed_bcs(&base, 1.0), &SolveParams::default());
    let du = rel(&s.displacement, &reference.displacement);
    let dt = rel(&s.traction, &reference.traction);
    eprintln!("unrounded translation by 1e7: u {du:.2e}, t {dt:.2e}");
    assert!(du < 1e-6 && dt < 1e-6, "u {du:e}, t {dt:e}");
}
