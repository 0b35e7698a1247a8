//! The vocabulary every control module shares, with no dependency inside the crate: which
//! side of the face a control is on, and the actions of the controls that are not muscle bands
//! (the jaw's rigid modes, the lids' actions, the sphincter's halves). The table of controls
//! ([`crate::controls::muscle_kind`]) and every generator import these; these import nothing.

use serde::{Deserialize, Serialize};

/// Which side of the face a control is on. "Left" is the face's own left, i.e. +x in the
/// canonical frame (the face looks toward +z).
// Exhaustive on purpose: a face has a left, a right and a midline, no other side.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Side {
    /// The face's left (+x in the canonical frame).
    Left,
    /// The face's right (−x in the canonical frame).
    Right,
    /// Unpaired, on the midline (its mirror is itself).
    Center,
}

impl Side {
    /// The other side (`Center` stays `Center`).
    pub fn opposite(self) -> Side {
        match self {
            Side::Left => Side::Right,
            Side::Right => Side::Left,
            Side::Center => Side::Center,
        }
    }
}

/// One rigid mode of the jaw.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum JawMode {
    /// Rotation about the TMJ axis (mouth opening).
    Open,
    /// Protrusion (translation toward +z).
    Forward,
    /// Lateral shift (translation along x).
    Lateral,
}

/// What a lid muscle does at full activation (slider −1).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[non_exhaustive]
pub enum LidAction {
    /// Orbicularis oculi, palpebral part: the upper margin closes onto the lower margin.
    Blink,
    /// Orbicularis oculi, orbital part: the lower lid and the cheek rise.
    Squint,
    /// Levator palpebrae superioris: the upper lid rises.
    Wide,
}

/// Which half of the mouth's sphincter a [`Generator::Sphincter`](crate::controls::muscle_kind::Generator::Sphincter) control is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Lip {
    /// Above the mouth's centre line.
    Upper,
    /// Below it.
    Lower,
}
