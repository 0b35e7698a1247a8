//! A file that is not one face but a head or an avatar of several parts (issue 32): what its
//! parts are ([`face_prep::parts`]) and the one line that says why it is not rigged yet. The
//! command line and the viewer say the same.

use std::path::Path;

use face_prep::parts::{HeadParts, PartKind, Scene, find_parts};

/// The fewest triangles of the largest part for a file without eyeballs to be refused as "no
/// eyeballs" rather than with the face reader's error.
pub const MIN_SKIN_TRIANGLES: usize = 1000;

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
        Self::examine(path).and_then(Result::ok)
    }

    /// Like [`WholeFile::read`], but a file of several parts that is refused as a head (two
    /// skins: two heads or two faces; a part over [`face_prep::parts::MAX_PART_TRIANGLES`])
    /// is `Some(Err(one line))`.
    pub fn examine(path: &Path) -> Option<Result<WholeFile, String>> {
        let scene = Scene::read(path, &face_prep::InputLimits::default()).ok()?;
        match find_parts(&scene) {
            Ok(parts) if parts.eyeballs.is_some() => Some(Ok(WholeFile { scene, parts })),
            // A surface of some size with other parts and no eyeballs: not a head (a file of
            // loose triangles keeps the face reader's own error).
            Ok(parts)
                if parts.components.len() >= 2
                    && parts.components[0].triangles.len() >= MIN_SKIN_TRIANGLES =>
            {
                Some(Err(format!(
                    "{}: {} parts and no eyeballs among them: a head is read whole by its two \
                     eyeballs (closed spheres in the eye openings), a face alone needs four \
                     openings (contour, two eyes, mouth)",
                    path.display(),
                    parts.components.len()
                )))
            }
            Err(face_prep::parts::PartsError::TwoSkins(a, _)) if a < MIN_SKIN_TRIANGLES => None,
            Ok(_) | Err(face_prep::parts::PartsError::Empty) => None,
            Err(e) => Some(Err(format!("{}: {e}", path.display()))),
        }
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
             carries the rig to every part (pose, sheet and the viewer move it so), but a rig \
             file holds one face (four openings: contour, eyes, mouth), not a whole head yet",
            path.display(),
            self.parts.components.len(),
            self.summary()
        )
    }
}
