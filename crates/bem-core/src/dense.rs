//! Dense LU with partial pivoting (faer), in place, with singularity detection.

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::lu::partial_pivoting::{factor, solve};
use faer::perm::PermRef;
use faer::prelude::{Reborrow, ReborrowMut};
use faer::{Mat, MatMut, Par};
use rayon::prelude::*;

use crate::BemError;

/// Pivots smaller than this × n × the largest pivot mark the matrix numerically singular.
const SINGULAR_PIVOT_RATIO: f64 = f64::EPSILON;

/// An LU factorisation `P A = L U` of a square dense matrix, computed in place.
#[derive(Debug, Clone)]
pub struct DenseLu {
    lu: Mat<f64>,
    perm: Vec<usize>,
    perm_inv: Vec<usize>,
}

impl DenseLu {
    /// Factorises `matrix` in place with partial pivoting on all rayon threads.
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
    pub fn factor(mut matrix: Mat<f64>) -> Result<Self, BemError> {
        let n = matrix.nrows();
        if matrix.ncols() != n {
            return Err(BemError::WrongLength {
                what: "columns of a square matrix",
                expected: n,
                got: matrix.ncols(),
            });
        }
        let finite = matrix
            .par_col_chunks_mut(1)
            .all(|c| c.col_iter().all(|c| c.iter().all(|v| v.is_finite())));
        if !finite {
            return Err(BemError::NonFinite {
                what: "system matrix",
            });
        }
        let par = Par::rayon(0);
        let mut perm = vec![0usize; n];
        let mut perm_inv = vec![0usize; n];
        let mut buf = MemBuffer::new(factor::lu_in_place_scratch::<usize, f64>(
            n,
            n,
            par,
            Default::default(),
        ));
        let stack = MemStack::new(&mut buf);
        let _ = factor::lu_in_place(
            matrix.as_mut(),
            &mut perm,
            &mut perm_inv,
            par,
            stack,
            Default::default(),
        );
        let (mut min, mut min_index, mut max) = (f64::INFINITY, 0, 0.0f64);
        for k in 0..n {
            let p = matrix[(k, k)].abs();
            if !p.is_finite() {
                return Err(BemError::NonFinite { what: "LU factor" });
            }
            if p < min {
                min = p;
                min_index = k;
            }
            max = max.max(p);
        }
        // written so that a NaN pivot also counts as singular
        if n > 0 && (min.is_nan() || min <= SINGULAR_PIVOT_RATIO * n as f64 * max) {
            return Err(BemError::Singular {
                index: min_index,
                pivot: min,
                max_pivot: max,
            });
        }
        Ok(Self {
            lu: matrix,
            perm,
            perm_inv,
        })
    }

    /// Dimension n.
    pub fn dim(&self) -> usize {
        self.lu.nrows()
    }

    /// Solves `A X = B` for all columns of `rhs` at once, overwriting `rhs` with X.
    pub fn solve_in_place(&self, mut rhs: MatMut<'_, f64>) -> Result<(), BemError> {
        let n = self.dim();
        if rhs.nrows() != n {
            return Err(BemError::WrongLength {
                what: "rows of the right-hand side",
                expected: n,
                got: rhs.nrows(),
            });
        }
        let par = Par::rayon(0);
        let mut buf = MemBuffer::new(solve::solve_in_place_scratch::<usize, f64>(
            n,
            rhs.ncols(),
            par,
        ));
        let stack = MemStack::new(&mut buf);
        let perm = PermRef::new_checked(&self.perm, &self.perm_inv, n);
        let lu = self.lu.as_ref();
        solve::solve_in_place(lu, lu, perm, rhs.rb_mut(), par, stack);
        let finite = rhs.rb().col_iter().all(|c| c.iter().all(|v| v.is_finite()));
        if !finite {
            return Err(BemError::NonFinite { what: "solution" });
        }
        Ok(())
    }
}
