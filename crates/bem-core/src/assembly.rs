//! Direct column-block assembly of the mixed system `K x = y`.
//!
//! Column block j (3 contiguous columns of the column-major K) is produced by one rayon task:
//! the H block column of element j when its traction is prescribed, −G when its displacement is.
//! The H blocks of displacement-prescribed columns go straight into the right-hand sides
//! (`y −= H_ij u_j` for every load case at once) and every H block is added to a per-thread row
//! sum, from which the diagonal blocks `h_ii = −Σ_{j≠i} h_ij` (rigid-body trick, eq. 4.5) are
//! put in at the end. Neither H nor G is ever held whole.

use std::sync::atomic::{AtomicUsize, Ordering};

use faer::reborrow::ReborrowMut;
use faer::{Mat, MatMut};
use glam::DVec3;
use rayon::prelude::*;

use crate::DenseMatrix;
use crate::assembly_report::AssemblyReport;
use crate::column::{ColumnInputs, Partial, assemble_column, block_times};
use crate::kernels::{Block, KernelConstants};
use crate::params::{Precision, RigidModes, SolveParams};
use crate::quadrature::ElementQuad;
use crate::{
    BemError, Control, ElementKind, ElementKinds, Loads, MIXED_MIN_UNKNOWNS, Material,
    MemoryEstimate, Stage, SurfaceMesh, tangent_frame,
};

/// The assembled dense system: `matrix · x = rhs`, x = (u on traction-prescribed elements,
/// t on displacement-prescribed ones, (normal traction, tangential displacement in
/// [`tangent_frame`]) on sliding ones) per element in element order, one column per load case.
#[derive(Debug, Clone)]
pub struct LinearSystem {
    /// K (3N × 3N, or 3N+6 with the gauge fixed).
    pub matrix: DenseMatrix,
    /// Right-hand sides, one column per load case.
    pub rhs: Mat<f64>,
    /// Which elements have a prescribed displacement ([`ElementKind::Displacement`]).
    pub prescribed: Vec<bool>,
    /// What is prescribed on each element.
    pub kinds: Vec<ElementKind>,
    /// Unit normal of each element (the frame of a sliding element's unknowns).
    pub normals: Vec<DVec3>,
    /// The prescribed values (copied for unpacking the solution).
    pub loads: Loads,
    /// Whether six gauge rows/columns were appended.
    pub gauge_fixed: bool,
    /// Largest accepted condition estimate of K ([`SolveParams::max_condition`]).
    pub max_condition: f64,
    /// Quadrature accuracy of the assembly.
    pub quadrature: AssemblyReport,
    /// Precision of the LU ([`SolveParams::precision`], or [`Precision::Double`] where the
    /// mixed solve's f32 copy of K would not fit the memory budget).
    pub precision: Precision,
}

/// Number of contiguous column ranges whose row sums are accumulated separately during assembly
/// (enough to keep any core count busy; bounded so their memory stays a few % of K).
const REDUCTION_RANGES: usize = 64;

/// Allocates a zero dense matrix, reporting allocation failure instead of aborting.
pub(crate) fn try_zeros(rows: usize, cols: usize) -> Result<Mat<f64>, BemError> {
    let oom = BemError::OutOfMemory {
        rows,
        cols,
        bytes: rows.saturating_mul(cols).saturating_mul(8),
    };
    let mut m = Mat::<f64>::new();
    m.try_reserve(rows, cols).map_err(|_| oom)?;
    m.resize_with(rows, cols, |_, _| 0.0);
    Ok(m)
}

/// The three contiguous column slices of a 3-column block.
fn three_columns<'a>(block: MatMut<'a, f64>) -> Option<[&'a mut [f64]; 3]> {
    let mut it = block
        .col_iter_mut()
        .map(|c| c.try_as_col_major_mut().map(|c| c.as_slice_mut()));
    let c0 = it.next()??;
    let c1 = it.next()??;
    let c2 = it.next()??;
    Some([c0, c1, c2])
}

