//! Mixed-precision solve: the LU in f32, the answer refined to f64 accuracy.
//!
//! Nearly all of a dense solve's time is the LU's matrix products, and f32 products run twice
//! as fast as f64 ones (twice the lanes per vector register). [`MixedLu`] factorises a single-
//! precision copy of K, keeps K itself, and solves by iterative refinement (Wilkinson; LAPACK's
//! `dsgesv`): x ← x + LU⁻¹(b − K x), the residual in f64, until the residual is as small as an
//! f64 LU's backward error (‖r‖∞ ≤ √n · ε₆₄ · ‖K‖∞ ‖x‖∞ per column). Each round gains about
//! −log₁₀(κ · ε₃₂) digits, so it converges when κ ≪ 1/ε₃₂ ≈ 1.7e7; the bundled faces' K have
//! κ ≈ 2e3–5.5e4 and converge in 2–4 rounds. Where it does not (the f32 factor is singular, the
//! condition estimate is above [`MAX_MIXED_CONDITION`] or the refinement stalls), the caller
//! falls back to the f64 LU ([`crate::Precision`]). The f32 copy costs 4 bytes per entry on
//! top of K's 8.

use faer::linalg::matmul::matmul;
use faer::prelude::Reborrow;
use faer::{Accum, Mat, MatMut, MatRef, Par};
use rayon::prelude::*;

use crate::dense::{check_rhs_rows, column_norms, factor_blocked, pivot_check, solve_factored};
use crate::{BemError, Control, DenseMatrix};

/// Above this condition estimate (of the f32 factor) the mixed solve is not attempted: with
/// κ · ε₃₂ above about 0.1 the refinement gains under a digit a round. The bundled faces'
/// copies: 2e3 (MediaPipe) to 5.5e4 (ICT 13k).
pub const MAX_MIXED_CONDITION: f64 = 1e6;

/// Smallest K (unknowns) solved in mixed precision by default ([`crate::Precision::Mixed`]):
/// below it the f32 copy and the refinement cost what the faster factorisation saves.
/// Measured (`cargo run --release -p bem-core --example mixed_bench`, 2 cores): 2 976 unknowns
/// 0.14 s mixed against 0.12 s f64; 9 576 unknowns 2.3 s against 3.4 s.
pub const MIXED_MIN_UNKNOWNS: usize = 4000;

/// Most refinement rounds before the solve counts as stalled (LAPACK's `dsgesv`: 30).
const MAX_ROUNDS: usize = 30;

/// K in f64 with an LU factorisation of its f32 copy.
#[derive(Debug)]
pub struct MixedLu {
    matrix: DenseMatrix,
    lu: Vec<f32>,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
    col_norms: Vec<f64>,
    norm_inf: f64,
    usable: bool,
}

