//! Overlay lines drawn over the face: muscles (a colour each, with their direction), skull
//! elements, feature boxes and the selected element. Built from the rig (canonical frame) and
//! carried to the user's frame with `input_from_canonical`.

use face_prep::{Box2, ElementTag, FaceRig, FeatureBoxes, Muscle};
use glam::{DAffine3, DVec3};

use crate::renderer::LineVertex;

/// Which overlays to draw; none by default (issue 35: on a first look the muscle chains
/// read as noise).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct OverlayOptions {
    /// Muscles, each one smooth line along its element chain with an arrow head pointing the
    /// way a contraction pulls the skin ([`muscle_path`]).
    pub muscles: bool,
    /// Outlines of the skull (fixed) elements.
    pub skull: bool,
    /// The feature boxes (face, eyes, mouth, nose, skull), in the front plane.
    pub boxes: bool,
    /// Also show what lies behind the front face: back chains and the edges of the back and
    /// rim elements (drawn through the face).
    pub whole_shell: bool,
}

/// Ten base hues and their names; [`muscle_color`] cycles through them, then through lighter,
/// darker and paler shades of them, so the rig's own list of muscles (however long the control
/// table grows) gets distinct colours with distinct names.
const HUES: [(&str, [f32; 3]); 10] = [
    ("red", [0.90, 0.10, 0.10]),
    ("blue", [0.10, 0.45, 0.95]),
    ("green", [0.10, 0.75, 0.20]),
    ("orange", [0.95, 0.55, 0.05]),
    ("purple", [0.60, 0.20, 0.85]),
    ("teal", [0.05, 0.75, 0.75]),
    ("pink", [0.95, 0.20, 0.65]),
    ("brown", [0.55, 0.40, 0.10]),
    ("grey", [0.35, 0.35, 0.35]),
    ("yellow", [0.75, 0.75, 0.05]),
];

/// Shades applied to the base hues in turn: (name prefix, mix toward white, brightness).
const SHADES: [(&str, f32, f32); 4] = [
    ("", 0.0, 1.0),
    ("light ", 0.5, 1.0),
    ("dark ", 0.0, 0.55),
    ("pale ", 0.75, 0.9),
];

/// Name of the colour [`muscle_color`] gives muscle number `index` of a rig's muscle list
/// (shown in the legend, so it can be told apart without telling the hues apart). Distinct for
/// every index: past the 40 named shades a number is appended.
///
/// ```
/// use viewer::overlay::muscle_color_name;
/// assert_eq!(muscle_color_name(0), "red");
/// assert_eq!(muscle_color_name(11), "light blue");
/// assert_eq!(muscle_color_name(40), "red 2");
/// ```
pub fn muscle_color_name(index: usize) -> String {
    let (hue, _) = HUES[index % HUES.len()];
    let (shade, _, _) = SHADES[(index / HUES.len()) % SHADES.len()];
    let round = index / (HUES.len() * SHADES.len());
    if round == 0 {
        format!("{shade}{hue}")
    } else {
        format!("{shade}{hue} {}", round + 1)
    }
}

/// Colour of muscle number `index` of a rig's muscle list: ten distinct hues, then their
/// lighter, darker and paler shades ([`muscle_color_name`] names it).
pub fn muscle_color(index: usize) -> [f32; 4] {
    let (_, [r, g, b]) = HUES[index % HUES.len()];
    let (_, white, bright) = SHADES[(index / HUES.len()) % SHADES.len()];
    let f = |c: f32| (c + (1.0 - c) * white) * bright;
    [f(r), f(g), f(b), 1.0]
}

/// Element centroids and vertices of a rig, in the user's frame.
#[derive(Clone, Debug)]
pub struct RigGeometry {
    /// `input_from_canonical` (inverse of the rig's `canonical_from_input`).
    pub input_from_canonical: DAffine3,
    /// Shell vertices, user frame.
    pub vertices: Vec<DVec3>,
}

