//! The eyes' gaze on a whole head (issue 32, item 5): ARKit's eight `eyeLook*` targets and
//! VRM's `lookUp`/`lookDown`/`lookLeft`/`lookRight`, made from the eyeballs the head has.
//!
//! - **The eyeball** rotates rigidly about its own centre (the fitted sphere's,
//!   [`face_prep::parts::fit_sphere`]) by [`GAZE_UP_DEG`], [`GAZE_DOWN_DEG`] or
//!   [`GAZE_SIDEWAYS_DEG`], about the axis `forward × direction` of the head's own frame
//!   ([`face_prep::parts::HeadFrame`]), so its front turns the named way. A morph target is a
//!   straight line from neutral, so at weight 1 the eyeball is exactly rotated and between it
//!   is on the chord (at most `r (1 − cos θ/2)`, 0.5 mm for a 12 mm eyeball at 30°, inside).
//! - **The lids and the skin of the orbit follow the gaze** (lid–eye coordination: the upper
//!   lid tracks vertical gaze, Becker & Fuchs 1988, *Exp. Brain Res.* 69): a skin vertex is
//!   rotated about the same axis and centre by `k · s · θ`, where `k` is the direction's
//!   coupling ([`LID_FOLLOW_DOWN`], [`LID_FOLLOW_UP`], [`LID_FOLLOW_SIDEWAYS`]) and `s` falls
//!   from 1 within [`ORBIT_INNER`] eyeball radii of the centre to 0 at [`ORBIT_OUTER`]
//!   (`1 − smoothstep`). A rotation about the eyeball's centre keeps every skin vertex's
//!   distance from it, so a lid that clears the eyeball at rest clears it in every pose.
//!   The couplings and the orbit's extent were measured on ICT-FaceKit's captured `eyeLook*`
//!   shapes on its whole head (`tests/data/calibration/ict_head_deltas/`): the upper lid moves
//!   7.7 mm in eyeLookDown, 3.7 mm in eyeLookUp and 2.5 mm in eyeLookIn/Out, and the skin is
//!   still 1.7 eyeball radii from the centre.
//! - Lid parts (lashes, occlusion, tear film) follow the skin they lie nearest, as in every
//!   other target ([`super::head`]).
//!
//! The captured shapes leave the eyeballs still (ICT-FaceKit turns them with a separate
//! transform), so a comparison with them is made on every vertex but the eyeballs'.

use face_prep::parts::{HeadFrame, PartKind, Side, Sphere};
use glam::{DQuat, DVec3};

/// Upward gaze of `eyeLookUp*` at weight 1, in degrees (the human upward range is about 25°
/// of comfortable gaze, of at most 40–45°).
pub const GAZE_UP_DEG: f64 = 25.0;
/// Downward gaze of `eyeLookDown*` at weight 1, in degrees.
pub const GAZE_DOWN_DEG: f64 = 30.0;
/// Inward and outward gaze of `eyeLookIn*`/`eyeLookOut*` at weight 1, in degrees.
pub const GAZE_SIDEWAYS_DEG: f64 = 30.0;
/// The share of a downward gaze's angle the lids take.
pub const LID_FOLLOW_DOWN: f64 = 0.65;
/// The share of an upward gaze's angle the lids take.
pub const LID_FOLLOW_UP: f64 = 0.4;
/// The share of a sideways gaze's angle the lids take.
pub const LID_FOLLOW_SIDEWAYS: f64 = 0.2;
/// Within this many eyeball radii of its centre the skin takes the lids' full share.
pub const ORBIT_INNER: f64 = 1.4;
/// From this many eyeball radii of its centre the skin is still.
pub const ORBIT_OUTER: f64 = 1.7;

/// Where one eye looks.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Look {
    /// Up.
    Up,
    /// Down.
    Down,
    /// Toward the nose.
    In,
    /// Away from the nose.
    Out,
}

/// ARKit's eight gaze targets: (name, eye, direction).
pub const ARKIT_GAZE: [(&str, Side, Look); 8] = [
    ("eyeLookDownLeft", Side::Left, Look::Down),
    ("eyeLookDownRight", Side::Right, Look::Down),
    ("eyeLookInLeft", Side::Left, Look::In),
    ("eyeLookInRight", Side::Right, Look::In),
    ("eyeLookOutLeft", Side::Left, Look::Out),
    ("eyeLookOutRight", Side::Right, Look::Out),
    ("eyeLookUpLeft", Side::Left, Look::Up),
    ("eyeLookUpRight", Side::Right, Look::Up),
];

