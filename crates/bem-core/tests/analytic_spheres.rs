//! Hollow and solid spheres against closed-form elasticity solutions (the accuracy table in `docs/design/solve.md`).

use bem_core::{
    BoundaryCondition, Control, Material, RigidModes, SolveParams, SurfaceMesh, shapes, solve,
};
use glam::DVec3;

/// Radial displacement `u(r) = A r + B / r²` of a spherically symmetric field.
#[derive(Clone, Copy)]
struct Radial {
    a: f64,
    b: f64,
}

impl Radial {
    fn at(&self, r: f64) -> f64 {
        self.a * r + self.b / (r * r)
    }
}

/// Hollow sphere a < r < b, u(a) = ua prescribed, traction-free at b.
fn mixed_exact(a: f64, b: f64, ua: f64, m: &Material) -> Radial {
    let nu = m.poisson();
    // σ_rr(b) = 0  ⇒  B = A b³ (1+ν) / (2 (1−2ν))
    let k = b.powi(3) * (1.0 + nu) / (2.0 * (1.0 - 2.0 * nu));
    let aa = ua / (a + k / (a * a));
    Radial { a: aa, b: aa * k }
}

/// Lamé: internal pressure p at a, traction-free at b.
fn lame_exact(a: f64, b: f64, p: f64, m: &Material) -> Radial {
    let mu = m.shear_modulus();
    let three_k = 3.0 * m.lambda() + 2.0 * mu;
    let d = b.powi(3) - a.powi(3);
    Radial {
        a: p * a.powi(3) / (three_k * d),
        b: p * a.powi(3) * b.powi(3) / (4.0 * mu * d),
    }
}

/// Mean relative radial displacement error over elements `range` against the exact field at the
/// nominal radius `r` of that surface (the convention of the figures of `docs/design/solve.md`: comparing at the
/// centroid radius instead adds the polyhedral inset, ≈ 1.2% on the inner sphere at 640 elements).
fn mean_radial_error(
    mesh: &SurfaceMesh,
    u: &[DVec3],
    exact: Radial,
    r: f64,
    range: std::ops::Range<usize>,
) -> f64 {
    let count = range.len() as f64;
    let ex = exact.at(r);
    range
        .map(|e| {
            let ur = u[e].dot(mesh.centroid(e).normalize());
            ((ur - ex) / ex).abs()
        })
        .sum::<f64>()
        / count
}

/// Mixed hollow-sphere problem; returns the outer mean radial error.
fn mixed_outer_error(inner: f64, outer: f64, subdivisions: u32, nu: f64) -> f64 {
    let mesh = shapes::hollow_sphere(inner, outer, subdivisions).expect("valid sphere");
    let m = Material::from_young(1.0, nu).expect("valid material");
    let n = mesh.element_count();
    let half = n / 2;
    let ua = 0.01;
    let exact = mixed_exact(inner, outer, ua, &m);
    let bcs: Vec<BoundaryCondition> = (0..n)
        .map(|e| {
            if e < half {
                BoundaryCondition::Displacement(ua * mesh.centroid(e).normalize())
            } else {
                BoundaryCondition::FREE
            }
        })
        .collect();
    let s = solve(
        &mesh,
        &m,
        &bcs,
        &SolveParams::default(),
        &Control::default(),
    )
    .expect("solve");
    let err = mean_radial_error(&mesh, &s.displacement, exact, outer, half..n);
    eprintln!("mixed a={inner} b={outer} N={n} nu={nu}: outer mean radial error {err:.4e}");
    err
}

#[test]
fn hollow_sphere_mixed_nu_045_within_design_figures_and_converges() {
    let coarse = mixed_outer_error(1.0, 2.0, 2, 0.45);
    let fine = mixed_outer_error(1.0, 2.0, 3, 0.45);
    assert!(
        coarse <= 1.2 * 0.008,
        "640 elements: {coarse:e} > 1.2 × 0.8%"
    );
    assert!(
        fine <= 1.2 * 0.0045,
        "2560 elements: {fine:e} > 1.2 × 0.45%"
    );
    assert!(
        fine < coarse,
        "error must decrease under refinement: {coarse:e} -> {fine:e}"
    );
}