/// Rigid-body modes (3 translations, 3 rotations about the area centroid) evaluated at the element
/// centroids and weighted by relative area: `modes[k][e]` is mode k's vector on element e.
fn rigid_mode_rows(mesh: &SurfaceMesh) -> [Vec<DVec3>; 6] {
    let n = mesh.element_count();
    let total: f64 = mesh.areas().iter().sum();
    let center = mesh
        .centroids()
        .iter()
        .zip(mesh.areas())
        .map(|(c, a)| *c * *a)
        .sum::<DVec3>()
        / total;
    let radius = mesh
        .centroids()
        .iter()
        .map(|c| (*c - center).length())
        .fold(0.0, f64::max)
        .max(f64::MIN_POSITIVE);
    let max_area = mesh.areas().iter().copied().fold(0.0, f64::max);
    let axes = [DVec3::X, DVec3::Y, DVec3::Z];
    std::array::from_fn(|k| {
        (0..n)
            .map(|e| {
                let w = mesh.area(e) / max_area;
                if k < 3 {
                    axes[k] * w
                } else {
                    axes[k - 3].cross(mesh.centroid(e) - center) / radius * w
                }
            })
            .collect()
    })
}

impl LinearSystem {
    /// Assembles K and the right-hand sides for the given split of elements into
    /// displacement-prescribed (`prescribed[e] == true`) and traction-prescribed ones, with one
    /// load case per right-hand side in `loads`.
    ///
    /// Memory: K, the right-hand sides, and per rayon thread 9N + 3N × (load cases) doubles
    /// ([`MemoryEstimate`]), checked first against [`SolveParams::memory_budget_bytes`]
    /// ([`BemError::OverBudget`]).
    ///
    /// ```
    /// use bem_core::{shapes, Control, LinearSystem, Loads, Material, SolveParams};
    /// use glam::DVec3;
    /// let mesh = shapes::sphere(1, 1.0).unwrap();
    /// let n = mesh.element_count();
    /// // lower half fixed; load case 0 pulls one fixed element sideways, case 1 pushes the top
    /// let prescribed: Vec<bool> = mesh.centroids().iter().map(|c| c.z < 0.0).collect();
    /// let pulled = prescribed.iter().position(|&p| p).unwrap();
    /// let mut loads = Loads::new(n, 2);
    /// loads.set(pulled, 0, DVec3::new(0.01, 0.0, 0.0)).unwrap();
    /// for e in (0..n).filter(|&e| !prescribed[e]) {
    ///     loads.set(e, 1, -0.001 * mesh.normal(e)).unwrap();
    /// }
    /// let m = Material::new(0.45, 1.0).unwrap();
    /// let system = LinearSystem::assemble(&mesh, &m, &prescribed, &loads, &SolveParams::default(), &Control::default()).unwrap();
    /// assert_eq!(system.matrix.nrows(), 3 * n);
    /// let solutions = system.solve(&Control::default()).unwrap();
    /// assert_eq!(solutions.len(), 2);
    /// assert_eq!(solutions[0].displacement[pulled], DVec3::new(0.01, 0.0, 0.0));
    /// ```
    ///
    /// Any [`ElementKind`] per element works too, including sliding contact. A body is held
    /// when some element of it is displacement-prescribed or sliding (sliding on one plane
    /// alone leaves it free to slide: the condition check refuses that).
    ///
    /// ```
    /// use bem_core::{shapes, Control, ElementKind, LinearSystem, Loads, Material, SolveParams};
    /// use glam::DVec3;
    /// let mesh = shapes::sphere(1, 1.0).unwrap();
    /// let n = mesh.element_count();
    /// // lower cap fixed, a band above it sliding on its support, the top pushed down
    /// let kinds: Vec<ElementKind> = mesh
    ///     .centroids()
    ///     .iter()
    ///     .map(|c| match c.z {
    ///         z if z < -0.5 => ElementKind::Displacement,
    ///         z if z < 0.0 => ElementKind::Sliding,
    ///         _ => ElementKind::Traction,
    ///     })
    ///     .collect();
    /// let mut loads = Loads::new(n, 1);
    /// for e in (0..n).filter(|&e| mesh.centroid(e).z > 0.5) {
    ///     loads.set(e, 0, -0.001 * mesh.normal(e)).unwrap();
    /// }
    /// let m = Material::new(0.45, 1.0).unwrap();
    /// let system = LinearSystem::assemble(&mesh, &m, &kinds, &loads, &SolveParams::default(), &Control::default()).unwrap();
    /// let s = system.solve(&Control::default()).unwrap().remove(0);
    /// // sliding elements stay on their support: no normal displacement
    /// for e in (0..n).filter(|&e| kinds[e] == ElementKind::Sliding) {
    ///     assert!(s.displacement[e].dot(mesh.normal(e)).abs() < 1e-12);
    /// }
    /// ```
    pub fn assemble<K: ElementKinds + ?Sized>(
        mesh: &SurfaceMesh,
        material: &Material,
        kinds: &K,
        loads: &Loads,
        params: &SolveParams,
        control: &Control<'_>,
    ) -> Result<Self, BemError> {
        let n = mesh.element_count();
        let kinds = kinds.kinds_of(n)?;
        let kinds: &[ElementKind] = &kinds;
        let prescribed: Vec<bool> = kinds
            .iter()
            .map(|&k| k == ElementKind::Displacement)
            .collect();
        let held: Vec<bool> = kinds.iter().map(|&k| k != ElementKind::Traction).collect();
        check_lengths(n, kinds, loads)?;
        let gauge_fixed = check_bodies_held(mesh, &held, params.rigid_modes)?;
        control.check()?;
        // assemble in coordinates relative to the mesh's centre: translation invariance
        let local = mesh.recentred();
        let mesh = &local;
        let dof = 3 * n;
        let size = dof + if gauge_fixed { 6 } else { 0 };
        let rhs_count = loads.rhs_count();
        let threads = rayon::current_num_threads().max(1);
        let precision = choose_precision(n, size, rhs_count, threads, params)?;
        let mut matrix = DenseMatrix::zeros(size, size)?;
        let consts = KernelConstants::new(material);
        let quads: Vec<ElementQuad> = (0..n).map(|e| ElementQuad::new(mesh, e)).collect();
        let centroids = mesh.centroids();
        let modes = gauge_fixed.then(|| rigid_mode_rows(mesh));
        let qp = params.quadrature;
        // Columns go to a fixed number of contiguous ranges, each assembled in column order with
        // its own partial row sums, and the partials are added in range order: the result is
        // bit-for-bit the same whatever the thread count or the work stealing did.
        let tasks = ColumnTasks {
            inputs: ColumnInputs {
                quads: &quads,
                centroids,
                consts: &consts,
                qp: &qp,
                mesh,
                material,
                dof,
                modes: modes.as_ref(),
            },
            kinds,
            loads,
            control,
            n,
            rhs_count,
            width: n.div_ceil(REDUCTION_RANGES).max(1),
            done: AtomicUsize::new(0),
            step: (n / 100).max(1),
        };
        control.report(Stage::Assembly, 0, n);
        let (row_sums, quadrature, mut rhs) = tasks.run(&mut matrix, size, threads)?;
        add_diagonal_blocks(&mut matrix, &mut rhs, &row_sums, kinds, loads, mesh);
        control.report(Stage::Assembly, n, n);
        Ok(Self {
            matrix,
            rhs,
            prescribed,
            kinds: kinds.to_vec(),
            normals: mesh.normals().to_vec(),
            loads: loads.clone(),
            gauge_fixed,
            max_condition: params.max_condition,
            quadrature,
            precision,
        })
    }
}

