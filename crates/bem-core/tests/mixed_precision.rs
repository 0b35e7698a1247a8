//! The mixed-precision solve ([`bem_core::Precision::Mixed`], the default) gives the f64 LU's
//! answer on a face-sized BEM system, and falls back to the f64 LU where its f32 copy of K
//! does not fit the memory budget.

use bem_core::{
    Control, LinearSystem, Loads, MIXED_MIN_UNKNOWNS, Material, MemoryEstimate, Precision,
    SolveParams, shapes,
};
use glam::DVec3;

/// A torus of about 1 400 elements (4 200 unknowns, above [`MIXED_MIN_UNKNOWNS`]), 30 % fixed,
/// three load cases driving the fixed elements.
fn system(params: &SolveParams) -> LinearSystem {
    let mesh = shapes::torus(1.0, 0.35, 38, 19).unwrap();
    let n = mesh.element_count();
    assert!(3 * n >= MIXED_MIN_UNKNOWNS, "{n} elements");
    let prescribed: Vec<bool> = mesh.centroids().iter().map(|c| c.x < -0.55).collect();
    let mut loads = Loads::new(n, 3);
    for (k, e) in (0..n).filter(|&e| prescribed[e]).enumerate() {
        loads
            .set(e, k % 3, DVec3::new(0.01, 0.005 * (k % 2) as f64, -0.002))
            .unwrap();
    }
    let material = Material::new(0.45, 1.0).unwrap();
    LinearSystem::assemble(
        &mesh,
        &material,
        &prescribed,
        &loads,
        params,
        &Control::default(),
    )
    .unwrap()
}

#[test]
fn mixed_and_double_precision_agree_on_a_bem_system() {
    let mixed = SolveParams::default();
    assert_eq!(mixed.precision, Precision::Mixed);
    let double = SolveParams {
        precision: Precision::Double,
        ..SolveParams::default()
    };
    let (a, report_a) = system(&mixed)
        .solve_with_report(&Control::default())
        .unwrap();
    let (b, report_b) = system(&double)
        .solve_with_report(&Control::default())
        .unwrap();
    assert_eq!(report_a.precision, Precision::Mixed);
    assert_eq!(report_b.precision, Precision::Double);
    let scale = b
        .iter()
        .flat_map(|s| s.displacement.iter().chain(&s.traction))
        .map(|v| v.abs().max_element())
        .fold(0.0f64, f64::max);
    let diff = a
        .iter()
        .zip(&b)
        .flat_map(|(x, y)| {
            x.displacement
                .iter()
                .zip(&y.displacement)
                .chain(x.traction.iter().zip(&y.traction))
        })
        .map(|(u, v)| (*u - *v).abs().max_element())
        .fold(0.0f64, f64::max);
    eprintln!("largest difference {:.1e} of {scale:.2e}", diff);
    assert!(scale > 0.0);
    assert!(diff < 1e-11 * scale, "differs by {diff:e} of {scale:e}");
    // The condition estimates agree within the estimator's accuracy.
    let ratio = report_a.condition_estimate / report_b.condition_estimate;
    assert!((ratio - 1.0).abs() < 0.01, "condition estimates {ratio}");
}

#[test]
fn mixed_precision_falls_back_where_its_f32_copy_does_not_fit() {
    let mesh_elements = shapes::torus(1.0, 0.35, 38, 19).unwrap().element_count();
    let size = 3 * mesh_elements;
    let threads = rayon::current_num_threads();
    let estimate = MemoryEstimate::new(mesh_elements, size, 3, threads);
    // Room for K in place, not for its f32 copy besides.
    let budget = estimate.total() + (estimate.with_f32_factor().total() - estimate.total()) / 2;
    let params = SolveParams {
        memory_budget_bytes: Some(budget),
        ..SolveParams::default()
    };
    let sys = system(&params);
    assert_eq!(sys.precision, Precision::Double);
    let (_, report) = sys.solve_with_report(&Control::default()).unwrap();
    assert_eq!(report.precision, Precision::Double);
}
