//! Nearest input vertex of a point: a uniform grid over the input's vertices.

use glam::DVec3;
use std::collections::HashMap;

/// Nearest-point queries over the input vertices (a uniform grid).
pub(super) struct PointGrid<'a> {
    points: &'a [DVec3],
    lo: DVec3,
    cell: f64,
    dims: [usize; 3],
    cells: HashMap<[usize; 3], Vec<u32>>,
}

impl<'a> PointGrid<'a> {
    pub(super) fn new(points: &'a [DVec3]) -> Self {
        let lo = points
            .iter()
            .fold(DVec3::splat(f64::INFINITY), |a, &p| a.min(p));
        let hi = points
            .iter()
            .fold(DVec3::splat(f64::NEG_INFINITY), |a, &p| a.max(p));
        let extent = (hi - lo).max_element().max(f64::MIN_POSITIVE);
        let cell = extent / (points.len() as f64).cbrt().max(1.0);
        let dims = ((hi - lo) / cell)
            .to_array()
            .map(|d| (d as usize).min(1 << 10) + 1);
        let mut grid = PointGrid {
            points,
            lo,
            cell,
            dims,
            cells: HashMap::new(),
        };
        for (i, &p) in points.iter().enumerate() {
            let c = grid.cell_of(p);
            grid.cells.entry(c).or_default().push(i as u32);
        }
        grid
    }

    fn cell_of(&self, p: DVec3) -> [usize; 3] {
        let q = ((p - self.lo) / self.cell).to_array();
        [0, 1, 2].map(|k| (q[k].max(0.0) as usize).min(self.dims[k] - 1))
    }

    pub(super) fn nearest(&self, p: DVec3) -> u32 {
        let c = self.cell_of(p);
        let mut best = (f64::INFINITY, 0u32);
        let max_ring = self.dims.iter().copied().max().unwrap_or(1);
        for ring in 0..=max_ring {
            let r = ring as i64;
            for dx in -r..=r {
                for dy in -r..=r {
                    for dz in -r..=r {
                        if dx.abs().max(dy.abs()).max(dz.abs()) != r {
                            continue;
                        }
                        let cc = [c[0] as i64 + dx, c[1] as i64 + dy, c[2] as i64 + dz];
                        if cc.iter().any(|&x| x < 0) {
                            continue;
                        }
                        let key = cc.map(|x| x as usize);
                        for &i in self.cells.get(&key).map_or(&[][..], |v| v) {
                            let d = self.points[i as usize].distance_squared(p);
                            if d < best.0 || (d == best.0 && i < best.1) {
                                best = (d, i);
                            }
                        }
                    }
                }
            }
            // Every point within `ring` cells has been seen: done once the best is closer.
            if best.0.is_finite() && best.0.sqrt() <= ring as f64 * self.cell {
                break;
            }
        }
        best.1
    }
}
