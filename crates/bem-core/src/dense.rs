//! Dense LU with partial pivoting (faer), in place, with singularity detection.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::{factor, solve};
use faer::linalg::matmul::matmul;
use faer::linalg::triangular_solve::solve_unit_lower_triangular_in_place;
use faer::perm::PermRef;
use faer::prelude::{Reborrow, ReborrowMut};
use faer::{Accum, MatMut, MatRef, Par};
use rayon::prelude::*;

use crate::{BemError, Control, DenseMatrix, Stage};

/// Columns per panel of the blocked LU (progress and cancellation granularity).
pub const LU_PANEL: usize = 256;

/// Pivots smaller than this × n × the largest pivot mark the matrix numerically singular (both
/// measured relative to the 1-norm of their column of A, so the test does not depend on units).
const SINGULAR_PIVOT_RATIO: f64 = f64::EPSILON;

/// An LU factorisation `P A = L U` of a square dense matrix, computed in place.
#[derive(Debug, Clone)]
pub struct DenseLu {
    lu: DenseMatrix,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
    /// 1-norm of each column of A (before factorisation): the column equilibration under which
    /// pivots are compared and the condition number is estimated.
    col_norms: Vec<f64>,
}

/// Scalars the blocked LU runs in: `f64` ([`DenseLu`]) and `f32` (the factor of
/// [`crate::MixedLu`]).
pub(crate) trait LuScalar:
    faer::traits::ComplexField + Copy + Send + Sync + 'static
{
    /// −1 in this precision (the trailing update's factor).
    const MINUS_ONE: Self;
}

impl LuScalar for f64 {
    const MINUS_ONE: f64 = -1.0;
}

impl LuScalar for f32 {
    const MINUS_ONE: f32 = -1.0;
}

/// Right-looking blocked LU with partial pivoting of the square `matrix`, in place: each panel
/// of [`LU_PANEL`] columns is factorised with faer's recursive partial-pivoting LU, its row
/// interchanges are applied to the other columns, then the trailing matrix is updated with
/// faer's parallel triangular solve and matrix product (where nearly all the flops are).
/// Returns the row permutation (row `i` of the factors is row `perm[i]` of the input).
/// Progress (`Stage::Factorisation`, columns) and cancellation between panels.
pub(crate) fn factor_blocked<T: LuScalar>(
    mut matrix: MatMut<'_, T>,
    control: &Control<'_>,
) -> Result<Vec<usize>, BemError> {
    let n = matrix.nrows();
    let par = Par::rayon(0);
    let mut perm: Vec<usize> = (0..n).collect();
    let mut panel_perm = vec![0usize; n];
    let mut panel_perm_inv = vec![0usize; n];
    let mut at = vec![0usize; n]; // panel-local row currently at each position
    let mut position = vec![0usize; n]; // position of each panel-local row
    let mut swaps: Vec<(usize, usize)> = Vec::with_capacity(LU_PANEL);
    let mut buf = MemBuffer::new(factor::lu_in_place_scratch::<usize, T>(
        n,
        LU_PANEL,
        par,
        Default::default(),
    ));
    let mut k = 0;
    while k < n {
        control.check()?;
        control.report(Stage::Factorisation, k, n);
        let nb = LU_PANEL.min(n - k);
        let m = n - k;
        {
            let panel = matrix.rb_mut().submatrix_mut(k, k, m, nb);
            let stack = MemStack::new(&mut buf);
            let _ = factor::lu_in_place(
                panel,
                &mut panel_perm[..m],
                &mut panel_perm_inv[..m],
                par,
                stack,
                Default::default(),
            );
        }
        // the panel's row permutation as the sequence of interchanges that produced it
        swaps.clear();
        for i in 0..m {
            at[i] = i;
            position[i] = i;
        }
        for i in 0..nb {
            let row = panel_perm[i];
            let j = position[row];
            if j != i {
                swaps.push((k + i, k + j));
                let displaced = at[i];
                at.swap(i, j);
                position[displaced] = j;
                position[row] = i;
            }
        }
        for &(i, j) in &swaps {
            perm.swap(i, j);
        }
        if !swaps.is_empty() {
            let chunk = 32;
            matrix
                .rb_mut()
                .par_col_chunks_mut(chunk)
                .enumerate()
                .for_each(|(c, block)| {
                    for (l, col) in block.col_iter_mut().enumerate() {
                        let column = c * chunk + l;
                        if (k..k + nb).contains(&column) {
                            continue;
                        }
                        if let Some(col) = col.try_as_col_major_mut() {
                            let col = col.as_slice_mut();
                            for &(i, j) in &swaps {
                                col.swap(i, j);
                            }
                        }
                    }
                });
        }
        if nb < m {
            let rest = matrix.rb_mut().submatrix_mut(k, k, m, m);
            let (l11, mut a12, l21, a22) = rest.split_at_mut(nb, nb);
            solve_unit_lower_triangular_in_place(l11.rb(), a12.rb_mut(), par);
            matmul(a22, Accum::Add, l21.rb(), a12.rb(), T::MINUS_ONE, par);
        }
        k += nb;
    }
    Ok(perm)
}

