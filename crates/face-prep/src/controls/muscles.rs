//! Muscles and skull (thesis ch. 7): muscle-definers from the feature boxes, ray projection
//! along −z onto the shell, ordered element chains, skull elements and displacement patterns.

use crate::bvh::TriangleBvh;
use crate::controls::muscle_kind::MuscleKind;
use crate::frame::features::FeatureBoxes;
use crate::shell::{ElementTag, Shell};
use glam::{DVec2, DVec3};
use serde::{Deserialize, Serialize};
use std::collections::HashSet;

/// One muscle: ordered chains of shell elements from its start to its end.
///
/// A chain never contains an element twice; front chains hold only Front elements, back chains
/// only Back elements, and no chain holds a skull element.
#[derive(Clone, Debug, PartialEq, Eq, Serialize, Deserialize)]
pub struct Muscle {
    /// Display name (thesis names for the standard muscles, e.g. "Zygomaticus major L").
    pub name: String,
    /// Which standard muscle this is, if any.
    pub kind: Option<MuscleKind>,
    /// Front elements from start to end.
    pub front_chain: Vec<u32>,
    /// Back elements from start to end (empty for the frontalis).
    pub back_chain: Vec<u32>,
}

impl Muscle {
    /// The muscle's id: its standard id when it is a standard muscle ([`MuscleKind::id`],
    /// whatever name denotes it), else its name. Sliders and morph targets are named by it, so
    /// the muscles of a rig have distinct ids.
    ///
    /// ```
    /// use face_prep::{Muscle, MuscleKind};
    /// let m = |name: &str, kind| Muscle { name: name.into(), kind, front_chain: vec![], back_chain: vec![] };
    /// assert_eq!(m("Frontalis L", Some(MuscleKind::FrontalisL)).id(), "frontalis_l");
    /// assert_eq!(m("my muscle", None).id(), "my muscle");
    /// ```
    pub fn id(&self) -> &str {
        match self.kind {
            Some(k) => k.id(),
            None => &self.name,
        }
    }

    /// All elements of the muscle, front chain then back chain.
    pub fn elements(&self) -> impl Iterator<Item = u32> + '_ {
        self.front_chain.iter().chain(&self.back_chain).copied()
    }
}

/// The muscle-definer (start → end, canonical x-y) of one of the thesis's ten muscles, thesis
/// Table 7.1 (`None` for any other control: the thesis model places only
/// [`MuscleKind::THESIS`]).
pub fn muscle_definer(kind: MuscleKind, b: &FeatureBoxes) -> Option<(DVec2, DVec2)> {
    use MuscleKind::*;
    let nose_mid_y = b.nose.center().y;
    Some(match kind {
        FrontalisL => (b.eye_l.c6(), DVec2::new(b.eye_l.c6().x, b.face.max.y)),
        FrontalisR => (b.eye_r.c7(), DVec2::new(b.eye_r.c7().x, b.face.max.y)),
        LevatorLabiiSuperiorisL => {
            let end = 0.5 * (b.eye_l.c4() + b.eye_l.c5());
            (DVec2::new(end.x, b.nose.min.y), end)
        }
        LevatorLabiiSuperiorisR => {
            let end = 0.5 * (b.eye_r.c4() + b.eye_r.c5());
            (DVec2::new(end.x, b.nose.min.y), end)
        }
        ZygomaticusMajorL => (b.mouth.c7(), DVec2::new(b.face.max.x, nose_mid_y)),
        ZygomaticusMajorR => (b.mouth.c6(), DVec2::new(b.face.min.x, nose_mid_y)),
        MentalisL => {
            let x = b.mouth.c5().x - b.mouth.width() / 3.0;
            (DVec2::new(x, b.mouth.min.y), DVec2::new(x, b.face.min.y))
        }
        MentalisR => {
            let x = b.mouth.c4().x + b.mouth.width() / 3.0;
            (DVec2::new(x, b.mouth.min.y), DVec2::new(x, b.face.min.y))
        }
        DepressorLabiiInferiorisL => (b.mouth.c5(), b.face.c5()),
        DepressorLabiiInferiorisR => (b.mouth.c4(), b.face.c4()),
        #[allow(unreachable_patterns)] // the table grows beyond the thesis's ten
        _ => return None,
    })
}

/// Whether the muscle has a front chain only (thesis: the frontalis lies on the skull).
pub(crate) fn front_only(kind: MuscleKind) -> bool {
    matches!(kind, MuscleKind::FrontalisL | MuscleKind::FrontalisR)
}

/// Skull (fixed) elements: every rim element plus every back element whose centroid lies in
/// FBSkull or FBNose in x-y. Sorted.
pub(crate) fn skull_elements(shell: &Shell, boxes: &FeatureBoxes) -> Vec<u32> {
    (0..shell.element_count())
        .filter(|&e| match shell.tags[e] {
            ElementTag::Rim => true,
            ElementTag::Back => {
                let c = shell.centroid(e).truncate();
                boxes.skull.contains(c) || boxes.nose.contains(c)
            }
            ElementTag::Front => false,
        })
        .map(|e| e as u32)
        .collect()
}

