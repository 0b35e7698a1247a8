//! One column block of K: the H or −G block column of an element (or, for a sliding
//! element, −G n and H t₁, H t₂), its contributions to the row sums and to the right-hand sides.

use glam::DVec3;

use crate::assembly_report::{AssemblyReport, UnconvergedBlock};
use crate::kernels::{Block, KernelConstants, Moments};
use crate::quadrature::ElementQuad;
use crate::singular::g_diagonal;
use crate::{BemError, ElementKind, Material, QuadratureParams, SurfaceMesh, tangent_frame};

/// Accumulators of one column range: H row sums and, once a column of the range carries a load,
/// its contributions to the right-hand sides.
pub(crate) struct Partial {
    pub(crate) row_sums: Vec<Block>,
    pub(crate) rhs: Option<Vec<f64>>,
    pub(crate) rhs_len: usize,
    pub(crate) quadrature: AssemblyReport,
}

impl Partial {
    pub(crate) fn new(n: usize, dof: usize, rhs_count: usize) -> Self {
        Self {
            row_sums: vec![[[0.0; 3]; 3]; n],
            rhs: None,
            rhs_len: dof * rhs_count,
            quadrature: AssemblyReport::default(),
        }
    }
}

/// What every column task reads: the (recentred) mesh, its quadrature data, the kernel constants
/// and, with the gauge fixed, the rigid-mode rows.
pub(crate) struct ColumnInputs<'a> {
    pub(crate) quads: &'a [ElementQuad],
    pub(crate) centroids: &'a [DVec3],
    pub(crate) consts: &'a KernelConstants,
    pub(crate) qp: &'a QuadratureParams,
    pub(crate) mesh: &'a SurfaceMesh,
    pub(crate) material: &'a Material,
    pub(crate) dof: usize,
    pub(crate) modes: Option<&'a [Vec<DVec3>; 6]>,
}

/// The column block being filled: what is prescribed on its element, that element's normal and
/// tangent frame, the prescribed values and the length of one right-hand side.
struct Target<'a> {
    kind: ElementKind,
    normal: DVec3,
    t1: DVec3,
    t2: DVec3,
    values: &'a [(u32, DVec3)],
    dof: usize,
}

impl Target<'_> {
    /// A sliding element's value: its normal part is the prescribed normal displacement, the
    /// rest the prescribed tangential traction.
    fn split(&self, v: DVec3) -> (DVec3, DVec3) {
        let un = self.normal * v.dot(self.normal);
        (un, v - un)
    }
}

/// Fills column block `j` of K and accumulates its contributions to the row sums and the rhs.
pub(crate) fn assemble_column(
    j: usize,
    cols: [&mut [f64]; 3],
    inputs: &ColumnInputs<'_>,
    kind: ElementKind,
    values: &[(u32, DVec3)],
    partial: &mut Partial,
) -> Result<(), BemError> {
    let mut cols = cols;
    let ColumnInputs {
        quads,
        centroids,
        consts,
        qp,
        mesh,
        material,
        dof,
        modes,
    } = *inputs;
    let q = &quads[j];
    let need_u = kind != ElementKind::Traction || !values.is_empty();
    let normal = mesh.normal(j);
    let (t1, t2) = tangent_frame(normal);
    let target = Target {
        kind,
        normal,
        t1,
        t2,
        values,
        dof,
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
        off_diagonal_block(&target, &mut cols, row, &h, consts, &m, rhs.as_deref_mut());
    }
    // singular diagonal G block (analytic)
    if need_u {
        let g = g_diagonal(mesh, j, material).ok_or(BemError::Internal {
            what: "analytic diagonal G block: centroid not inside its (validated) element",
        })?;
        diagonal_block(&target, &mut cols, 3 * j, &g, rhs);
    }
    // gauge rows: Rᵀ
    if let Some(modes) = modes {
        let [c0, c1, c2] = cols;
        for (k, mode) in modes.iter().enumerate() {
            let v = mode[j];
            c0[dof + k] = v.x;
            c1[dof + k] = v.y;
            c2[dof + k] = v.z;
        }
    }
    Ok(())
}

/// Off-diagonal block of the column in element row `row`: −G, H or (−G n, H t₁, H t₂) into K
/// and the prescribed values' contributions into the right-hand sides. `h` is the H block, G
/// comes from the moments `m` (only where needed).
fn off_diagonal_block(
    target: &Target<'_>,
    cols: &mut [&mut [f64]; 3],
    row: usize,
    h: &Block,
    consts: &KernelConstants,
    m: &Moments,
    rhs: Option<&mut Vec<f64>>,
) {
    let [c0, c1, c2] = cols;
    let (values, dof) = (target.values, target.dof);
    match target.kind {
        ElementKind::Displacement => {
            let g = consts.u_block(m);
            for a in 0..3 {
                c0[row + a] = -g[a][0];
                c1[row + a] = -g[a][1];
                c2[row + a] = -g[a][2];
            }
            if let Some(rhs) = rhs {
                for &(r, u) in values {
                    add_to_rhs(rhs, dof, row, r, block_times(h, u).map(|x| -x));
                }
            }
        }
        ElementKind::Traction => {
            for a in 0..3 {
                c0[row + a] = h[a][0];
                c1[row + a] = h[a][1];
                c2[row + a] = h[a][2];
            }
            if let Some(rhs) = rhs {
                let g = consts.u_block(m);
                for &(r, t) in values {
                    add_to_rhs(rhs, dof, row, r, block_times(&g, t));
                }
            }
        }
        ElementKind::Sliding => {
            // unknowns (t·n, u·t1, u·t2): columns −G n, H t1, H t2
            let g = consts.u_block(m);
            let (gn, h1, h2) = (
                block_times(&g, target.normal),
                block_times(h, target.t1),
                block_times(h, target.t2),
            );
            for a in 0..3 {
                c0[row + a] = -gn[a];
                c1[row + a] = h1[a];
                c2[row + a] = h2[a];
            }
            if let Some(rhs) = rhs {
                for &(r, v) in values {
                    let (un, tt) = target.split(v);
                    let (hu, gt) = (block_times(h, un), block_times(&g, tt));
                    add_to_rhs(rhs, dof, row, r, std::array::from_fn(|a| gt[a] - hu[a]));
                }
            }
        }
    }
}

/// The analytic diagonal G block `g` of the column's own element (rows `row..row + 3`): into K
/// where the traction is unknown, into the right-hand sides where it is prescribed.
fn diagonal_block(
    target: &Target<'_>,
    cols: &mut [&mut [f64]; 3],
    row: usize,
    g: &Block,
    rhs: Option<&mut Vec<f64>>,
) {
    let [c0, c1, c2] = cols;
    let (values, dof) = (target.values, target.dof);
    match target.kind {
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
                    add_to_rhs(rhs, dof, row, r, block_times(g, t));
                }
            }
        }
        ElementKind::Sliding => {
            let gn = block_times(g, target.normal);
            for a in 0..3 {
                c0[row + a] = -gn[a];
            }
            if let Some(rhs) = rhs {
                for &(r, v) in values {
                    add_to_rhs(rhs, dof, row, r, block_times(g, target.split(v).1));
                }
            }
        }
    }
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