/// VRM 1.0's gaze targets as sums of ARKit's (left and right are the avatar's own, as in
/// three-vrm's `VRMLookAtExpressionApplier`: `lookLeft` turns both eyes to the avatar's left).
pub const VRM_GAZE: [(&str, [&str; 2]); 4] = [
    ("lookUp", ["eyeLookUpLeft", "eyeLookUpRight"]),
    ("lookDown", ["eyeLookDownLeft", "eyeLookDownRight"]),
    ("lookLeft", ["eyeLookOutLeft", "eyeLookInRight"]),
    ("lookRight", ["eyeLookInLeft", "eyeLookOutRight"]),
];

/// The gaze angle at weight 1, in radians, and the lids' share of it.
pub fn angle_and_follow(look: Look) -> (f64, f64) {
    match look {
        Look::Up => (GAZE_UP_DEG.to_radians(), LID_FOLLOW_UP),
        Look::Down => (GAZE_DOWN_DEG.to_radians(), LID_FOLLOW_DOWN),
        Look::In | Look::Out => (GAZE_SIDEWAYS_DEG.to_radians(), LID_FOLLOW_SIDEWAYS),
    }
}

/// The unit axis the eye on `side` turns about, by the right-hand rule, to look `look`.
pub fn axis(frame: &HeadFrame, side: Side, look: Look) -> DVec3 {
    let toward_left = match side {
        Side::Left => 1.0,
        Side::Right => -1.0,
    };
    let direction = match look {
        Look::Up => frame.up,
        Look::Down => -frame.up,
        // Out of the left eye is toward the subject's left.
        Look::Out => toward_left * frame.left,
        Look::In => -toward_left * frame.left,
    };
    frame.forward.cross(direction).normalize_or_zero()
}

/// The displacement field (before lid parts follow the skin) of the eye on `side` looking
/// `look` at weight 1: its eyeball rotated, the skin of its orbit following.
///
/// ```
/// use face_prep::parts::{HeadFrame, PartKind, Side, Sphere};
/// use facebem::transfer::gaze::{Look, look_field};
/// use glam::DVec3;
/// let frame = HeadFrame { left: DVec3::X, up: DVec3::Y, forward: DVec3::Z };
/// let eye = Sphere { centre: DVec3::ZERO, radius: 1.0, rms: 0.0 };
/// let positions = [DVec3::Z, DVec3::new(0.0, 0.0, 5.0)];
/// let kinds = [Some(PartKind::Eyeball(Side::Left)), Some(PartKind::Skin)];
/// let field = look_field(&positions, &kinds, &frame, [eye, eye], Side::Left, Look::Up);
/// assert!(field[0].y > 0.4 && field[0].z < 0.0); // the front of the eye turns up
/// assert_eq!(field[1], DVec3::ZERO); // skin five radii away is still
/// ```
pub fn look_field(
    positions: &[DVec3],
    kinds: &[Option<PartKind>],
    frame: &HeadFrame,
    eyeballs: [Sphere; 2],
    side: Side,
    look: Look,
) -> Vec<DVec3> {
    let eye = match side {
        Side::Left => eyeballs[0],
        Side::Right => eyeballs[1],
    };
    let other = match side {
        Side::Left => eyeballs[1],
        Side::Right => eyeballs[0],
    };
    let (angle, follow) = angle_and_follow(look);
    let axis = axis(frame, side, look);
    let turn = |p: DVec3, share: f64| {
        let q = DQuat::from_axis_angle(axis, share * angle);
        q * (p - eye.centre) - (p - eye.centre)
    };
    positions
        .iter()
        .zip(kinds)
        .map(|(&p, kind)| match kind {
            Some(PartKind::Eyeball(s)) if *s == side => turn(p, 1.0),
            Some(PartKind::Skin) => {
                let d = p.distance(eye.centre);
                // The skin of the other orbit is the other eye's.
                if d >= p.distance(other.centre) || eye.radius <= 0.0 {
                    return DVec3::ZERO;
                }
                let t =
                    ((d / eye.radius - ORBIT_INNER) / (ORBIT_OUTER - ORBIT_INNER)).clamp(0.0, 1.0);
                let s = 1.0 - t * t * (3.0 - 2.0 * t);
                if s > 0.0 {
                    turn(p, follow * s)
                } else {
                    DVec3::ZERO
                }
            }
            _ => DVec3::ZERO,
        })
        .collect()
}
