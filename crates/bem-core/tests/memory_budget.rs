//! Memory: the dense solve's needs are checked against a budget before anything large is
//! allocated, and many right-hand sides are assembled and solved in bounded buffers.

use bem_core::{
    BemError, Control, LinearSystem, Loads, Material, MemoryEstimate, SolveParams, shapes,
};
use glam::DVec3;

fn problem(rhs_count: usize) -> (bem_core::SurfaceMesh, Vec<bool>, Loads) {
    let mesh = shapes::sphere(1, 1.0).expect("valid");
    let n = mesh.element_count();
    let prescribed: Vec<bool> = mesh.centroids().iter().map(|c| c.z < 0.0).collect();
    let fixed: Vec<usize> = (0..n).filter(|&e| prescribed[e]).collect();
    let mut loads = Loads::new(n, rhs_count);
    for r in 0..rhs_count {
        let e = fixed[r % fixed.len()];
        let k = r as f64;
        loads
            .set(e, r, 0.01 * DVec3::new(1.0 + k.sin(), k.cos(), 0.1 * k))
            .expect("set");
    }
    (mesh, prescribed, loads)
}

#[test]
fn a_solve_above_the_memory_budget_is_refused_before_allocating() {
    let (mesh, prescribed, loads) = problem(3);
    let m = Material::new(0.45, 1.0).expect("material");
    let budget = SolveParams {
        memory_budget_bytes: Some(100_000),
        ..SolveParams::default()
    };
    let err = LinearSystem::assemble(&mesh, &m, &prescribed, &loads, &budget, &Control::default())
        .unwrap_err();
    match err {
        BemError::OverBudget {
            needed_bytes,
            budget_bytes,
            matrix_bytes,
            rhs_bytes,
        } => {
            assert_eq!(budget_bytes, 100_000);
            assert_eq!(matrix_bytes, 8 * 240 * 240);
            assert_eq!(rhs_bytes, 8 * 240 * 3);
            assert!(needed_bytes > matrix_bytes + rhs_bytes);
        }
        other => panic!("expected OverBudget, got {other:?}"),
    }
    // a sufficient budget passes
    let enough = SolveParams {
        memory_budget_bytes: Some(10_000_000),
        ..SolveParams::default()
    };
    LinearSystem::assemble(&mesh, &m, &prescribed, &loads, &enough, &Control::default())
        .expect("within budget");
}

#[test]
fn memory_estimate_is_k_plus_rhs_plus_thread_buffers() {
    // 3000 elements, 1000 load cases, 2 threads: K 648 MB, y 72 MB, 2 × 72 MB of partial sums
    let e = MemoryEstimate::new(3000, 9000, 1000, 2);
    assert_eq!(e.matrix, 648_000_000);
    assert_eq!(e.rhs, 72_000_000);
    assert_eq!(e.buffers, 2 * (72 * 3000 + 72_000_000));
    assert_eq!(e.total(), e.matrix + e.rhs + e.buffers);
}

/// More load cases than one solve block (256): every load case is solved and equals its own
/// single-right-hand-side solve.
#[test]
fn three_hundred_load_cases_match_single_solves() {
    let count = 300;
    let (mesh, prescribed, loads) = problem(count);
    let m = Material::new(0.45, 1.0).expect("material");
    let params = SolveParams::default();
    let control = Control::default();
    let all = LinearSystem::assemble(&mesh, &m, &prescribed, &loads, &params, &control)
        .expect("assemble")
        .solve(&control)
        .expect("solve");
    assert_eq!(all.len(), count);
    for r in [0, 7, 255, 256, 299] {
        let mut one = Loads::new(mesh.element_count(), 1);
        for e in 0..mesh.element_count() {
            let v = loads.get(e, r);
            if v != DVec3::ZERO {
                one.set(e, 0, v).expect("set");
            }
        }
        let single = LinearSystem::assemble(&mesh, &m, &prescribed, &one, &params, &control)
            .expect("assemble")
            .solve(&control)
            .expect("solve");
        let scale = single[0]
            .traction
            .iter()
            .map(|t| t.length())
            .fold(0.0, f64::max);
        let worst = all[r]
            .traction
            .iter()
            .zip(&single[0].traction)
            .chain(all[r].displacement.iter().zip(&single[0].displacement))
            .map(|(a, b)| (*a - *b).length())
            .fold(0.0, f64::max);
        assert!(
            worst <= 1e-12 * scale,
            "load case {r}: {worst:e} vs {scale:e}"
        );
    }
}