/// Solves `A X = B` (or `Aᵀ X = B` when `transpose`) in place in `rhs` with the factors `lu`
/// of [`factor_blocked`] and its permutation.
pub(crate) fn solve_factored<T: LuScalar>(
    lu: MatRef<'_, T>,
    perm: &[usize],
    perm_inv: &[usize],
    rhs: MatMut<'_, T>,
    transpose: bool,
) {
    let n = lu.nrows();
    let par = Par::rayon(0);
    let perm = PermRef::new_checked(perm, perm_inv, n);
    if transpose {
        let mut buf = MemBuffer::new(solve::solve_transpose_in_place_scratch::<usize, T>(
            n,
            rhs.ncols(),
            par,
        ));
        solve::solve_transpose_in_place(lu, lu, perm, rhs, par, MemStack::new(&mut buf));
    } else {
        let mut buf = MemBuffer::new(solve::solve_in_place_scratch::<usize, T>(
            n,
            rhs.ncols(),
            par,
        ));
        solve::solve_in_place(lu, lu, perm, rhs, par, MemStack::new(&mut buf));
    }
}

/// Finite entries and the 1-norm of each column of a square matrix (the column equilibration
/// under which pivots are compared and the condition number is estimated). Fails with
/// [`BemError::WrongLength`] for a non-square matrix, [`BemError::NonFinite`] on NaN/inf and
/// [`BemError::Singular`] on a zero column.
pub(crate) fn column_norms(matrix: &DenseMatrix) -> Result<Vec<f64>, BemError> {
    let n = matrix.nrows();
    if matrix.ncols() != n {
        return Err(BemError::WrongLength {
            what: "columns of a square matrix",
            expected: n,
            got: matrix.ncols(),
        });
    }
    let finite = matrix
        .as_slice()
        .par_chunks(1 << 16)
        .all(|c| c.iter().all(|v| v.is_finite()));
    if !finite {
        return Err(BemError::NonFinite {
            what: "system matrix",
        });
    }
    let col_norms: Vec<f64> = if n == 0 {
        Vec::new()
    } else {
        matrix
            .as_slice()
            .par_chunks(n)
            .map(|c| c.iter().map(|v| v.abs()).sum())
            .collect()
    };
    if let Some(index) = col_norms.iter().position(|&c| c == 0.0) {
        return Err(BemError::Singular {
            index,
            pivot: 0.0,
            max_pivot: 0.0,
        });
    }
    Ok(col_norms)
}

/// Fails with [`BemError::WrongLength`] unless a right-hand side has `n` rows.
pub(crate) fn check_rhs_rows(n: usize, rows: usize) -> Result<(), BemError> {
    if rows != n {
        return Err(BemError::WrongLength {
            what: "rows of the right-hand side",
            expected: n,
            got: rows,
        });
    }
    Ok(())
}

/// Fails with [`BemError::Singular`] when a pivot `diag(k)` of the factors, relative to its
/// column's 1-norm, is non-finite or below `ratio · n` times the largest one (partial pivoting
/// chooses the same rows for A and the column-equilibrated A D, whose U is U D).
pub(crate) fn pivot_check(
    diag: impl Fn(usize) -> f64,
    col_norms: &[f64],
    ratio: f64,
) -> Result<(), BemError> {
    let n = col_norms.len();
    let (mut min, mut min_index, mut max) = (f64::INFINITY, 0, 0.0f64);
    for (k, &norm) in col_norms.iter().enumerate() {
        let p = diag(k).abs() / norm;
        if !p.is_finite() {
            // finite input, non-finite factor: a zero pivot was divided by
            return Err(BemError::Singular {
                index: k,
                pivot: 0.0,
                max_pivot: max,
            });
        }
        if p < min {
            min = p;
            min_index = k;
        }
        max = max.max(p);
    }
    if n > 0 && min <= ratio * n as f64 * max {
        return Err(BemError::Singular {
            index: min_index,
            pivot: min,
            max_pivot: max,
        });
    }
    Ok(())
}