/// Projects the segment `start → end` onto the shell with rays along −z every `spacing`, and
/// returns (front chain, back chain). For each ray, the first hit must be a Front element (it
/// joins the front chain) and the first Back element after it joins the back chain: the near
/// layer of tissue under the definer, even where lips or nostrils fold the surface so that a ray
/// crosses it several times. Skull elements are skipped; each element is kept at its first
/// occurrence, so chains are ordered start → end without repeats.
pub(crate) fn project_definer(
    shell: &Shell,
    bvh: &TriangleBvh,
    skull: &HashSet<u32>,
    start: DVec2,
    end: DVec2,
    spacing: f64,
) -> (Vec<u32>, Vec<u32>) {
    let z_top = shell
        .vertices
        .iter()
        .map(|v| v.z)
        .fold(f64::NEG_INFINITY, f64::max);
    let z_bottom = shell
        .vertices
        .iter()
        .map(|v| v.z)
        .fold(f64::INFINITY, f64::min);
    let z0 = z_top + 0.01 * (z_top - z_bottom).max(1e-9);
    let len = start.distance(end);
    let steps = if spacing > 0.0 {
        ((len / spacing).ceil() as usize).max(1)
    } else {
        1
    };
    let (mut front, mut back) = (Vec::new(), Vec::new());
    let (mut seen_f, mut seen_b) = (HashSet::new(), HashSet::new());
    for s in 0..=steps {
        let p = start.lerp(end, s as f64 / steps as f64);
        let hits = bvh.ray_hits(DVec3::new(p.x, p.y, z0), DVec3::NEG_Z);
        let Some(first) = hits.first() else { continue };
        if shell.tags[first.triangle as usize] != ElementTag::Front {
            continue;
        }
        if !skull.contains(&first.triangle) && seen_f.insert(first.triangle) {
            front.push(first.triangle);
        }
        if let Some(b) = hits[1..]
            .iter()
            .find(|h| shell.tags[h.triangle as usize] == ElementTag::Back)
            && !skull.contains(&b.triangle)
            && seen_b.insert(b.triangle)
        {
            back.push(b.triangle);
        }
    }
    (front, back)
}

/// Places the thesis's ten muscles (in [`MuscleKind::THESIS`] order) from the boxes.
pub(crate) fn place_standard_muscles(
    shell: &Shell,
    boxes: &FeatureBoxes,
    skull: &[u32],
    spacing: f64,
) -> Vec<Muscle> {
    let tris: Vec<[DVec3; 3]> = (0..shell.element_count())
        .map(|e| shell.corners(e))
        .collect();
    let bvh = TriangleBvh::new(&tris);
    let skull: HashSet<u32> = skull.iter().copied().collect();
    MuscleKind::THESIS
        .iter()
        .filter_map(|&kind| {
            let (s, e) = muscle_definer(kind, boxes)?;
            let (front, mut back) = project_definer(shell, &bvh, &skull, s, e, spacing);
            if front_only(kind) {
                back.clear();
            }
            Some(Muscle {
                name: kind.display_name().to_owned(),
                kind: Some(kind),
                front_chain: front,
                back_chain: back,
            })
        })
        .collect()
}

/// The path a chain of element centroids follows: interior points smoothed with weights
/// 1-2-1 (`(c[k-1] + 2 c[k] + c[k+1]) / 4`), the first and last centroids kept.
///
/// Ray projection puts into a chain every element a definer's rays hit, so consecutive
/// centroids alternate between the two sides of the definer and sometimes step backward; the
/// smoothed path cancels that alternation while keeping the chain's ends.
///
/// ```
/// use face_prep::muscles::chain_path;
/// use glam::DVec3;
/// // A zig-zag along +x, 0.3 to either side: the smoothed interior points lie within 0.15.
/// let c: Vec<DVec3> = (0..5)
///     .map(|k| DVec3::new(k as f64, if k % 2 == 0 { 0.3 } else { -0.3 }, 0.0))
///     .collect();
/// let p = chain_path(&c);
/// assert_eq!(p[0], c[0]);
/// assert_eq!(p[4], c[4]);
/// assert!(p[1..4].iter().all(|q| q.y.abs() < 0.16));
/// ```
pub fn chain_path(centroids: &[DVec3]) -> Vec<DVec3> {
    let n = centroids.len();
    (0..n)
        .map(|k| {
            if k > 0 && k + 1 < n {
                0.25 * (centroids[k - 1] + 2.0 * centroids[k] + centroids[k + 1])
            } else {
                centroids[k]
            }
        })
        .collect()
}

/// Per-element prescribed displacement of `muscle` at slider = +1 (relax): every chain element
/// but the last moves away from the next point of its chain's path ([`chain_path`]: the
/// centroids, smoothed) by the distance between the two path points; the end element stays put
/// (listed with zero). Contraction (negative slider) moves each element toward the next path
/// point, so the chain contracts toward its end. Slider `s` scales it exactly. Front chain
/// entries come first, then back chain entries.
///
/// Regression: with the raw centroids (`docs/design/controls.md`: "toward the next element's centroid") the
/// alternation of the centroids about the definer turned the contraction of the bundled faces'
/// standard muscles 40–51° off their definers on average (mean cosine 0.63–0.77 per face),
/// with 27 of 490 front steps backward; along the smoothed path the mean cosine is 0.83–0.95
/// and 6 steps are backward (0.85–0.94 and 6 of 526 on the pipeline's peeled, simplified
/// copies).
pub fn muscle_pattern(shell: &Shell, muscle: &Muscle) -> Vec<(u32, DVec3)> {
    let mut out = Vec::with_capacity(muscle.front_chain.len() + muscle.back_chain.len());
    for chain in [&muscle.front_chain, &muscle.back_chain] {
        let centroids: Vec<DVec3> = chain.iter().map(|&e| shell.centroid(e as usize)).collect();
        let path = chain_path(&centroids);
        for (k, &e) in chain.iter().enumerate() {
            let d = match path.get(k + 1) {
                Some(&next) => path[k] - next,
                None => DVec3::ZERO,
            };
            out.push((e, d));
        }
    }
    out
}
