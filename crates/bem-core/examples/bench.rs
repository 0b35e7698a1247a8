//! Benchmark of assembly, LU and memory at ~1000, ~3000 and ~5000 elements.
//!
//! `cargo run --release -p bem-core --example bench` (optionally with element counts as
//! arguments, e.g. `-- 1000 3000`). For each size, on a torus with 30% of its elements fixed and
//! ten driven groups (the shape of the face problem):
//! * parallel column-block assembly time, next to the same code on one thread and the naive
//!   single-threaded full-H-and-G assembly ([`bem_core::assemble_h_g`], skipped above 3500
//!   elements because it holds two dense matrices);
//! * LU GFLOP/s of K next to faer's `partial_piv_lu` on a random dense matrix of the same size;
//! * peak heap bytes of assemble + factor + solve over one dense K, 8·(3N)² bytes (counting allocator).
//!
//! `cargo run --release -p bem-core --example bench -- rhs [N] [R ...]`: peak heap and times of
//! assemble + factor + solve with many right-hand sides (default N = 3000 elements, R = 1, 10,
//! 100, 1000 load cases), each load case driving its own share of the fixed elements.

#![allow(unsafe_code)] // the counting global allocator below

use std::alloc::{GlobalAlloc, Layout, System};
use std::sync::atomic::{AtomicUsize, Ordering};
use std::time::Instant;

use bem_core::{
    Control, DenseLu, LinearSystem, Loads, Material, SolveParams, assemble_h_g, shapes,
};
use glam::DVec3;
use rand::{Rng, SeedableRng};

struct Counting;

static CURRENT: AtomicUsize = AtomicUsize::new(0);
static PEAK: AtomicUsize = AtomicUsize::new(0);

// SAFETY: forwards to the system allocator and only counts bytes.
unsafe impl GlobalAlloc for Counting {
    unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
        // SAFETY: same contract as System.alloc.
        let p = unsafe { System.alloc(layout) };
        if !p.is_null() {
            let now = CURRENT.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
            PEAK.fetch_max(now, Ordering::Relaxed);
        }
        p
    }
    unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
        // SAFETY: same contract as System.alloc_zeroed (calloc: fresh pages are not touched).
        let p = unsafe { System.alloc_zeroed(layout) };
        if !p.is_null() {
            let now = CURRENT.fetch_add(layout.size(), Ordering::Relaxed) + layout.size();
            PEAK.fetch_max(now, Ordering::Relaxed);
        }
        p
    }
    unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
        // SAFETY: same contract as System.dealloc.
        unsafe { System.dealloc(ptr, layout) };
        CURRENT.fetch_sub(layout.size(), Ordering::Relaxed);
    }
    unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
        // SAFETY: same contract as System.realloc.
        let p = unsafe { System.realloc(ptr, layout, new_size) };
        if !p.is_null() {
            if new_size >= layout.size() {
                let now = CURRENT.fetch_add(new_size - layout.size(), Ordering::Relaxed) + new_size
                    - layout.size();
                PEAK.fetch_max(now, Ordering::Relaxed);
            } else {
                CURRENT.fetch_sub(layout.size() - new_size, Ordering::Relaxed);
            }
        }
        p
    }
}

#[global_allocator]
static GLOBAL: Counting = Counting;

/// Torus grid closest to `target` elements (2·around·tube, around ≈ 2·tube).
fn torus_for(target: usize) -> bem_core::SurfaceMesh {
    let tube = ((target as f64 / 4.0).sqrt().round() as u32).max(3);
    let around = ((target as f64 / (2.0 * tube as f64)).round() as u32).max(3);
    shapes::torus(1.0, 0.35, around, tube).expect("torus is a valid closed surface")
}