impl RigGeometry {
    /// Carries the rig's shell into the user's frame.
    pub fn new(rig: &FaceRig) -> Self {
        let input_from_canonical = rig.canonical_from_input.inverse();
        let vertices = rig
            .shell
            .vertices
            .iter()
            .map(|p| input_from_canonical.transform_point3(*p))
            .collect();
        RigGeometry {
            input_from_canonical,
            vertices,
        }
    }

    /// Corners of shell element `e` (user frame), if it exists.
    pub fn corners(&self, rig: &FaceRig, e: u32) -> Option<[DVec3; 3]> {
        let t = rig.shell.triangles.get(e as usize)?;
        Some([
            *self.vertices.get(t[0] as usize)?,
            *self.vertices.get(t[1] as usize)?,
            *self.vertices.get(t[2] as usize)?,
        ])
    }

    /// Centroid of shell element `e` (user frame), if it exists.
    pub fn centroid(&self, rig: &FaceRig, e: u32) -> Option<DVec3> {
        self.corners(rig, e).map(|[a, b, c]| (a + b + c) / 3.0)
    }
}

fn push_line(out: &mut Vec<LineVertex>, a: DVec3, b: DVec3, color: [f32; 4]) {
    for p in [a, b] {
        out.push(LineVertex {
            position: p.as_vec3().to_array(),
            color,
        });
    }
}

fn scaled(c: [f32; 4], k: f32, alpha: f32) -> [f32; 4] {
    [c[0] * k, c[1] * k, c[2] * k, alpha]
}

/// Points of a drawn muscle line ([`muscle_path`]).
pub const PATH_POINTS: usize = 12;

/// The line drawn for a muscle chain: one smooth curve from the first element's centroid to the
/// last one's (the chain runs the way a contraction pulls the skin, e.g. from the mouth corner
/// toward the cheekbone for the zygomaticus major) instead of the zig-zag through every
/// centroid.
/// It is a Gaussian kernel regression of the centroids over their arc length (σ = 15 % of the
/// length), corrected linearly so it starts and ends exactly at the chain's ends, sampled at
/// [`PATH_POINTS`] evenly spaced arc lengths. Empty for a chain of fewer than two elements.
pub fn muscle_path(rig: &FaceRig, geo: &RigGeometry, chain: &[u32]) -> Vec<DVec3> {
    let points: Vec<DVec3> = chain.iter().filter_map(|&e| geo.centroid(rig, e)).collect();
    let (Some(&first), Some(&last)) = (points.first(), points.last()) else {
        return Vec::new();
    };
    if points.len() < 2 {
        return Vec::new();
    }
    let mut arc = vec![0.0];
    for w in points.windows(2) {
        arc.push(arc[arc.len() - 1] + w[0].distance(w[1]));
    }
    let length = arc[arc.len() - 1];
    if length <= 0.0 {
        return vec![first, last];
    }
    let sigma = 0.15 * length;
    let regress = |t: f64| {
        let (mut sum, mut weight) = (DVec3::ZERO, 0.0);
        for (p, a) in points.iter().zip(&arc) {
            let w = (-(a - t).powi(2) / (2.0 * sigma * sigma)).exp();
            sum += w * *p;
            weight += w;
        }
        sum / weight
    };
    let (g0, g1) = (regress(0.0), regress(length));
    (0..PATH_POINTS)
        .map(|i| {
            let f = i as f64 / (PATH_POINTS - 1) as f64;
            regress(f * length) + (first - g0) * (1.0 - f) + (last - g1) * f
        })
        .collect()
}

