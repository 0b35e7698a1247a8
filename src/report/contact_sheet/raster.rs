//! A z-buffered triangle rasteriser with Lambert + ambient shading and per-pixel heat colour.
//!
//! Deterministic (no threads inside one panel, fixed evaluation order), supersampled `ss × ss`
//! per pixel and box-filtered down. Attributes (normal, displacement magnitude) are
//! interpolated linearly in screen space, which is exact for an orthographic camera; the heat
//! colour is looked up per sample, so bin boundaries are crisp iso-lines of the interpolated
//! magnitude. Faces are lit two-sided (a normal facing away from the camera is flipped), so
//! rolled-in lips and lids seen from behind are shaded rather than black.
//!
//! The heat map shows how far the skin moved, not which way: [`Arrows`] overlays a sparse field
//! of motion arrows (one per grid cell of the panel, on the visible surface, tail at the drawn
//! point, pointing where the skin moved, exaggerated by a stated factor).

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

/// The motion-arrow overlay of a panel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Arrows {
    /// One arrow per square of this many panel pixels (at most).
    pub spacing_px: u32,
    /// Drawn length ÷ projected true length of the motion.
    pub exaggeration: f64,
    /// Skin moving less than this many mm gets no arrow.
    pub min_mm: f64,
    /// Arrow colour.
    pub colour: [u8; 3],
}

