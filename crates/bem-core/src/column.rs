//! One column block of K: the H or −G block column of an element (or, for a sliding
//! element, −G n and H t₁, H t₂), its contributions to the row sums and to the right-hand sides.

use glam::DVec3;

use crate::assembly::{Partial, UnconvergedBlock};
use crate::kernels::{Block, KernelConstants};
use crate::quadrature::ElementQuad;
use crate::singular::g_diagonal;
use crate::{BemError, ElementKind, Material, QuadratureParams, SurfaceMesh, tangent_frame};

/// Fills column block `j` of K and accumulates its contributions to the row sums and the rhs.
#[allow(clippy::too_many_arguments)] // one column task's whole context
pub(crate) fn assemble_column(
    j: usize,
    cols: [&mut [f64]; 3],
    quads: &[ElementQuad],
    centroids: &[DVec3],
    consts: &KernelConstants,
    qp: &QuadratureParams,
    kind: ElementKind,
    values: &[(u32, DVec3)],
    mesh: &SurfaceMesh,
    material: &Material,
    partial: &mut Partial,
    dof: usize,
    modes: Option<&[Vec<DVec3>; 6]>,
) -> Result<(), BemError> {
    let [c0, c1, c2] = cols;
    let q = &quads[j];
    let need_u = kind != ElementKind::Traction || !values.is_empty();
    let normal = mesh.normal(j);
    let (t1, t2) = tangent_frame(normal);
    // A sliding element's value: its normal part is the prescribed normal displacement, the rest
    // the prescribed tangential traction.
    let split = |v: DVec3| {
        let un = normal * v.dot(normal);
        (un, v - un)
    };
    let n = quads.len();
    let rhs_len = partial.rhs_len;
    let (row_sums, report, mut rhs) = (
        &mut partial.row_sums,
        &mut partial.quadrature,
        (!values.is_empty()).then(|| partial.rhs.get_or_insert_with(|| vec![0.0; rhs_len])),
    );
    for (i, &p) in centroids.iter().enumerate().take(n) {
        if i == j {
            continue;
        }
        let (m, estimated_error) = q.moments(p, qp, need_u);
        if estimated_error > qp.tolerance {
            report.note(UnconvergedBlock {
                row_element: i,
                column_element: j,
                estimated_error,
            });
        }
        let h = consts.t_block(&m, q.normal);
        let rs = &mut row_sums[i];
        for a in 0..3 {
            for b in 0..3 {
                rs[a][b] += h[a][b];
            }
        }
        let row = 3 * i;
        match kind {
            ElementKind::Displacement => {
                let g = consts.u_block(&m);
                for a in 0..3 {
                    c0[row + a] = -g[a][0];
                    c1[row + a] = -g[a][1];
                    c2[row + a] = -g[a][2];
                }
                if let Some(rhs) = rhs.as_deref_mut() {
                    for &(r, u) in values {
                        add_to_rhs(rhs, dof, row, r, block_times(&h, u).map(|x| -x));
                    }
                }
            }
            ElementKind::Traction => {
                for a in 0..3 {
                    c0[row + a] = h[a][0];
                    c1[row + a] = h[a][1];
                    c2[row + a] = h[a][2];
                }
                if let Some(rhs) = rhs.as_deref_mut() {
                    let g = consts.u_block(&m);
                    for &(r, t) in values {
                        add_to_rhs(rhs, dof, row, r, block_times(&g, t));
                    }
                }
            }
            ElementKind::Sliding => {
                // unknowns (t·n, u·t1, u·t2): columns −G n, H t1, H t2
                let g = consts.u_block(&m);
                let (gn, h1, h2) = (
                    block_times(&g, normal),
                    block_times(&h, t1),
                    block_times(&h, t2),
                );
                for a in 0..3 {
                    c0[row + a] = -gn[a];
                    c1[row + a] = h1[a];
                    c2[row + a] = h2[a];
                }
                if let Some(rhs) = rhs.as_deref_mut() {
                    for &(r, v) in values {
                        let (un, tt) = split(v);
                        let (hu, gt) = (block_times(&h, un), block_times(&g, tt));
                        add_to_rhs(rhs, dof, row, r, std::array::from_fn(|a| gt[a] - hu[a]));
                    }
                }
            }
        }
    }
    // singular diagonal G block (analytic)
    if need_u {
        let g = g_diagonal(mesh, j, material).ok_or(BemError::Internal {
            what: "analytic diagonal G block: centroid not inside its (validated) element",
        })?;
        let row = 3 * j;
        match kind {
            ElementKind::Displacement => {
                for a in 0..3 {
                    c0[row + a] = -g[a][0];
                    c1[row + a] = -g[a][1];
                    c2[row + a] = -g[a][2];
                }
            }
            ElementKind::Traction => {
                if let Some(rhs) = rhs {
                    for &(r, t) in values {
                        add_to_rhs(rhs, dof, row, r, block_times(&g, t));
                    }
                }
            }
            ElementKind::Sliding => {
                let gn = block_times(&g, normal);
                for a in 0..3 {
                    c0[row + a] = -gn[a];
                }
                if let Some(rhs) = rhs {
                    for &(r, v) in values {
                        add_to_rhs(rhs, dof, row, r, block_times(&g, split(v).1));
                    }
                }
            }
        }
    }
    // gauge rows: Rᵀ
    if let Some(modes) = modes {
        for (k, mode) in modes.iter().enumerate() {
            let v = mode[j];
            c0[dof + k] = v.x;
            c1[dof + k] = v.y;
            c2[dof + k] = v.z;
        }
    }
    Ok(())
}

/// `b · v` for a 3 × 3 block.
pub(crate) fn block_times(b: &Block, v: DVec3) -> [f64; 3] {
    std::array::from_fn(|a| b[a][0] * v.x + b[a][1] * v.y + b[a][2] * v.z)
}

/// Adds `v` to the three rows of element row `row` in right-hand side `r` (the partial right-hand
/// sides are stored one after another, `dof` values each).
fn add_to_rhs(rhs: &mut [f64], dof: usize, row: usize, r: u32, v: [f64; 3]) {
    let start = r as usize * dof + row;
    for (y, d) in rhs[start..start + 3].iter_mut().zip(v) {
        *y += d;
    }
}