fn path_lines(out: &mut Vec<LineVertex>, path: &[DVec3], color: [f32; 4], view_normal: DVec3) {
    for w in path.windows(2) {
        push_line(out, w[0], w[1], color);
    }
    if let [.., a, b] = path[..] {
        // An arrow head at the chain's end: the direction of the pull.
        let d = b - a;
        let len = d.length();
        if len > 0.0 {
            let dir = d / len;
            let side = view_normal.cross(dir).normalize_or_zero();
            let head = 1.5 * len;
            for s in [-1.0, 1.0] {
                push_line(out, b, b - head * dir + s * 0.5 * head * side, color);
            }
        }
    }
}

fn box_lines(out: &mut Vec<LineVertex>, geo: &RigGeometry, b: &Box2, z: f64, color: [f32; 4]) {
    let c = [
        DVec3::new(b.min.x, b.min.y, z),
        DVec3::new(b.max.x, b.min.y, z),
        DVec3::new(b.max.x, b.max.y, z),
        DVec3::new(b.min.x, b.max.y, z),
    ]
    .map(|p| geo.input_from_canonical.transform_point3(p));
    for i in 0..4 {
        push_line(out, c[i], c[(i + 1) % 4], color);
    }
}

/// All overlay lines for `rig` with `options`; `selected` (a shell element) is outlined in yellow.
/// `muscles` replaces the rig's muscles (edited ones, not solved yet) and `boxes` its feature
/// boxes (while the user edits them).
pub fn overlay_lines(
    rig: &FaceRig,
    geo: &RigGeometry,
    options: &OverlayOptions,
    selected: Option<u32>,
    muscles: Option<&[Muscle]>,
    boxes: Option<&FeatureBoxes>,
) -> Vec<LineVertex> {
    let mut out = Vec::new();
    // Canonical +z (the face looks that way) in the user's frame: the plane of arrow heads.
    let view_normal = geo
        .input_from_canonical
        .transform_vector3(DVec3::Z)
        .normalize_or_zero();
    if options.whole_shell {
        // The rest of the closed shell: back and rim element edges, faint.
        let col = [0.6, 0.6, 0.65, 0.25];
        for (e, tag) in rig.shell.tags.iter().enumerate() {
            if *tag != ElementTag::Front
                && let Some([a, b, c]) = geo.corners(rig, e as u32)
            {
                push_line(&mut out, a, b, col);
                push_line(&mut out, b, c, col);
                push_line(&mut out, c, a, col);
            }
        }
    }
    if options.skull {
        for &e in &rig.skull {
            if let Some([a, b, c]) = geo.corners(rig, e) {
                let col = [0.55, 0.65, 0.85, 0.7];
                push_line(&mut out, a, b, col);
                push_line(&mut out, b, c, col);
                push_line(&mut out, c, a, col);
            }
        }
    }
    if options.muscles {
        for (i, m) in muscles.unwrap_or(&rig.muscles).iter().enumerate() {
            let color = muscle_color(i);
            let front = muscle_path(rig, geo, &m.front_chain);
            path_lines(&mut out, &front, color, view_normal);
            if options.whole_shell {
                let back = muscle_path(rig, geo, &m.back_chain);
                path_lines(&mut out, &back, scaled(color, 1.0, 0.5), -view_normal);
            }
        }
    }
    if options.boxes {
        let z = rig
            .shell
            .vertices
            .iter()
            .take(rig.face_vertex_count)
            .map(|p| p.z)
            .fold(f64::NEG_INFINITY, f64::max);
        let z = if z.is_finite() { z } else { 0.0 };
        let b = boxes.unwrap_or(&rig.boxes);
        box_lines(&mut out, geo, &b.face, z, [0.95, 0.95, 0.95, 0.9]);
        box_lines(&mut out, geo, &b.eye_l, z, [0.2, 0.9, 0.95, 0.9]);
        box_lines(&mut out, geo, &b.eye_r, z, [0.2, 0.9, 0.95, 0.9]);
        box_lines(&mut out, geo, &b.mouth, z, [0.95, 0.3, 0.85, 0.9]);
        box_lines(&mut out, geo, &b.nose, z, [0.95, 0.9, 0.2, 0.9]);
        box_lines(&mut out, geo, &b.skull, z, [0.95, 0.55, 0.15, 0.9]);
    }
    if let Some(e) = selected
        && let Some([a, b, c]) = geo.corners(rig, e)
    {
        let col = [1.0, 0.9, 0.1, 1.0];
        push_line(&mut out, a, b, col);
        push_line(&mut out, b, c, col);
        push_line(&mut out, c, a, col);
    }
    out
}

