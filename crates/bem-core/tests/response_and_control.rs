//! Response basis superposition, multi-RHS, progress, cancellation, singular matrices, vertex averaging.

use std::sync::Mutex;
use std::sync::atomic::{AtomicBool, Ordering};

use bem_core::{
    BemError, BoundaryCondition, Control, DenseLu, LinearSystem, Loads, Material, Progress,
    ResponseBasis, SolveParams, Stage, assemble_h_g, element_to_vertex, shapes, solve,
};
use glam::DVec3;

fn max_rel(a: &[DVec3], b: &[DVec3]) -> f64 {
    let scale = b.iter().map(|v| v.length()).fold(0.0, f64::max);
    a.iter()
        .zip(b)
        .map(|(x, y)| (*x - *y).length())
        .fold(0.0, f64::max)
        / scale
}

#[test]
fn response_superposition_equals_direct_solve() {
    // hollow sphere: inner surface fixed except two driven patches ("muscles"), outer free
    let mesh = shapes::hollow_sphere(1.0, 1.3, 2).expect("valid");
    let m = Material::new(0.45, 1.0).expect("material");
    let half = mesh.element_count() / 2;
    let prescribed: Vec<bool> = (0..mesh.element_count()).map(|e| e < half).collect();
    let patch = |dir: DVec3| -> Vec<(usize, DVec3)> {
        (0..half)
            .filter(|&e| mesh.centroid(e).normalize().dot(dir) > 0.8)
            .map(|e| (e, 0.02 * dir.cross(mesh.centroid(e)) + 0.01 * dir))
            .collect()
    };
    let groups = vec![patch(DVec3::X), patch(DVec3::new(0.0, 0.6, 0.8))];
    assert!(groups.iter().all(|g| g.len() > 5));
    let basis = ResponseBasis::compute(
        &mesh,
        &m,
        &prescribed,
        &groups,
        &SolveParams::default(),
        &Control::default(),
    )
    .expect("basis");
    let s = [0.7, -1.3];
    let mut bcs: Vec<BoundaryCondition> = (0..mesh.element_count())
        .map(|e| {
            if prescribed[e] {
                BoundaryCondition::Displacement(DVec3::ZERO)
            } else {
                BoundaryCondition::FREE
            }
        })
        .collect();
    for (g, group) in groups.iter().enumerate() {
        for &(e, u) in group {
            let BoundaryCondition::Displacement(old) = bcs[e] else {
                panic!("prescribed")
            };
            bcs[e] = BoundaryCondition::Displacement(old + s[g] * u);
        }
    }
    let direct = solve(
        &mesh,
        &m,
        &bcs,
        &SolveParams::default(),
        &Control::default(),
    )
    .expect("solve");
    let u = basis.combine_displacement(&s).expect("combine");
    let t = basis.combine_traction(&s).expect("combine");
    let (eu, et) = (
        max_rel(&u, &direct.displacement),
        max_rel(&t, &direct.traction),
    );
    eprintln!("superposition: displacement {eu:e}, traction {et:e}");
    assert!(eu < 1e-10 && et < 1e-10, "u {eu:e} t {et:e}");
    // the free surface really moved and the driven elements kept their prescribed values
    assert!(u[half..].iter().any(|v| v.length() > 1e-4));
    for &(e, v) in &groups[0] {
        assert!((basis.responses[0].displacement[e] - v).length() < 1e-15);
    }
    assert!(basis.combine_displacement(&[1.0]).is_err());
}