#[test]
fn hollow_sphere_mixed_nu_049_below_one_percent_and_converges() {
    let coarse = mixed_outer_error(1.0, 2.0, 2, 0.49);
    let fine = mixed_outer_error(1.0, 2.0, 3, 0.49);
    assert!(coarse <= 1.2 * 0.01, "640 elements: {coarse:e} > 1.2 × 1%");
    assert!(fine <= 1.2 * 0.01, "2560 elements: {fine:e} > 1.2 × 1%");
    assert!(
        fine < coarse,
        "error must decrease under refinement: {coarse:e} -> {fine:e}"
    );
}

#[test]
fn hollow_sphere_mixed_nu_03_converges_at_rate_one() {
    // `docs/design/solve.md` gives no ν = 0.3 figure for the mixed problem (measured: 3.5% at 640, 1.7% at
    // 2560). Held to its convergence statement instead: rate ≥ 1 in h (h halves from 640
    // to 2560 elements), and to a 5% sanity bound at 640.
    let coarse = mixed_outer_error(1.0, 2.0, 2, 0.3);
    let fine = mixed_outer_error(1.0, 2.0, 3, 0.3);
    assert!(coarse <= 0.05, "640 elements: {coarse:e}");
    assert!(
        fine <= 0.55 * coarse,
        "rate < 1 in h: {coarse:e} -> {fine:e}"
    );
}

#[test]
fn thin_shell_mixed_within_twice_thick_shell_figures() {
    // b/a = 1.1: the shell is about as thick as one element is wide (what the face shell needs)
    let coarse = mixed_outer_error(1.0, 1.1, 2, 0.45);
    let fine = mixed_outer_error(1.0, 1.1, 3, 0.45);
    assert!(coarse <= 2.0 * 0.008, "640 elements: {coarse:e} > 2 × 0.8%");
    assert!(fine <= 2.0 * 0.0045, "2560 elements: {fine:e} > 2 × 0.45%");
}

/// Lamé internal pressure, pure traction with the rigid modes fixed; returns (inner, outer) errors.
fn lame_errors(subdivisions: u32) -> (f64, f64) {
    let mesh = shapes::hollow_sphere(1.0, 2.0, subdivisions).expect("valid sphere");
    let m = Material::from_young(1.0, 0.3).expect("valid material");
    let n = mesh.element_count();
    let half = n / 2;
    let p = 0.01;
    let bcs: Vec<BoundaryCondition> = (0..n)
        .map(|e| {
            if e < half {
                // outward normal of the body points to the centre; t = σ n = p r̂
                BoundaryCondition::Traction(-p * mesh.normal(e))
            } else {
                BoundaryCondition::FREE
            }
        })
        .collect();
    let params = SolveParams {
        rigid_modes: RigidModes::Fix,
        ..SolveParams::default()
    };
    let s = solve(&mesh, &m, &bcs, &params, &Control::default()).expect("solve");
    let exact = lame_exact(1.0, 2.0, p, &m);
    let inner = mean_radial_error(&mesh, &s.displacement, exact, 1.0, 0..half);
    let outer = mean_radial_error(&mesh, &s.displacement, exact, 2.0, half..n);
    eprintln!("Lamé N={n}: inner {inner:.4e} outer {outer:.4e}");
    (inner, outer)
}

#[test]
fn lame_internal_pressure_with_rigid_modes_fixed() {
    let (ci, co) = lame_errors(2);
    let (fi, fo) = lame_errors(3);
    assert!(
        ci <= 1.2 * 0.040 && co <= 1.2 * 0.0043,
        "640: inner {ci:e} outer {co:e}"
    );
    assert!(
        fi <= 1.2 * 0.019 && fo <= 1.2 * 0.0015,
        "2560: inner {fi:e} outer {fo:e}"
    );
    assert!(fi < ci && fo < co, "errors must decrease under refinement");
}