impl MixedLu {
    /// Copies `matrix` to f32 and factorises the copy (progress and cancellation as
    /// [`crate::DenseLu::factor_with`]); `matrix` is kept for the refinement. Fails on
    /// non-finite entries, a zero column, cancellation, or when the f32 copy cannot be
    /// allocated; a numerically singular f32 factor is not an error but makes the result
    /// unusable ([`MixedLu::is_usable`]): fall back with [`MixedLu::into_matrix`].
    ///
    /// ```
    /// let a = faer::mat![[4.0, 1.0], [2.0, 3.0]];
    /// let lu = bem_core::MixedLu::factor_with(a.into(), &bem_core::Control::default()).unwrap();
    /// assert!(lu.is_usable());
    /// let mut b = faer::mat![[1.0], [2.0]];
    /// let rounds = lu.solve_in_place(b.as_mut()).unwrap();
    /// assert!(rounds >= 1);
    /// assert!((4.0 * b[(0, 0)] + b[(1, 0)] - 1.0).abs() < 1e-15);
    /// ```
    pub fn factor_with(matrix: DenseMatrix, control: &Control<'_>) -> Result<Self, BemError> {
        let n = matrix.nrows();
        let col_norms = column_norms(&matrix)?;
        let len = n * n;
        let mut lu: Vec<f32> = Vec::new();
        lu.try_reserve_exact(len)
            .map_err(|_| BemError::OutOfMemory {
                rows: n,
                cols: n,
                bytes: len.saturating_mul(4),
            })?;
        lu.resize(len, 0.0);
        lu.par_chunks_mut(1 << 16)
            .zip(matrix.as_slice().par_chunks(1 << 16))
            .for_each(|(dst, src)| {
                for (d, &s) in dst.iter_mut().zip(src) {
                    *d = s as f32;
                }
            });
        // ‖K‖∞, the largest row sum, accumulated column by column (K is column-major).
        let row_sums = matrix
            .as_slice()
            .par_chunks(n.max(1) * 64)
            .map(|columns| {
                let mut rows = vec![0.0f64; n];
                for column in columns.chunks(n.max(1)) {
                    for (r, v) in rows.iter_mut().zip(column) {
                        *r += v.abs();
                    }
                }
                rows
            })
            .reduce(
                || vec![0.0f64; n],
                |mut a, b| {
                    for (x, y) in a.iter_mut().zip(b) {
                        *x += y;
                    }
                    a
                },
            );
        let norm_inf = row_sums.into_iter().fold(0.0f64, f64::max);
        let perm = factor_blocked(MatMut::from_column_major_slice_mut(&mut lu, n, n), control)?;
        let mut perm_inv = vec![0usize; n];
        for (i, &p) in perm.iter().enumerate() {
            perm_inv[p] = i;
        }
        let factors = MatRef::from_column_major_slice(&lu, n, n);
        // Unusable where a pivot is lost in f32's rounding (below ε₃₂ of the largest); smaller
        // spreads than an f64 LU would accept are left to the condition estimate and the
        // refinement (ICT 13k's copy: pivots down to 1e-3 of the largest, κ 2e4, converges).
        let usable = pivot_check(
            |k| factors[(k, k)] as f64,
            &col_norms,
            f32::EPSILON as f64 / n.max(1) as f64,
        )
        .is_ok();
        Ok(Self {
            matrix,
            lu,
            perm,
            perm_inv,
            col_norms,
            norm_inf,
            usable,
        })
    }

    /// Whether the f32 factor can be used (no pivot below n·ε₃₂ of the largest).
    pub fn is_usable(&self) -> bool {
        self.usable
    }

    /// K itself, for the f64 fallback.
    pub fn into_matrix(self) -> DenseMatrix {
        self.matrix
    }

    /// Dimension n.
    pub fn dim(&self) -> usize {
        self.matrix.nrows()
    }