#[test]
fn full_h_and_g_reproduce_the_mixed_system_solution() {
    // research path: H u = G t holds for the solution of the column-block solver
    let mesh = shapes::hollow_sphere(1.0, 2.0, 1).expect("valid");
    let m = Material::new(0.3, 1.0).expect("material");
    let half = mesh.element_count() / 2;
    let bcs: Vec<BoundaryCondition> = (0..mesh.element_count())
        .map(|e| {
            if e < half {
                BoundaryCondition::Displacement(0.01 * mesh.centroid(e).normalize())
            } else {
                BoundaryCondition::Traction(DVec3::new(0.0, 0.0, 0.001 * mesh.normal(e).z))
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
    let (h, g) =
        assemble_h_g(&mesh, &m, &SolveParams::default().quadrature).expect("full matrices");
    let n = mesh.element_count();
    let flat = |v: &[DVec3]| faer::Mat::<f64>::from_fn(3 * n, 1, |r, _| v[r / 3][r % 3]);
    let hu = &h * flat(&s.displacement);
    let gt = &g * flat(&s.traction);
    let diff = (&hu - &gt).norm_l2() / hu.norm_l2();
    eprintln!("|Hu − Gt| / |Hu| = {diff:e}");
    assert!(diff < 1e-12, "{diff:e}");
}

#[test]
fn progress_is_reported_per_stage_and_cancellation_stops_assembly() {
    let mesh = shapes::sphere(2, 1.0).expect("valid");
    let m = Material::new(0.3, 1.0).expect("material");
    let bcs = vec![BoundaryCondition::Displacement(DVec3::X); mesh.element_count()];
    let seen: Mutex<Vec<Progress>> = Mutex::new(Vec::new());
    let record = |p: Progress| seen.lock().expect("lock").push(p);
    let control = Control {
        cancel: None,
        progress: Some(&record),
    };
    solve(&mesh, &m, &bcs, &SolveParams::default(), &control).expect("solve");
    let seen = seen.into_inner().expect("lock");
    for stage in [Stage::Assembly, Stage::Factorisation, Stage::Solve] {
        let last = seen
            .iter()
            .rev()
            .find(|p| p.stage == stage)
            .expect("stage reported");
        assert_eq!(last.done, last.total, "{stage:?} did not finish");
    }
    let assembly: Vec<_> = seen.iter().filter(|p| p.stage == Stage::Assembly).collect();
    assert!(assembly.len() > 10 && assembly.iter().all(|p| p.total == 320));

    // cancel from the progress callback once 10% of the columns are done
    let cancel = AtomicBool::new(false);
    let max_done = Mutex::new(0usize);
    let on_progress = |p: Progress| {
        {
            let mut d = max_done.lock().expect("lock");
            *d = (*d).max(p.done);
        }
        if p.stage == Stage::Assembly && p.done >= 32 {
            cancel.store(true, Ordering::Relaxed);
        }
        assert_ne!(p.stage, Stage::Factorisation, "factorisation after cancel");
    };
    let control = Control {
        cancel: Some(&cancel),
        progress: Some(&on_progress),
    };
    let err = solve(&mesh, &m, &bcs, &SolveParams::default(), &control).unwrap_err();
    assert_eq!(err, BemError::Cancelled);
    let done = *max_done.lock().expect("lock");
    assert!(
        done < 320,
        "assembly ran to the end ({done}) despite cancellation"
    );

    // already cancelled: nothing starts
    let cancel = AtomicBool::new(true);
    let control = Control {
        cancel: Some(&cancel),
        progress: None,
    };
    assert_eq!(
        solve(&mesh, &m, &bcs, &SolveParams::default(), &control).unwrap_err(),
        BemError::Cancelled
    );
}

#[test]
fn singular_and_non_finite_matrices_are_reported_not_returned_as_nan() {
    // rank 2 matrix
    let a = faer::Mat::<f64>::from_fn(3, 3, |i, j| {
        ((i + 1) * (j + 1)) as f64 + if j == 0 { i as f64 } else { 0.0 }
    });
    let err = DenseLu::factor(a).unwrap_err();
    assert!(matches!(err, BemError::Singular { .. }), "{err}");
    let mut b = faer::Mat::<f64>::identity(4, 4);
    b[(2, 1)] = f64::NAN;
    assert_eq!(
        DenseLu::factor(b).unwrap_err(),
        BemError::NonFinite {
            what: "system matrix"
        }
    );
    // a real BEM K with one column duplicated (two identical unknowns) is singular
    let mesh = shapes::sphere(1, 1.0).expect("valid");
    let m = Material::new(0.3, 1.0).expect("material");
    let prescribed = vec![true; 80];
    let mut loads = Loads::new(80, 1);
    loads.set(3, 0, DVec3::X).expect("set");
    let mut sys = LinearSystem::assemble(
        &mesh,
        &m,
        &prescribed,
        &loads,
        &SolveParams::default(),
        &Control::default(),
    )
    .expect("assemble");
    for r in 0..240 {
        sys.matrix[(r, 5)] = sys.matrix[(r, 4)];
    }
    let err = sys.solve(&Control::default()).unwrap_err();
    assert!(matches!(err, BemError::Singular { .. }), "{err}");
}

#[test]
fn multiple_right_hand_sides_match_separate_solves() {
    let mesh = shapes::hollow_sphere(1.0, 1.5, 1).expect("valid");
    let m = Material::new(0.4, 2.0).expect("material");
    let n = mesh.element_count();
    let prescribed: Vec<bool> = (0..n).map(|e| e < n / 2).collect();
    let mut loads = Loads::new(n, 2);
    for (e, &p) in prescribed.iter().enumerate() {
        let x = mesh.centroid(e);
        if p {
            loads.set(e, 0, 0.01 * x).expect("set");
        } else {
            loads
                .set(e, 1, DVec3::new(0.0, 0.0, 0.01 * x.z))
                .expect("set");
        }
    }
    let p = SolveParams::default();
    let c = Control::default();
    let both = LinearSystem::assemble(&mesh, &m, &prescribed, &loads, &p, &c)
        .expect("assemble")
        .solve(&c)
        .expect("solve");
    for (r, sol) in both.iter().enumerate() {
        let bcs: Vec<BoundaryCondition> = (0..n)
            .map(|e| {
                let v = loads.get(e, r);
                if prescribed[e] {
                    BoundaryCondition::Displacement(v)
                } else {
                    BoundaryCondition::Traction(v)
                }
            })
            .collect();
        let single = solve(&mesh, &m, &bcs, &p, &c).expect("solve");
        assert!(max_rel(&sol.displacement, &single.displacement) < 1e-12);
        assert!(max_rel(&sol.traction, &single.traction) < 1e-12);
    }
}

#[test]
fn element_to_vertex_is_area_weighted() {
    let (mut v, t) = shapes::icosphere(1, 1.0);
    // stretch so areas differ
    for p in &mut v {
        p.x *= 2.0;
    }
    let mesh = bem_core::SurfaceMesh::new(v, t).expect("valid");
    let values: Vec<DVec3> = (0..mesh.element_count())
        .map(|e| DVec3::splat(e as f64))
        .collect();
    let out = element_to_vertex(&mesh, &values).expect("lengths match");
    let vertex = mesh.triangles()[10][1] as usize;
    let (mut s, mut w) = (0.0, 0.0);
    for (e, tri) in mesh.triangles().iter().enumerate() {
        if tri.contains(&(vertex as u32)) {
            s += mesh.area(e) * e as f64;
            w += mesh.area(e);
        }
    }
    assert!((out[vertex].x - s / w).abs() < 1e-12);
    // linear field of centroids is reproduced closely at the vertices (sanity of weighting)
    assert!(element_to_vertex(&mesh, &values[1..]).is_err());
}

#[test]
fn blocked_lu_matches_faer_and_has_small_residual() {
    use faer::linalg::solvers::Solve;
    use rand::{Rng, SeedableRng};
    // 3 full panels plus a partial one, and a matrix that needs pivoting (small diagonal)
    let n = 3 * bem_core::dense::LU_PANEL + 77;
    let mut rng = rand::rngs::StdRng::seed_from_u64(11);
    let a = faer::Mat::<f64>::from_fn(n, n, |i, j| {
        let v: f64 = rng.random::<f64>() - 0.5;
        if i == j { 1e-3 * v } else { v }
    });
    let b = faer::Mat::<f64>::from_fn(n, 3, |i, j| ((i * 7 + j * 3) % 11) as f64 - 5.0);
    let lu = DenseLu::factor(a.clone()).expect("regular");
    let mut x = b.clone();
    lu.solve_in_place(x.as_mut()).expect("solve");
    let residual = (&a * &x - &b).norm_l2() / b.norm_l2();
    let reference = a.partial_piv_lu().solve(&b);
    let diff = (&x - &reference).norm_l2() / reference.norm_l2();
    eprintln!("blocked LU: residual {residual:e}, difference to faer {diff:e}");
    assert!(residual < 1e-11, "{residual:e}");
    assert!(diff < 1e-9, "{diff:e}");
}

#[test]
fn factorisation_reports_panels_and_can_be_cancelled() {
    let n = 4 * bem_core::dense::LU_PANEL;
    let a = faer::Mat::<f64>::from_fn(n, n, |i, j| {
        if i == j {
            4.0
        } else {
            1.0 / (1.0 + (i + 2 * j) as f64)
        }
    });
    let seen = Mutex::new(Vec::new());
    let record = |p: Progress| seen.lock().expect("lock").push(p.done);
    let control = Control {
        cancel: None,
        progress: Some(&record),
    };
    DenseLu::factor_with(a.clone(), &control).expect("regular");
    assert_eq!(
        seen.into_inner().expect("lock"),
        (0..=4)
            .map(|k| k * bem_core::dense::LU_PANEL)
            .collect::<Vec<_>>()
    );
    let cancel = AtomicBool::new(false);
    let stop = |p: Progress| {
        if p.done > 0 {
            cancel.store(true, Ordering::Relaxed);
        }
    };
    let control = Control {
        cancel: Some(&cancel),
        progress: Some(&stop),
    };
    assert_eq!(
        DenseLu::factor_with(a, &control).unwrap_err(),
        BemError::Cancelled
    );
}

/// Regression (CI, 2026-11-22): the H row sums were accumulated per worker thread, so which
/// columns a thread stole decided the summation order and two runs differed in the last bits
/// (a recomputed cache did not equal the first computation). K and the right-hand sides must be
/// bit-for-bit the same whatever the thread count.
#[test]
fn assembly_is_bit_identical_for_any_thread_count() {
    let mesh = shapes::hollow_sphere(1.0, 1.3, 2).expect("valid");
    let m = Material::new(0.45, 1.0).expect("material");
    let n = mesh.element_count();
    let prescribed: Vec<bool> = (0..n).map(|e| e % 3 == 0).collect();
    let mut loads = Loads::new(n, 2);
    for e in (0..n).filter(|e| e % 3 == 0) {
        let c = mesh.centroid(e);
        loads.set(e, 0, 0.01 * c).expect("load");
        loads
            .set(e, 1, DVec3::new(0.0, 0.02 * c.z, 0.0))
            .expect("load");
    }
    let assemble = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("pool")
            .install(|| {
                LinearSystem::assemble(
                    &mesh,
                    &m,
                    &prescribed,
                    &loads,
                    &SolveParams::default(),
                    &Control::default(),
                )
                .expect("assembly")
            })
    };
    let one = assemble(1);
    for threads in [2, 3, 7] {
        let other = assemble(threads);
        assert!(
            one.matrix.as_slice() == other.matrix.as_slice(),
            "K differs with {threads} threads"
        );
        assert!(one.rhs == other.rhs, "rhs differs with {threads} threads");
    }
}