#[test]
fn pure_traction_is_rejected_without_gauge_fixing() {
    let mesh = shapes::hollow_sphere(1.0, 2.0, 1).expect("valid sphere");
    let m = Material::new(0.3, 1.0).expect("valid material");
    let bcs = vec![BoundaryCondition::FREE; mesh.element_count()];
    let r = solve(
        &mesh,
        &m,
        &bcs,
        &SolveParams::default(),
        &Control::default(),
    );
    assert_eq!(r.unwrap_err(), bem_core::BemError::PureTraction);
}

/// Solid sphere with u = εx prescribed at the centroids: mean traction error against σ·n_e (n_e the
/// flat element's normal, for which σ·n_e is exact on the polyhedron), normalised by the largest
/// exact traction ε(λ+2μ) — the normalisation that reproduces the figures of `docs/design/solve.md` (normalising
/// element by element by |σ·n_e| gives 2.9% / 1.4% instead).
fn solid_sphere_traction_error(subdivisions: u32) -> f64 {
    let mesh = shapes::sphere(subdivisions, 1.0).expect("valid sphere");
    let m = Material::from_young(1.0, 0.3).expect("valid material");
    let eps = 1e-3;
    let bcs: Vec<BoundaryCondition> = mesh
        .centroids()
        .iter()
        .map(|x| BoundaryCondition::Displacement(DVec3::new(eps * x.x, 0.0, 0.0)))
        .collect();
    let s = solve(
        &mesh,
        &m,
        &bcs,
        &SolveParams::default(),
        &Control::default(),
    )
    .expect("solve");
    let (lambda, mu) = (m.lambda(), m.shear_modulus());
    let n_el = mesh.element_count();
    let err = (0..n_el)
        .map(|e| {
            let n = mesh.normal(e);
            let exact = eps * DVec3::new((lambda + 2.0 * mu) * n.x, lambda * n.y, lambda * n.z);
            (s.traction[e] - exact).length() / (eps * (lambda + 2.0 * mu))
        })
        .sum::<f64>()
        / n_el as f64;
    eprintln!("solid sphere u = εx, N={n_el}: mean traction error {err:.4e}");
    err
}

#[test]
fn solid_sphere_linear_field_tractions_match_sigma_n() {
    let coarse = solid_sphere_traction_error(2);
    let fine = solid_sphere_traction_error(3);
    assert!(
        coarse <= 1.2 * 0.018,
        "320 elements: {coarse:e} > 1.2 × 1.8%"
    );
    assert!(fine <= 1.2 * 0.009, "1280 elements: {fine:e} > 1.2 × 0.9%");
    assert!(fine < coarse);
}

#[test]
fn rigid_translation_gives_zero_tractions() {
    let mesh = shapes::hollow_sphere(1.0, 2.0, 2).expect("valid sphere");
    let m = Material::new(0.3, 1.0).expect("valid material");
    let c = DVec3::new(0.3, -0.2, 0.5);
    let bcs = vec![BoundaryCondition::Displacement(c); mesh.element_count()];
    let s = solve(
        &mesh,
        &m,
        &bcs,
        &SolveParams::default(),
        &Control::default(),
    )
    .expect("solve");
    // traction scale of a unit strain: μ |c| / (body size)
    let scale = m.shear_modulus() * c.length() / 2.0;
    let worst = s.traction.iter().map(|t| t.length()).fold(0.0, f64::max) / scale;
    eprintln!("rigid translation: max |t| / (μ|c|/R) = {worst:e}");
    assert!(worst < 1e-10, "{worst:e}");
    assert!(s.displacement.iter().all(|u| *u == c));
}