/// Hager–Higham estimate (Higham 1988, LAPACK's `xLACN2`) of `κ₁(A D)` for an `n × n` matrix A
/// with column 1-norms `norms` (`D = diag(1/norms)`), given in-place solves with A (`solve`)
/// and Aᵀ (`solve_t`) of an `n × 1` right-hand side.
pub(crate) fn hager_higham(
    n: usize,
    norms: &[f64],
    solve: impl Fn(MatMut<'_, f64>),
    solve_t: impl Fn(MatMut<'_, f64>),
) -> Result<f64, BemError> {
    if n == 0 {
        return Ok(0.0);
    }
    // B = D⁻¹ A⁻¹:  B x = diag(norms) A⁻¹ x,  Bᵀ y = A⁻ᵀ diag(norms) y
    let apply = |x: &[f64]| -> Result<Vec<f64>, BemError> {
        let mut m = faer::Mat::<f64>::from_fn(n, 1, |i, _| x[i]);
        solve(m.as_mut());
        if m.col(0).iter().any(|v| !v.is_finite()) {
            return Err(BemError::NonFinite { what: "solution" });
        }
        Ok((0..n).map(|i| m[(i, 0)] * norms[i]).collect())
    };
    let apply_t = |y: &[f64]| -> Result<Vec<f64>, BemError> {
        let mut m = faer::Mat::<f64>::from_fn(n, 1, |i, _| y[i] * norms[i]);
        solve_t(m.as_mut());
        if m.col(0).iter().any(|v| !v.is_finite()) {
            return Err(BemError::NonFinite { what: "solution" });
        }
        Ok((0..n).map(|i| m[(i, 0)]).collect())
    };
    let norm1 = |v: &[f64]| v.iter().map(|x| x.abs()).sum::<f64>();
    let sign = |v: &[f64]| -> Vec<f64> {
        v.iter()
            .map(|&x| if x >= 0.0 { 1.0 } else { -1.0 })
            .collect()
    };
    let argmax = |v: &[f64]| -> usize {
        let mut best = 0;
        for (i, x) in v.iter().enumerate() {
            if x.abs() > v[best].abs() {
                best = i;
            }
        }
        best
    };
    let y = apply(&vec![1.0 / n as f64; n])?;
    let mut estimate = norm1(&y);
    if n > 1 {
        let mut xi = sign(&y);
        let mut z = apply_t(&xi)?;
        let mut j = argmax(&z);
        for _ in 0..4 {
            let mut e = vec![0.0; n];
            e[j] = 1.0;
            let y = apply(&e)?;
            let previous = estimate;
            estimate = norm1(&y);
            let new_xi = sign(&y);
            if new_xi == xi || estimate <= previous {
                estimate = estimate.max(previous);
                break;
            }
            xi = new_xi;
            z = apply_t(&xi)?;
            let last = j;
            j = argmax(&z);
            if z[j].abs() == z[last].abs() {
                break;
            }
        }
        // Higham's extra vector guards against the rare matrices that fool the iteration
        let alt: Vec<f64> = (0..n)
            .map(|i| {
                let s = if i % 2 == 0 { 1.0 } else { -1.0 };
                s * (1.0 + i as f64 / (n - 1) as f64)
            })
            .collect();
        let y = apply(&alt)?;
        estimate = estimate.max(2.0 * norm1(&y) / (3.0 * n as f64));
    }
    Ok(estimate)
}

impl DenseLu {
    /// Factorises `matrix` in place with partial pivoting on all rayon threads (a `faer::Mat` is
    /// copied into a [`DenseMatrix`] first; a `DenseMatrix` is used as is).
    ///
    /// Fails with [`BemError::NonFinite`] on NaN/inf entries and [`BemError::Singular`] when a pivot
    /// is below `n·ε` times the largest one (the solve would return garbage or NaNs).
    ///
    /// ```
    /// let a = faer::mat![[4.0, 1.0], [2.0, 3.0]];
    /// let lu = bem_core::DenseLu::factor(a).unwrap();
    /// let mut b = faer::mat![[1.0], [2.0]];
    /// lu.solve_in_place(b.as_mut()).unwrap();
    /// assert!((4.0 * b[(0, 0)] + b[(1, 0)] - 1.0).abs() < 1e-14);
    /// assert!(bem_core::DenseLu::factor(faer::mat![[1.0, 2.0], [2.0, 4.0]]).is_err());
    /// ```
    pub fn factor(matrix: impl Into<DenseMatrix>) -> Result<Self, BemError> {
        Self::factor_with(matrix, &Control::default())
    }

    /// [`DenseLu::factor`] with progress (`Stage::Factorisation`, done/total = columns) and
    /// cancellation between panels.
    ///
    /// Right-looking blocked LU: each panel of [`LU_PANEL`] columns is factorised with faer's
    /// recursive partial-pivoting LU, its row interchanges are applied to the other columns, then
    /// the trailing matrix is updated with faer's parallel triangular solve and matrix product
    /// (where nearly all the flops are).
    pub fn factor_with(
        matrix: impl Into<DenseMatrix>,
        control: &Control<'_>,
    ) -> Result<Self, BemError> {
        let mut matrix: DenseMatrix = matrix.into();
        let col_norms = column_norms(&matrix)?;
        let n = matrix.nrows();
        let perm = factor_blocked(matrix.as_mut(), control)?;
        control.report(Stage::Factorisation, n, n);
        pivot_check(|k| matrix[(k, k)], &col_norms, SINGULAR_PIVOT_RATIO)?;
        let mut perm_inv = vec![0usize; n];
        for (i, &p) in perm.iter().enumerate() {
            perm_inv[p] = i;
        }
        Ok(Self {
            lu: matrix,
            perm,
            perm_inv,
            col_norms,
        })
    }

    /// Dimension n.
    pub fn dim(&self) -> usize {
        self.lu.nrows()
    }

    /// Solves `A X = B` for all columns of `rhs` at once, overwriting `rhs` with X.
    pub fn solve_in_place(&self, rhs: MatMut<'_, f64>) -> Result<(), BemError> {
        self.solve_either(rhs, false)
    }

    /// Solves `Aᵀ X = B` for all columns of `rhs` at once, overwriting `rhs` with X.
    pub fn solve_transpose_in_place(&self, rhs: MatMut<'_, f64>) -> Result<(), BemError> {
        self.solve_either(rhs, true)
    }

    fn solve_either(&self, mut rhs: MatMut<'_, f64>, transpose: bool) -> Result<(), BemError> {
        check_rhs_rows(self.dim(), rhs.nrows())?;
        solve_factored(
            self.lu.as_ref(),
            &self.perm,
            &self.perm_inv,
            rhs.rb_mut(),
            transpose,
        );
        let finite = rhs.rb().col_iter().all(|c| c.iter().all(|v| v.is_finite()));
        if !finite {
            return Err(BemError::NonFinite { what: "solution" });
        }
        Ok(())
    }

    /// Estimate of the 1-norm condition number `κ₁(A D) = ‖A D‖₁ ‖(A D)⁻¹‖₁` of the matrix with
    /// its columns scaled to unit 1-norm (`D = diag(1/‖a_k‖₁)`, so `‖A D‖₁ = 1`), by the
    /// Hager–Higham estimator (Higham 1988, LAPACK's `xLACN2`): a handful of solves with A and
    /// Aᵀ, O(n²) each. The estimate is a lower bound of the true κ₁, usually within a factor 3.
    ///
    /// The column scaling makes it independent of the units of the unknowns (in the BEM,
    /// displacement columns are dimensionless and traction columns carry length / modulus), and by
    /// van der Sluis' theorem it is within √n of the best κ₁ over all column scalings. `κ · ε`
    /// bounds the relative error the LU introduces into a solution: 1e8 costs 8 of 16 digits.
    ///
    /// ```
    /// let a = faer::mat![[1.0, 1.0], [1.0, 1.0 + 1e-9]];
    /// let lu = bem_core::DenseLu::factor(a).unwrap();
    /// let kappa = lu.condition_estimate().unwrap();
    /// assert!(kappa > 1e9 && kappa < 1e10);
    /// ```
    pub fn condition_estimate(&self) -> Result<f64, BemError> {
        let n = self.dim();
        if n == 0 {
            return Ok(0.0);
        }
        hager_higham(
            n,
            &self.col_norms,
            |m| {
                // infallible for the right row count: the check is in solve_in_place
                let _ = self.solve_in_place(m);
            },
            |m| {
                let _ = self.solve_transpose_in_place(m);
            },
        )
    }
}