/// Names of the muscles whose front or back chain contains shell element `e`.
pub fn muscles_of_element(muscles: &[Muscle], e: u32) -> Vec<String> {
    muscles
        .iter()
        .filter(|m| m.front_chain.contains(&e) || m.back_chain.contains(&e))
        .map(|m| {
            m.kind
                .map_or_else(|| m.name.clone(), |k| k.display_name().to_owned())
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn overlays_of_the_default_rig_follow_the_options() {
        let (mesh, _) = facebem::input::read_face(&crate::source::default_face_path()).unwrap();
        let prepared = facebem::prepare(&mesh, &facebem::PipelineParams::default()).unwrap();
        let rig = prepared.rig;
        let geo = RigGeometry::new(&rig);
        // Front shell vertices are the simulated face's vertices, back in the user's frame:
        // each one a vertex of the input (the default face is simulated without its rolled-in
        // mouth corners).
        let copy = prepared
            .simplified
            .expect("the default face's mouth corners are peeled");
        let mut checked = 0;
        for (c, sim) in prepared.simulated.input_to_vertex.iter().enumerate() {
            let (Some(sim), Some(&orig)) = (sim, copy.original_vertex.get(c)) else {
                continue;
            };
            let (p, q) = (geo.vertices[*sim as usize], mesh.vertices[orig as usize]);
            assert!((p - q).length() < 1e-9 * (1.0 + q.length()), "{p} vs {q}");
            checked += 1;
        }
        assert_eq!(checked, rig.face_vertex_count);
        let none = OverlayOptions {
            muscles: false,
            skull: false,
            boxes: false,
            whole_shell: false,
        };
        assert!(overlay_lines(&rig, &geo, &none, None, None, None).is_empty());
        let muscles = overlay_lines(
            &rig,
            &geo,
            &OverlayOptions {
                muscles: true,
                ..none
            },
            None,
            None,
            None,
        );
        // Per muscle: (PATH_POINTS − 1) segments + 2 arrow-head strokes, 2 vertices each.
        let expected: usize = rig
            .muscles
            .iter()
            .filter(|m| m.front_chain.len() >= 2)
            .map(|_| 2 * (PATH_POINTS - 1 + 2))
            .sum();
        assert_eq!(muscles.len(), expected);
        // Edited muscles (not solved yet) are drawn instead of the rig's: here only the first.
        let edited = overlay_lines(
            &rig,
            &geo,
            &OverlayOptions {
                muscles: true,
                ..none
            },
            None,
            Some(&rig.muscles[..1]),
            None,
        );
        assert_eq!(edited.len(), 2 * (PATH_POINTS - 1 + 2));
        assert_eq!(edited[..], muscles[..edited.len()]);
        let boxes = overlay_lines(
            &rig,
            &geo,
            &OverlayOptions {
                boxes: true,
                ..none
            },
            None,
            None,
            None,
        );
        assert_eq!(boxes.len(), 6 * 4 * 2);
        let skull = overlay_lines(
            &rig,
            &geo,
            &OverlayOptions {
                skull: true,
                ..none
            },
            None,
            None,
            None,
        );
        assert_eq!(skull.len(), rig.skull.len() * 6);
        let selected = overlay_lines(&rig, &geo, &none, Some(0), None, None);
        assert_eq!(selected.len(), 6);
        assert!(overlay_lines(&rig, &geo, &none, Some(u32::MAX), None, None).is_empty());
    }
}