/// The element kinds and the loads must have one entry per element.
fn check_lengths(n: usize, kinds: &[ElementKind], loads: &Loads) -> Result<(), BemError> {
    for (what, got) in [
        ("element kinds", kinds.len()),
        ("loads", loads.element_count()),
    ] {
        if got != n {
            return Err(BemError::WrongLength {
                what,
                expected: n,
                got,
            });
        }
    }
    Ok(())
}

/// The precision of the LU: the mixed-precision LU needs an f32 copy of K besides K; where that
/// does not fit the budget, or K is too small for it to pay, the f64 LU in place does (and then
/// the f64 estimate must fit the budget, [`BemError::OverBudget`]).
fn choose_precision(
    n: usize,
    size: usize,
    rhs_count: usize,
    threads: usize,
    params: &SolveParams,
) -> Result<Precision, BemError> {
    let estimate = MemoryEstimate::new(n, size, rhs_count, threads);
    let mixed_fits = size >= MIXED_MIN_UNKNOWNS
        && estimate
            .with_f32_factor()
            .check(params.memory_budget_bytes)
            .is_ok();
    Ok(if params.precision == Precision::Mixed && mixed_fits {
        Precision::Mixed
    } else {
        estimate.check(params.memory_budget_bytes)?;
        Precision::Double
    })
}

