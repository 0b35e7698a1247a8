//! Benchmark of the mixed-precision LU against the f64 LU on one assembled K.
//!
//! `cargo run --release -p bem-core --example mixed_bench` (optionally with element counts as
//! arguments, default `1000 3200`). For each size, on a torus with 30 % of its elements fixed
//! and 37 driven groups (the shape of the face problem): the f64 LU's factor and solve times,
//! the mixed LU's ([`bem_core::MixedLu`]: f32 factor, iterative refinement), its refinement
//! rounds, and the largest difference between the two solutions relative to the largest
//! entry.

use std::time::Instant;

use bem_core::{Control, DenseLu, LinearSystem, Loads, Material, MixedLu, SolveParams, shapes};
use glam::DVec3;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let sizes: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let sizes = if sizes.is_empty() {
        vec![1000, 3200]
    } else {
        sizes
    };
    println!(
        "{:>6} {:>6} | {:>9} {:>9} | {:>9} {:>9} {:>6} | {:>7} | {:>9}",
        "N", "3N", "f64 LU", "f64 solve", "mixed LU", "mx solve", "rounds", "speedup", "max diff"
    );
    let material = Material::new(0.45, 1.0)?;
    let params = SolveParams::default();
    let control = Control::default();
    for target in sizes {
        let tube = ((target as f64 / 4.0).sqrt().round() as u32).max(3);
        let around = ((target as f64 / (2.0 * tube as f64)).round() as u32).max(3);
        let mesh = shapes::torus(1.0, 0.35, around, tube)?;
        let n = mesh.element_count();
        let prescribed: Vec<bool> = mesh.centroids().iter().map(|c| c.x < -0.55).collect();
        let fixed: Vec<usize> = (0..n).filter(|&e| prescribed[e]).collect();
        let groups = 37;
        let mut loads = Loads::new(n, groups);
        for (k, &e) in fixed.iter().enumerate() {
            if k % 3 == 0 {
                loads.set(e, (k / 3) % groups, DVec3::new(0.01, 0.005, -0.002))?;
            }
        }
        let LinearSystem { matrix, rhs, .. } =
            LinearSystem::assemble(&mesh, &material, &prescribed, &loads, &params, &control)?;
        let copy = matrix.clone();

        let t = Instant::now();
        let lu = DenseLu::factor(copy)?;
        let t_lu = t.elapsed().as_secs_f64();
        let mut x64 = rhs.clone();
        let t = Instant::now();
        lu.solve_in_place(x64.as_mut())?;
        let t_solve = t.elapsed().as_secs_f64();
        drop(lu);

        let t = Instant::now();
        let mixed = MixedLu::factor_with(matrix, &control)?;
        let t_mlu = t.elapsed().as_secs_f64();
        let mut x = rhs.clone();
        let t = Instant::now();
        let rounds = mixed.solve_in_place(x.as_mut())?;
        let t_msolve = t.elapsed().as_secs_f64();

        let scale = x64
            .col_iter()
            .flat_map(|c| c.iter().copied())
            .fold(0.0f64, |m, v| m.max(v.abs()));
        let diff = (0..x.ncols())
            .flat_map(|j| (0..x.nrows()).map(move |i| (i, j)))
            .map(|(i, j)| (x[(i, j)] - x64[(i, j)]).abs())
            .fold(0.0f64, f64::max);
        println!(
            "{:>6} {:>6} | {:>9.2} {:>9.3} | {:>9.2} {:>9.3} {:>6} | {:>7.2} | {:>9.1e}",
            n,
            3 * n,
            t_lu,
            t_solve,
            t_mlu,
            t_msolve,
            rounds,
            (t_lu + t_solve) / (t_mlu + t_msolve),
            diff / scale
        );
    }
    println!("times in seconds; speedup = (f64 LU + solve) / (mixed LU + refined solve)");
    Ok(())
}
