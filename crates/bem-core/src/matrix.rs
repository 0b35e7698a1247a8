//! Owned column-major dense matrix whose zero pages are mapped lazily.

use faer::{Mat, MatMut, MatRef};

use crate::BemError;

/// Column-major dense f64 matrix for K and its LU factors.
///
/// Unlike `faer::Mat::zeros`, which writes every zero on one thread, the storage comes zeroed from
/// the allocator (`calloc`/fresh pages), so the pages of a 0.7 GB K are first touched by the
/// parallel column-block assembly instead of a serial fill (about a third of the assembly time at
/// 3000 elements). faer views are free: [`DenseMatrix::as_ref`] / [`DenseMatrix::as_mut`].
#[derive(Debug, Clone, PartialEq)]
pub struct DenseMatrix {
    data: Vec<f64>,
    nrows: usize,
    ncols: usize,
}

impl DenseMatrix {
    /// A zero matrix; fails with [`BemError::OutOfMemory`] instead of aborting when it cannot be
    /// allocated.
    pub fn zeros(nrows: usize, ncols: usize) -> Result<Self, BemError> {
        let len = nrows.checked_mul(ncols);
        let oom = BemError::OutOfMemory {
            rows: nrows,
            cols: ncols,
            bytes: len.map_or(usize::MAX, |l| l.saturating_mul(8)),
        };
        let len = len.ok_or(oom.clone())?;
        // probe: reserving address space is fallible and touches nothing
        let mut probe: Vec<f64> = Vec::new();
        probe.try_reserve_exact(len).map_err(|_| oom)?;
        drop(probe);
        // zeroed allocation: pages are materialised on first write
        let data = vec![0.0; len];
        Ok(Self { data, nrows, ncols })
    }

    /// Number of rows.
    pub fn nrows(&self) -> usize {
        self.nrows
    }

    /// Number of columns.
    pub fn ncols(&self) -> usize {
        self.ncols
    }

    /// Column-major storage.
    pub fn as_slice(&self) -> &[f64] {
        &self.data
    }

    /// faer view.
    pub fn as_ref(&self) -> MatRef<'_, f64> {
        MatRef::from_column_major_slice(&self.data, self.nrows, self.ncols)
    }

    /// Mutable faer view.
    pub fn as_mut(&mut self) -> MatMut<'_, f64> {
        MatMut::from_column_major_slice_mut(&mut self.data, self.nrows, self.ncols)
    }
}

impl From<&Mat<f64>> for DenseMatrix {
    fn from(m: &Mat<f64>) -> Self {
        let (nrows, ncols) = (m.nrows(), m.ncols());
        let mut data = Vec::with_capacity(nrows * ncols);
        for j in 0..ncols {
            data.extend(m.col(j).iter().copied());
        }
        Self { data, nrows, ncols }
    }
}

impl From<Mat<f64>> for DenseMatrix {
    fn from(m: Mat<f64>) -> Self {
        Self::from(&m)
    }
}

impl std::ops::Index<(usize, usize)> for DenseMatrix {
    type Output = f64;

    fn index(&self, (i, j): (usize, usize)) -> &f64 {
        assert!(
            i < self.nrows && j < self.ncols,
            "index ({i}, {j}) out of bounds"
        );
        &self.data[j * self.nrows + i]
    }
}

impl std::ops::IndexMut<(usize, usize)> for DenseMatrix {
    fn index_mut(&mut self, (i, j): (usize, usize)) -> &mut f64 {
        assert!(
            i < self.nrows && j < self.ncols,
            "index ({i}, {j}) out of bounds"
        );
        &mut self.data[j * self.nrows + i]
    }
}