impl Default for Arrows {
    fn default() -> Self {
        Arrows {
            spacing_px: 16,
            exaggeration: 2.0,
            min_mm: super::heat::EDGES_MM[0],
            colour: [15, 15, 15],
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
    /// Displacement of each vertex, canonical frame, model units (for [`Arrows`]; may be
    /// empty: no arrows).
    pub displacement: &'a [DVec3],
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

/// Renders `mesh` through `camera` into a `width` × `height` panel, supersampled `ss × ss`,
/// with motion arrows if `arrows` is set (`mm_per_unit` converts their threshold).
#[allow(clippy::too_many_arguments)]
pub fn render_panel(
    mesh: &PanelMesh<'_>,
    camera: &Camera,
    width: u32,
    height: u32,
    ss: u32,
    lighting: &Lighting,
    arrows: Option<&Arrows>,
) -> RgbImage {
    let ss = ss.max(1);
    let (sw, sh) = (width * ss, height * ss);
    let n_samples = sw as usize * sh as usize;
    let mut depth = vec![f64::NEG_INFINITY; n_samples];
    let mut colour = vec![lighting.background.map(f64::from); n_samples];
    let mut triangle_at = vec![u32::MAX; n_samples];

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

    for (ti, t) in mesh.triangles.iter().enumerate() {
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
                triangle_at[i] = ti as u32;
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
    if let Some(arrows) = arrows {
        let at = |px: u32, py: u32| triangle_at[py as usize * sw as usize + px as usize];
        draw_arrows(&mut img, mesh, camera, &screen, ss, arrows, at);
    }
    img
}

/// Draws one arrow per `spacing_px` square, from the visible surface point at the square's
/// centre, along the projected displacement interpolated there.
fn draw_arrows(
    img: &mut RgbImage,
    mesh: &PanelMesh<'_>,
    camera: &Camera,
    screen: &[(f64, f64, f64)],
    ss: u32,
    arrows: &Arrows,
    triangle_at: impl Fn(u32, u32) -> u32,
) {
    if mesh.displacement.len() != mesh.positions.len() {
        return;
    }
    let step = arrows.spacing_px.max(4);
    let s = f64::from(ss);
    let (w, h) = (img.width, img.height);
    for gy in (step / 2..h).step_by(step as usize) {
        for gx in (step / 2..w).step_by(step as usize) {
            // The supersample nearest the centre of pixel (gx, gy).
            let (sx, sy) = (gx * ss + ss / 2, gy * ss + ss / 2);
            let t = triangle_at(sx, sy);
            let Some(tri) = mesh.triangles.get(t as usize) else {
                continue;
            };
            let [a, b, c] = tri.map(|i| i as usize);
            let (p0, p1, p2) = (screen[a], screen[b], screen[c]);
            let (x, y) = (f64::from(sx) + 0.5, f64::from(sy) + 0.5);
            let area = (p1.0 - p0.0) * (p2.1 - p0.1) - (p1.1 - p0.1) * (p2.0 - p0.0);
            let w0 = ((p1.0 - x) * (p2.1 - y) - (p1.1 - y) * (p2.0 - x)) / area;
            let w1 = ((p2.0 - x) * (p0.1 - y) - (p2.1 - y) * (p0.0 - x)) / area;
            let w2 = 1.0 - w0 - w1;
            let mm = w0 * mesh.displacement_mm[a]
                + w1 * mesh.displacement_mm[b]
                + w2 * mesh.displacement_mm[c];
            if mm.is_nan() || mm < arrows.min_mm {
                continue;
            }
            let d = camera.rotation
                * (w0 * mesh.displacement[a]
                    + w1 * mesh.displacement[b]
                    + w2 * mesh.displacement[c]);
            let k = arrows.exaggeration * camera.pixels_per_unit;
            let tail = (x / s, y / s);
            let head = (tail.0 + k * d.x, tail.1 - k * d.y);
            let len = (head.0 - tail.0).hypot(head.1 - tail.1);
            if len < 1.5 {
                img.put(gx, gy, arrows.colour);
                continue;
            }
            draw_line(img, tail, head, arrows.colour);
            let (ux, uy) = ((tail.0 - head.0) / len, (tail.1 - head.1) / len);
            let barb = (0.35 * len).clamp(2.0, 5.0);
            for angle in [0.45f64, -0.45] {
                let (sa, ca) = angle.sin_cos();
                let bx = ux * ca - uy * sa;
                let by = ux * sa + uy * ca;
                draw_line(
                    img,
                    head,
                    (head.0 + barb * bx, head.1 + barb * by),
                    arrows.colour,
                );
            }
        }
    }
}

/// A 1-pixel line from `a` to `b` (pixel coordinates, clipped to the image).
fn draw_line(img: &mut RgbImage, a: (f64, f64), b: (f64, f64), rgb: [u8; 3]) {
    let n = (b.0 - a.0).abs().max((b.1 - a.1).abs()).ceil().max(1.0) as u32;
    for i in 0..=n {
        let t = f64::from(i) / f64::from(n);
        let (x, y) = (a.0 + t * (b.0 - a.0), a.1 + t * (b.1 - a.1));
        if x >= 0.0 && y >= 0.0 {
            img.put(x as u32, y as u32, rgb);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::report::contact_sheet::View;

    /// A flat square in the x-y plane moving uniformly by `d` (model units):
    /// 1 unit = 10 mm; its single arrow (spacing = panel) starts at the panel centre and points along `d` as
    /// seen from the front (+x right, +y up).
    fn arrow_pixels(d: DVec3) -> Vec<(i64, i64)> {
        let positions = [
            DVec3::new(-1.0, -1.0, 0.0),
            DVec3::new(1.0, -1.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(-1.0, 1.0, 0.0),
        ];
        let triangles = [[0, 1, 2], [0, 2, 3]];
        let mesh = PanelMesh {
            positions: &positions,
            triangles: &triangles,
            displacement_mm: &[10.0 * d.length(); 4],
            displacement: &[d; 4],
        };
        let cam = Camera::fit(&View::front(), &positions, 64, 64, 0.0);
        let arrows = Arrows {
            spacing_px: 64,
            exaggeration: 1.0,
            ..Arrows::default()
        };
        let img = render_panel(&mesh, &cam, 64, 64, 2, &Lighting::default(), Some(&arrows));
        let mut out = Vec::new();
        for y in 0..64 {
            for x in 0..64 {
                if img.get(x, y) == arrows.colour {
                    out.push((i64::from(x) - 32, i64::from(y) - 32));
                }
            }
        }
        out
    }

    #[test]
    fn arrows_point_the_way_the_skin_moves() {
        // 0.25 units = 8 px at 32 px per unit.
        let right = arrow_pixels(DVec3::new(0.25, 0.0, 0.0));
        assert!(right.len() >= 8, "{right:?}");
        assert!(
            right.iter().all(|&(x, y)| x >= -1 && y.abs() <= 4),
            "{right:?}"
        );
        assert!(right.iter().any(|&(x, _)| x >= 7), "{right:?}");
        let up = arrow_pixels(DVec3::new(0.0, 0.25, 0.0));
        assert!(up.iter().all(|&(x, y)| y <= 1 && x.abs() <= 4), "{up:?}");
        assert!(up.iter().any(|&(_, y)| y <= -7), "{up:?}");
        // Below the 0.5 mm threshold: no arrow.
        assert!(arrow_pixels(DVec3::new(0.04, 0.0, 0.0)).is_empty());
    }
}
