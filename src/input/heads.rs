//! A file that is not one face but a head or an avatar of several parts (issue 32): what its
//! parts are ([`face_prep::parts`]) and the one line that says why it is not rigged yet. The
//! command line and the viewer say the same.

use std::path::Path;

use face_prep::parts::{HeadParts, PartKind, Scene, find_parts};

/// What was found in a file of several parts.
#[derive(Clone, Debug)]
pub struct WholeFile {
    /// The file as read.
    pub scene: Scene,
    /// Its parts (two eyeballs among them).
    pub parts: HeadParts,
}

impl WholeFile {
    /// Reads `path` whole; `None` unless two of its components are eyeballs (then the face
    /// reader's own error is the one to show: a file of loose triangles is not a head).
    pub fn read(path: &Path) -> Option<WholeFile> {
        let scene = Scene::read(path, &face_prep::InputLimits::default()).ok()?;
        let parts = find_parts(&scene).ok().filter(|p| p.eyeballs.is_some())?;
        Some(WholeFile { scene, parts })
    }

    /// The parts in a few words: `skin, 2 eyeballs, 16 upper and 16 lower teeth, ...`.
    pub fn summary(&self) -> String {
        let count = |kind: PartKind| self.parts.kinds.iter().filter(|k| **k == kind).count();
        let upper = count(PartKind::UpperTooth);
        let lower = count(PartKind::LowerTooth);
        let mut words = vec!["skin".to_owned(), "2 eyeballs".to_owned()];
        if upper + lower > 0 {
            words.push(format!("{upper} upper and {lower} lower teeth"));
        }
        for (kind, name) in [
            (PartKind::GumsAndTongue, "gums and tongue"),
            (PartKind::LidPart, "lid parts"),
            (PartKind::Other, "other parts"),
        ] {
            let n = count(kind);
            if n > 0 {
                words.push(format!("{n} {name}"));
            }
        }
        words.join(", ")
    }

    /// The one line that refuses the file.
    pub fn refusal(&self, path: &Path) -> String {
        format!(
            "{}: a head or avatar of {} parts ({}); `facebem export` rigs its front face and \
             carries the rig to every part, but rig, pose, sheet and the viewer take one face \
             (four openings: contour, eyes, mouth), not a whole head yet",
            path.display(),
            self.parts.components.len(),
            self.summary()
        )
    }
}
