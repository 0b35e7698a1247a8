//! The frame stage: the input mesh's four loops (outer contour, two eyes, mouth) in canonical
//! order and its canonical frame, found once per build and passed down to the stages that need
//! them (the copy keeps the mouth corners, the transfer and the settling passes place their
//! regions by the loops). The maths of the canonical frame is face-prep's
//! ([`face_prep::orient::canonical_frame`], `docs/design/frame.md`).

use face_prep::orient::{FaceLoops, canonical_frame};
use face_prep::{FaceMesh, FaceRig, PrepError};
use glam::{DAffine3, DVec3};

/// Errors of the frame stage.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum FrameError {
    /// The input mesh has no face's four loops, or no canonical frame could be set up from them
    /// (the rig build reports the same cause for the same mesh).
    #[error(transparent)]
    Loops(#[from] PrepError),
}

/// The input mesh's loops and its own canonical frame.
///
/// ```
/// let mesh = facebem::input::default_face()?;
/// let frame = facebem::frame::InputFrame::find(&mesh)?;
/// assert!(frame.loops.mouth.len() > 3);
/// # Ok::<(), Box<dyn std::error::Error>>(())
/// ```
#[derive(Clone, Debug)]
pub struct InputFrame {
    /// The input mesh's loops, in canonical order.
    pub loops: FaceLoops,
    /// The input mesh's own canonical frame (the rig's may differ when it is built on a copy).
    pub canonical_from_input: DAffine3,
}

impl InputFrame {
    /// Finds the loops and the canonical frame of `mesh`.
    pub fn find(mesh: &FaceMesh) -> Result<InputFrame, FrameError> {
        let loops = face_prep::topology::validate(&mesh.vertices, &mesh.triangles)?;
        let (canonical_from_input, loops) =
            canonical_frame(&mesh.vertices, &mesh.triangles, &loops)?;
        Ok(InputFrame {
            loops,
            canonical_from_input,
        })
    }

    /// The input mesh's vertices in its own canonical frame.
    pub fn canonical_points(&self, mesh: &FaceMesh) -> Vec<DVec3> {
        transformed(self.canonical_from_input, &mesh.vertices)
    }

    /// The input mesh's loops with its vertices in `rig`'s canonical frame.
    pub fn in_rig(&self, rig: &FaceRig, mesh: &FaceMesh) -> CanonicalFace {
        CanonicalFace {
            loops: self.loops.clone(),
            points: transformed(rig.canonical_from_input, &mesh.vertices),
        }
    }
}

/// The input mesh's loops and its vertices in the rig's canonical frame: what the transfer and
/// the settling passes place their regions by.
#[derive(Clone, Debug)]
pub struct CanonicalFace {
    /// The input mesh's loops, in canonical order.
    pub loops: FaceLoops,
    /// The input mesh's vertices in the rig's canonical frame.
    pub points: Vec<DVec3>,
}

impl CanonicalFace {
    /// `mesh`'s loops with its vertices in the canonical frame `canonical_from_input` (a rig's,
    /// which may differ from the mesh's own); `None` when the mesh has no face's four loops.
    ///
    /// ```
    /// let mesh = facebem::input::default_face()?;
    /// let frame = facebem::frame::InputFrame::find(&mesh)?;
    /// let face = facebem::frame::CanonicalFace::of_mesh(&mesh, frame.canonical_from_input).unwrap();
    /// assert_eq!(face.points, frame.canonical_points(&mesh));
    /// # Ok::<(), Box<dyn std::error::Error>>(())
    /// ```
    pub fn of_mesh(mesh: &FaceMesh, canonical_from_input: DAffine3) -> Option<CanonicalFace> {
        let frame = InputFrame::find(mesh).ok()?;
        Some(CanonicalFace {
            loops: frame.loops,
            points: transformed(canonical_from_input, &mesh.vertices),
        })
    }

    /// The mouth corners of the input mesh ([`mouth_corners`] of its mouth loop).
    pub fn mouth_corners(&self) -> Option<(u32, u32)> {
        mouth_corners(&self.points, &self.loops.mouth)
    }
}

fn transformed(frame: DAffine3, points: &[DVec3]) -> Vec<DVec3> {
    points.iter().map(|&p| frame.transform_point3(p)).collect()
}

/// The mouth corners: the vertices of the mouth loop `mouth` of largest and smallest canonical
/// x (`points` in the canonical frame), the face's left corner first; `None` for an empty loop.
///
/// ```
/// use glam::DVec3;
/// let p = [DVec3::new(-2.0, 0.0, 0.0), DVec3::new(0.0, 1.0, 0.0), DVec3::new(2.0, 0.0, 0.0)];
/// assert_eq!(facebem::frame::mouth_corners(&p, &[0, 1, 2]), Some((2, 0)));
/// ```
pub fn mouth_corners(points: &[DVec3], mouth: &[u32]) -> Option<(u32, u32)> {
    let x = |v: u32| points.get(v as usize).map_or(f64::NAN, |p| p.x);
    let extreme = |sign: f64| {
        mouth
            .iter()
            .copied()
            .filter(|&v| x(v).is_finite())
            .max_by(|&a, &b| (sign * x(a)).total_cmp(&(sign * x(b))))
    };
    Some((extreme(1.0)?, extreme(-1.0)?))
}