/// Peak heap of assemble + factor + solve on a torus of `target` elements for each load-case count.
fn bench_rhs(target: usize, counts: &[usize]) -> anyhow_free::Result {
    let material = Material::new(0.45, 1.0)?;
    let params = SolveParams::default();
    let control = Control::default();
    let mesh = torus_for(target);
    let n = mesh.element_count();
    let dof = 3 * n;
    let prescribed: Vec<bool> = mesh.centroids().iter().map(|c| c.x < -0.55).collect();
    let fixed: Vec<usize> = (0..n).filter(|&e| prescribed[e]).collect();
    let k_bytes = 8.0 * (dof as f64).powi(2);
    println!(
        "many right-hand sides, N = {n} ({} fixed), {} rayon threads, K = {:.0} MB",
        fixed.len(),
        rayon::current_num_threads(),
        k_bytes / 1e6
    );
    println!(
        "{:>6} | {:>8} {:>8} | {:>9} {:>9} {:>7} | {:>9}",
        "R", "asm s", "solve s", "peak MB", "(peak-K)", "peak/K", "rhs MB"
    );
    for &count in counts {
        let mut loads = Loads::new(n, count);
        for (k, &e) in fixed.iter().enumerate() {
            loads.set(e, k % count, DVec3::new(0.01, 0.005, -0.002))?;
        }
        let baseline = CURRENT.load(Ordering::Relaxed);
        PEAK.store(baseline, Ordering::Relaxed);
        let t = Instant::now();
        let sys = LinearSystem::assemble(&mesh, &material, &prescribed, &loads, &params, &control)?;
        let t_asm = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let solutions = sys.solve(&control)?;
        let t_solve = t.elapsed().as_secs_f64();
        let peak = (PEAK.load(Ordering::Relaxed) - baseline) as f64;
        drop(solutions);
        println!(
            "{:>6} | {:>8.2} {:>8.2} | {:>9.0} {:>9.0} {:>7.3} | {:>9.0}",
            count,
            t_asm,
            t_solve,
            peak / 1e6,
            (peak - k_bytes) / 1e6,
            peak / k_bytes,
            8.0 * dof as f64 * count as f64 / 1e6
        );
    }
    println!("peak = heap high-water mark over assemble + factor + solve (counting allocator),");
    println!("including the returned solutions and gemm's thread-local buffers on first use");
    Ok(())
}

fn main() -> anyhow_free::Result {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if args.first().map(String::as_str) == Some("rhs") {
        let numbers: Vec<usize> = args[1..].iter().filter_map(|a| a.parse().ok()).collect();
        let target = numbers.first().copied().unwrap_or(3000);
        let counts = if numbers.len() > 1 {
            numbers[1..].to_vec()
        } else {
            vec![1, 10, 100, 1000]
        };
        return bench_rhs(target, &counts);
    }
    let sizes: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let sizes = if sizes.is_empty() {
        vec![1000, 3000, 5000]
    } else {
        sizes
    };
    let threads = rayon::current_num_threads();
    println!("bem-core benchmark, {threads} rayon threads");
    print_header();
    let material = Material::new(0.45, 1.0)?;
    let params = SolveParams::default();
    let control = Control::default();
    for target in sizes {
        bench_size(target, &material, &params, &control)?;
    }
    print_legend();
    Ok(())
}

/// Column headings of the size table.
fn print_header() {
    println!(
        "{:>6} {:>6} | {:>9} {:>9} {:>9} {:>7} | {:>8} {:>8} {:>6} | {:>7} | {:>6} {:>8} {:>11}",
        "N",
        "3N",
        "asm par",
        "asm 1thr",
        "naive HG",
        "Mat0 K",
        "LU GF/s",
        "faer GF/s",
        "ratio",
        "solve",
        "peak/K",
        "K MB",
        "gemm buf MB"
    );
}

/// What the columns of the size table mean.
fn print_legend() {
    println!(
        "Mat0 K = faer::Mat::zeros of one K alone (serial zero fill, which bem-core's lazily zeroed DenseMatrix avoids)"
    );
    println!(
        "times in seconds; ratio = LU rate of K / faer rate on random matrix; peak/K = peak heap of"
    );
    println!(
        "assemble+factor+solve / 8(3N)^2, including gemm's thread-local packing buffers the first time"
    );
    println!("they are allocated (gemm buf MB = heap retained after the solve, 0 once they exist)");
}