/// The column tasks of one assembly: what they read, and the progress counter they share.
struct ColumnTasks<'a, 'c> {
    inputs: ColumnInputs<'a>,
    kinds: &'a [ElementKind],
    loads: &'a Loads,
    control: &'a Control<'c>,
    /// Number of elements.
    n: usize,
    rhs_count: usize,
    /// Elements (column blocks) per contiguous column range.
    width: usize,
    /// Column blocks assembled so far (for progress reports).
    done: AtomicUsize,
    /// Progress is reported every `step` column blocks.
    step: usize,
}

impl ColumnTasks<'_, '_> {
    /// Assembles every column of K (`size` × `size`) and returns the H row sums, the quadrature
    /// report and the right-hand sides without the diagonal H blocks.
    fn run(
        &self,
        matrix: &mut DenseMatrix,
        size: usize,
        threads: usize,
    ) -> Result<(Vec<Block>, AssemblyReport, Mat<f64>), BemError> {
        // The ranges are assembled in waves of one range per thread, and each wave's partials
        // are added to the totals (in range order) before the next wave starts: at most
        // threads + 1 right-hand-side buffers (the partials of one wave and `rhs`) are alive.
        let chunk_cols = 3 * self.width;
        let chunks = size.div_ceil(chunk_cols);
        let mut row_sums: Vec<Block> = vec![[[0.0; 3]; 3]; self.n];
        let mut quadrature = AssemblyReport::default();
        let mut rhs = try_zeros(size, self.rhs_count)?;
        let mut first = 0;
        while first < chunks {
            let last = (first + threads).min(chunks);
            let c0 = first * chunk_cols;
            let c1 = (last * chunk_cols).min(size);
            let partials: Vec<Option<Partial>> = matrix
                .as_mut()
                .subcols_mut(c0, c1 - c0)
                .par_col_chunks_mut(chunk_cols)
                .enumerate()
                .map(|(kk, range)| self.assemble_range(first + kk, range))
                .collect::<Result<_, _>>()?;
            // add this wave's partials in range order (the same order whatever the wave size)
            for p in partials.into_iter().flatten() {
                add_partial(
                    &mut row_sums,
                    &mut quadrature,
                    &mut rhs,
                    &p,
                    self.inputs.dof,
                )?;
            }
            first = last;
        }
        Ok((row_sums, quadrature, rhs))
    }

    /// Assembles column range `k` (the columns of elements `k · width ..`, then the gauge
    /// columns), in column order; `None` when it holds no element column.
    fn assemble_range(
        &self,
        k: usize,
        mut range: MatMut<'_, f64>,
    ) -> Result<Option<Partial>, BemError> {
        let n = self.n;
        let mut partial: Option<Partial> = None;
        for l in 0..range.ncols() / 3 {
            self.control.check()?;
            let j = k * self.width + l;
            let cols =
                three_columns(range.rb_mut().subcols_mut(3 * l, 3)).ok_or(BemError::Internal {
                    what: "a column block of K is not 3 contiguous columns",
                })?;
            if j >= n {
                // gauge columns: R (rigid modes) in the displacement rows
                if let Some(modes) = self.inputs.modes {
                    for (c, col) in cols.into_iter().enumerate() {
                        let mode = &modes[3 * (j - n) + c];
                        for (e, v) in mode.iter().enumerate() {
                            col[3 * e..3 * e + 3].copy_from_slice(&v.to_array());
                        }
                    }
                }
                continue;
            }
            let partial =
                partial.get_or_insert_with(|| Partial::new(n, self.inputs.dof, self.rhs_count));
            assemble_column(
                j,
                cols,
                &self.inputs,
                self.kinds[j],
                self.loads.of(j),
                partial,
            )?;
            let d = self.done.fetch_add(1, Ordering::Relaxed) + 1;
            if d.is_multiple_of(self.step) || d == n {
                self.control.report(Stage::Assembly, d, n);
            }
        }
        Ok(partial)
    }
}

