//! A z-buffered triangle rasteriser with Lambert + ambient shading and per-pixel heat colour.
//!
//! Deterministic (no threads inside one panel, fixed evaluation order), supersampled `ss × ss`
//! per pixel and box-filtered down. Attributes (normal, displacement magnitude) are
//! interpolated linearly in screen space, which is exact for an orthographic camera; the heat
//! colour is looked up per sample, so bin boundaries are crisp iso-lines of the interpolated
//! magnitude. Faces are lit two-sided (a normal facing away from the camera is flipped), so
//! rolled-in lips and lids seen from behind are shaded rather than black.

use glam::DVec3;

use super::camera::Camera;
use super::heat;
use super::image::RgbImage;

/// Light and background of a panel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Lighting {
    /// Direction toward the light in view space (x right, y up, +z toward the camera);
    /// normalised when used.
    pub direction: DVec3,
    /// Ambient term in [0, 1].
    pub ambient: f64,
    /// Lambert (diffuse) weight in [0, 1]; `ambient + diffuse` ≤ 1 keeps colours unclipped.
    pub diffuse: f64,
    /// Panel background (pure white by default: no shaded face pixel is pure white).
    pub background: [u8; 3],
}

impl Default for Lighting {
    fn default() -> Self {
        Lighting {
            direction: DVec3::new(-0.35, 0.45, 1.0),
            ambient: 0.3,
            diffuse: 0.7,
            background: [255, 255, 255],
        }
    }
}

/// What one panel draws: a posed mesh in the canonical frame with a displacement per vertex.
pub struct PanelMesh<'a> {
    /// Posed vertex positions, canonical frame.
    pub positions: &'a [DVec3],
    /// Triangles indexing `positions`.
    pub triangles: &'a [[u32; 3]],
    /// Displacement magnitude of each vertex in mm.
    pub displacement_mm: &'a [f64],
}

/// Area-weighted vertex normals (unnormalised sums are normalised; isolated vertices get +z).
pub fn vertex_normals(positions: &[DVec3], triangles: &[[u32; 3]]) -> Vec<DVec3> {
    let mut n = vec![DVec3::ZERO; positions.len()];
    for t in triangles {
        let [a, b, c] = t.map(|i| i as usize);
        if a >= n.len() || b >= n.len() || c >= n.len() {
            continue;
        }
        let f = (positions[b] - positions[a]).cross(positions[c] - positions[a]);
        n[a] += f;
        n[b] += f;
        n[c] += f;
    }
    n.into_iter()
        .map(|v| v.try_normalize().unwrap_or(DVec3::Z))
        .collect()
}

/// Renders `mesh` through `camera` into a `width` × `height` panel, supersampled `ss × ss`.
pub fn render_panel(
    mesh: &PanelMesh<'_>,
    camera: &Camera,
    width: u32,
    height: u32,
    ss: u32,
    lighting: &Lighting,
) -> RgbImage {
    let ss = ss.max(1);
    let (sw, sh) = (width * ss, height * ss);
    let n_samples = sw as usize * sh as usize;
    let mut depth = vec![f64::NEG_INFINITY; n_samples];
    let mut colour = vec![lighting.background.map(f64::from); n_samples];

    let normals: Vec<DVec3> = vertex_normals(mesh.positions, mesh.triangles)
        .into_iter()
        .map(|n| camera.rotation * n)
        .collect();
    let light = lighting.direction.try_normalize().unwrap_or(DVec3::Z);
    let s = f64::from(ss);
    let screen: Vec<(f64, f64, f64)> = mesh
        .positions
        .iter()
        .map(|&p| {
            let (x, y, z) = camera.project(p);
            (x * s, y * s, z)
        })
        .collect();

    for t in mesh.triangles {
        let [a, b, c] = t.map(|i| i as usize);
        if a >= screen.len() || b >= screen.len() || c >= screen.len() {
            continue;
        }
        let (p0, p1, p2) = (screen[a], screen[b], screen[c]);
        let area = (p1.0 - p0.0) * (p2.1 - p0.1) - (p1.1 - p0.1) * (p2.0 - p0.0);
        if !area.is_finite() || area.abs() < 1e-12 {
            continue;
        }
        let min_x = p0.0.min(p1.0).min(p2.0).floor().max(0.0);
        let max_x = p0.0.max(p1.0).max(p2.0).ceil().min(f64::from(sw));
        let min_y = p0.1.min(p1.1).min(p2.1).floor().max(0.0);
        let max_y = p0.1.max(p1.1).max(p2.1).ceil().min(f64::from(sh));
        if min_x >= max_x || min_y >= max_y {
            continue;
        }
        let d = [
            mesh.displacement_mm.get(a).copied().unwrap_or(0.0),
            mesh.displacement_mm.get(b).copied().unwrap_or(0.0),
            mesh.displacement_mm.get(c).copied().unwrap_or(0.0),
        ];
        let nrm = [normals[a], normals[b], normals[c]];
        for py in (min_y as u32)..(max_y as u32) {
            let y = f64::from(py) + 0.5;
            for px in (min_x as u32)..(max_x as u32) {
                let x = f64::from(px) + 0.5;
                // Barycentric weights (edge functions), sign-normalised by the area.
                let w0 = ((p1.0 - x) * (p2.1 - y) - (p1.1 - y) * (p2.0 - x)) / area;
                let w1 = ((p2.0 - x) * (p0.1 - y) - (p2.1 - y) * (p0.0 - x)) / area;
                let w2 = 1.0 - w0 - w1;
                if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                    continue;
                }
                let z = w0 * p0.2 + w1 * p1.2 + w2 * p2.2;
                let i = py as usize * sw as usize + px as usize;
                if z <= depth[i] {
                    continue;
                }
                depth[i] = z;
                let mut n = (w0 * nrm[0] + w1 * nrm[1] + w2 * nrm[2])
                    .try_normalize()
                    .unwrap_or(DVec3::Z);
                if n.z < 0.0 {
                    n = -n;
                }
                let shade = lighting.ambient + lighting.diffuse * n.dot(light).max(0.0);
                let disp = w0 * d[0] + w1 * d[1] + w2 * d[2];
                colour[i] = heat::colour(disp).map(|v| f64::from(v) * shade);
            }
        }
    }

    let mut img = RgbImage::new(width, height, lighting.background);
    let inv = 1.0 / (s * s);
    for y in 0..height {
        for x in 0..width {
            let mut acc = [0.0f64; 3];
            for sy in 0..ss {
                let row = (y * ss + sy) as usize * sw as usize;
                for sx in 0..ss {
                    let c = colour[row + (x * ss + sx) as usize];
                    for k in 0..3 {
                        acc[k] += c[k];
                    }
                }
            }
            img.put(x, y, acc.map(|v| (v * inv).round().clamp(0.0, 255.0) as u8));
        }
    }
    img
}