/// One row of the size table: the torus closest to `target` elements.
fn bench_size(
    target: usize,
    material: &Material,
    params: &SolveParams,
    control: &Control<'_>,
) -> anyhow_free::Result {
    let mesh = torus_for(target);
    let n = mesh.element_count();
    let dof = 3 * n;
    // face-like problem: outer-left 30% fixed, ten driven groups among the fixed elements
    let prescribed: Vec<bool> = mesh.centroids().iter().map(|c| c.x < -0.55).collect();
    let fixed: Vec<usize> = (0..n).filter(|&e| prescribed[e]).collect();
    let mut loads = Loads::new(n, 10);
    for (k, &e) in fixed.iter().enumerate() {
        if k % 3 == 0 {
            loads.set(e, (k / 3) % 10, DVec3::new(0.01, 0.005, -0.002))?;
        }
    }

    let naive = if n <= 3500 {
        let t = Instant::now();
        let hg = assemble_h_g(&mesh, material, &params.quadrature)?;
        drop(hg);
        format!("{:9.2}", t.elapsed().as_secs_f64())
    } else {
        format!("{:>9}", "skipped")
    };
    let single = rayon::ThreadPoolBuilder::new().num_threads(1).build()?;
    let t = Instant::now();
    let sys1 = single.install(|| {
        LinearSystem::assemble(&mesh, material, &prescribed, &loads, params, control)
    })?;
    let asm_single = t.elapsed().as_secs_f64();
    drop(sys1);

    // for comparison: the serial zero fill of faer::Mat::zeros that DenseMatrix avoids
    let t = Instant::now();
    let zeros = faer::Mat::<f64>::zeros(dof, dof);
    let t_zero = t.elapsed().as_secs_f64();
    drop(zeros);

    let baseline = CURRENT.load(Ordering::Relaxed);
    PEAK.store(baseline, Ordering::Relaxed);
    let t = Instant::now();
    let sys = LinearSystem::assemble(&mesh, material, &prescribed, &loads, params, control)?;
    let asm_par = t.elapsed().as_secs_f64();
    let peak_asm = PEAK.load(Ordering::Relaxed) - baseline;
    let LinearSystem {
        matrix, mut rhs, ..
    } = sys;
    let t = Instant::now();
    let lu = DenseLu::factor(matrix)?;
    let t_lu = t.elapsed().as_secs_f64();
    let peak_lu = PEAK.load(Ordering::Relaxed) - baseline;
    if std::env::var_os("BENCH_DEBUG").is_some() {
        eprintln!(
            "peak after assembly {peak_asm}, after LU {peak_lu}, K {}",
            8 * dof * dof
        );
    }
    let t = Instant::now();
    lu.solve_in_place(rhs.as_mut())?;
    let t_solve = t.elapsed().as_secs_f64();
    let peak = PEAK.load(Ordering::Relaxed) - baseline;
    drop(lu);
    drop(rhs);
    // heap that outlives the solve: gemm's thread-local packing buffers (2 × L3 per thread,
    // allocated on a thread's first large matrix product, then reused)
    let retained = CURRENT.load(Ordering::Relaxed).saturating_sub(baseline);

    let t_random = random_lu_seconds(dof);

    let flops = 2.0 / 3.0 * (dof as f64).powi(3);
    let k_bytes = 8.0 * (dof as f64).powi(2);
    println!(
        "{:>6} {:>6} | {:>9.2} {:>9.2} {} {:>7.2} | {:>8.1} {:>8.1} {:>6.2} | {:>7.3} | {:>6.3} {:>8.0} {:>11.0}",
        n,
        dof,
        asm_par,
        asm_single,
        naive,
        t_zero,
        flops / t_lu * 1e-9,
        flops / t_random * 1e-9,
        t_random / t_lu,
        t_solve,
        peak as f64 / k_bytes,
        k_bytes / 1e6,
        retained as f64 / 1e6
    );
    Ok(())
}

/// Seconds faer's `partial_piv_lu` takes on a random dense `dof` × `dof` matrix.
fn random_lu_seconds(dof: usize) -> f64 {
    let mut rng = rand::rngs::StdRng::seed_from_u64(7);
    let random = faer::Mat::<f64>::from_fn(dof, dof, |_, _| rng.random::<f64>() - 0.5);
    let t = Instant::now();
    let lu_random = random.partial_piv_lu();
    let t_random = t.elapsed().as_secs_f64();
    drop(lu_random);
    t_random
}

/// Minimal boxed error for the example (no anyhow dependency in this crate).
mod anyhow_free {
    /// Result with any error.
    pub type Result = std::result::Result<(), Box<dyn std::error::Error>>;
}