/// Adds one column range's partial row sums, quadrature report and right-hand sides to the
/// totals.
fn add_partial(
    row_sums: &mut [Block],
    quadrature: &mut AssemblyReport,
    rhs: &mut Mat<f64>,
    p: &Partial,
    dof: usize,
) -> Result<(), BemError> {
    quadrature.merge(&p.quadrature);
    for (t, s) in row_sums.iter_mut().zip(&p.row_sums) {
        for a in 0..3 {
            for b in 0..3 {
                t[a][b] += s[a][b];
            }
        }
    }
    if let Some(y) = &p.rhs {
        for (r, part) in y.chunks_exact(dof.max(1)).enumerate() {
            let col = rhs
                .col_mut(r)
                .try_as_col_major_mut()
                .ok_or(BemError::Internal {
                    what: "a right-hand side is not a contiguous column",
                })?;
            for (t, s) in col.as_slice_mut().iter_mut().zip(part) {
                *t += s;
            }
        }
    }
    Ok(())
}

/// Diagonal H blocks `h_ii = −Σ_{j≠i} h_ij` from the row sums: into K for traction-prescribed
/// elements, into the right-hand sides for the others.
fn add_diagonal_blocks(
    matrix: &mut DenseMatrix,
    rhs: &mut Mat<f64>,
    row_sums: &[Block],
    kinds: &[ElementKind],
    loads: &Loads,
    mesh: &SurfaceMesh,
) {
    for i in 0..kinds.len() {
        let s = row_sums[i];
        let h_ii: Block = std::array::from_fn(|a| std::array::from_fn(|b| -s[a][b]));
        match kinds[i] {
            ElementKind::Displacement => {
                for &(r, u) in loads.of(i) {
                    let hu = block_times(&h_ii, u);
                    for a in 0..3 {
                        rhs[(3 * i + a, r as usize)] -= hu[a];
                    }
                }
            }
            ElementKind::Traction => {
                for a in 0..3 {
                    for b in 0..3 {
                        matrix[(3 * i + a, 3 * i + b)] = h_ii[a][b];
                    }
                }
            }
            ElementKind::Sliding => {
                let normal = mesh.normal(i);
                let (t1, t2) = tangent_frame(normal);
                let (h1, h2) = (block_times(&h_ii, t1), block_times(&h_ii, t2));
                for a in 0..3 {
                    matrix[(3 * i + a, 3 * i + 1)] = h1[a];
                    matrix[(3 * i + a, 3 * i + 2)] = h2[a];
                }
                for &(r, v) in loads.of(i) {
                    let hu = block_times(&h_ii, normal * v.dot(normal));
                    for a in 0..3 {
                        rhs[(3 * i + a, r as usize)] -= hu[a];
                    }
                }
            }
        }
    }
}

/// Every body must be held: some element of it displacement-prescribed or sliding (`held`). A
/// problem with nothing prescribed at all is rejected ([`BemError::PureTraction`]) or, with [`RigidModes::Fix`] and a
/// single body, gauge-fixed (returns true); otherwise a body without prescribed displacement is a
/// [`BemError::FloatingBody`].
fn check_bodies_held(
    mesh: &SurfaceMesh,
    held_mask: &[bool],
    rigid_modes: RigidModes,
) -> Result<bool, BemError> {
    let bodies = mesh.body_count();
    if !held_mask.iter().any(|&p| p) {
        match rigid_modes {
            RigidModes::Reject => return Err(BemError::PureTraction),
            RigidModes::Fix if bodies <= 1 => return Ok(true),
            RigidModes::Fix => {} // six gauge conditions cannot hold several bodies
        }
    }
    let mut held = vec![false; bodies];
    let mut first = vec![usize::MAX; bodies];
    for (e, &p) in held_mask.iter().enumerate() {
        let b = mesh.body(e);
        held[b] |= p;
        first[b] = first[b].min(e);
    }
    match held.iter().position(|&h| !h) {
        Some(body) => Err(BemError::FloatingBody {
            body,
            element: first[body],
            bodies,
        }),
        None => Ok(false),
    }
}