    fn factors(&self) -> MatRef<'_, f32> {
        MatRef::from_column_major_slice(&self.lu, self.dim(), self.dim())
    }

    /// One f32 solve of `rhs` (f64 in and out), transposed or not.
    fn solve32(&self, rhs: MatRef<'_, f64>, transpose: bool) -> Mat<f64> {
        let mut x = Mat::<f32>::from_fn(rhs.nrows(), rhs.ncols(), |i, j| rhs[(i, j)] as f32);
        solve_factored(
            self.factors(),
            &self.perm,
            &self.perm_inv,
            x.as_mut(),
            transpose,
        );
        Mat::<f64>::from_fn(x.nrows(), x.ncols(), |i, j| x[(i, j)] as f64)
    }

    /// Solves `K X = B` for all columns of `rhs` to f64 accuracy by iterative refinement,
    /// overwriting `rhs` with X; returns the rounds it took. Fails with
    /// [`BemError::RefinementStalled`] (rhs unchanged) when the residual stops shrinking, and
    /// on a non-finite solution.
    pub fn solve_in_place(&self, mut rhs: MatMut<'_, f64>) -> Result<usize, BemError> {
        let n = self.dim();
        check_rhs_rows(n, rhs.nrows())?;
        let k = rhs.ncols();
        let par = Par::rayon(0);
        let tolerance = (n as f64).sqrt() * f64::EPSILON * self.norm_inf;
        let mut x = self.solve32(rhs.rb(), false);
        let mut residual = Mat::<f64>::zeros(n, k);
        let mut previous = f64::INFINITY;
        for round in 1..=MAX_ROUNDS {
            // r = b − K x
            residual.copy_from(rhs.rb());
            matmul(
                residual.as_mut(),
                Accum::Add,
                self.matrix.as_ref(),
                x.as_ref(),
                -1.0,
                par,
            );
            let mut worst: f64 = 0.0;
            let mut converged = true;
            for j in 0..k {
                let r = residual.col(j).iter().fold(0.0f64, |m, v| m.max(v.abs()));
                let xn = x.col(j).iter().fold(0.0f64, |m, v| m.max(v.abs()));
                if !(r.is_finite() && xn.is_finite()) {
                    return Err(BemError::NonFinite { what: "solution" });
                }
                if r > tolerance * xn {
                    converged = false;
                }
                worst = worst.max(if xn > 0.0 { r / xn } else { r });
            }
            if converged {
                rhs.copy_from(x.as_ref());
                return Ok(round);
            }
            // Stalled: the residual no longer shrinks by half a round.
            if worst > 0.5 * previous {
                break;
            }
            previous = worst;
            let d = self.solve32(residual.as_ref(), false);
            x += d;
        }
        Err(BemError::RefinementStalled { rounds: MAX_ROUNDS })
    }

    /// Hager–Higham estimate of κ₁ of K with unit-1-norm columns, as
    /// [`crate::DenseLu::condition_estimate`], from the f32 factor (unrefined solves: an
    /// estimate within the estimator's own factor of about 3 while κ · ε₃₂ ≪ 1).
    pub fn condition_estimate(&self) -> Result<f64, BemError> {
        crate::dense::hager_higham(
            self.dim(),
            &self.col_norms,
            |mut m| {
                let x = self.solve32(m.rb(), false);
                m.copy_from(x.as_ref());
            },
            |mut m| {
                let x = self.solve32(m.rb(), true);
                m.copy_from(x.as_ref());
            },
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::DenseLu;

    /// A dense, unsymmetric, well-conditioned test matrix (diagonally weighted).
    fn matrix(n: usize) -> Mat<f64> {
        Mat::from_fn(n, n, |i, j| {
            let x = ((i * 7 + j * 13) % 17) as f64 / 17.0 - 0.5;
            if i == j {
                x + 4.0
            } else {
                x / (1.0 + (i as f64 - j as f64).abs())
            }
        })
    }

    #[test]
    fn refined_solution_matches_the_f64_lu() {
        let n = 300;
        let a = matrix(n);
        let b = Mat::<f64>::from_fn(n, 3, |i, j| ((i + 3 * j) % 5) as f64 - 2.0);
        let mut x64 = b.clone();
        DenseLu::factor(a.clone())
            .unwrap()
            .solve_in_place(x64.as_mut())
            .unwrap();
        let lu = MixedLu::factor_with(a.into(), &Control::default()).unwrap();
        assert!(lu.is_usable());
        let mut x = b.clone();
        let rounds = lu.solve_in_place(x.as_mut()).unwrap();
        assert!((1..=6).contains(&rounds), "{rounds} rounds");
        let diff = (0..3)
            .flat_map(|j| (0..n).map(move |i| (i, j)))
            .map(|(i, j)| (x[(i, j)] - x64[(i, j)]).abs())
            .fold(0.0f64, f64::max);
        assert!(diff < 1e-13, "differs from the f64 LU by {diff:e}");
        // Its condition estimate agrees with the f64 LU's within the estimator's accuracy.
        let k32 = lu.condition_estimate().unwrap();
        let k64 = DenseLu::factor(lu.into_matrix())
            .unwrap()
            .condition_estimate()
            .unwrap();
        assert!((k32 / k64 - 1.0).abs() < 1e-3, "{k32} against {k64}");
    }

    #[test]
    fn a_matrix_singular_in_f32_is_not_usable() {
        // Exactly singular once rounded to f32; fine (κ ≈ 4e9) in f64.
        let a = faer::mat![[1.0, 1.0], [1.0, 1.0 + 1e-9]];
        let lu = MixedLu::factor_with(a.clone().into(), &Control::default()).unwrap();
        assert!(!lu.is_usable());
        // The f64 fallback still solves it.
        let mut b = faer::mat![[2.0], [2.0 + 1e-9]];
        DenseLu::factor(lu.into_matrix())
            .unwrap()
            .solve_in_place(b.as_mut())
            .unwrap();
        assert!((b[(0, 0)] - 1.0).abs() < 1e-6 && (b[(1, 0)] - 1.0).abs() < 1e-6);
    }

    #[test]
    fn non_finite_entries_and_wrong_shapes_are_refused() {
        let a = faer::mat![[1.0, f64::NAN], [0.0, 1.0]];
        assert!(matches!(
            MixedLu::factor_with(a.into(), &Control::default()),
            Err(BemError::NonFinite { .. })
        ));
        let lu = MixedLu::factor_with(faer::mat![[2.0]].into(), &Control::default()).unwrap();
        let mut b = Mat::<f64>::zeros(2, 1);
        assert!(matches!(
            lu.solve_in_place(b.as_mut()),
            Err(BemError::WrongLength { .. })
        ));
    }
}
