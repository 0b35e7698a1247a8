//! The user's own look in a glTF export: an OBJ's `mtllib` materials (`Kd` colour, `map_Kd`
//! texture) instead of the fixed [`super::MATERIAL_NAME`] skin (issue 34, item 4).
//!
//! [`ObjMaterials::load`] reads the material libraries an OBJ text names and the PNG or JPEG
//! textures they name, all from the OBJ's own folder: a path that leaves it (`..`, an absolute
//! path, a symbolic link pointing out) is refused, as the rest of facebem never reads outside
//! an input's folder. The textures are embedded in the GLB (`images[].bufferView`, glTF's
//! `image/png` or `image/jpeg`). What cannot be used is a warning, not an error: a missing
//! library or texture, a texture in another format (TGA, BMP: glTF has none of them) leaves
//! that material with its `Kd` colour, or the skin.
//!
//! Each triangle takes the material of the `usemtl` before its `f` line; triangles before any
//! `usemtl` (or naming a material no library defines) take [`super::MATERIAL_NAME`]. The export
//! writes one primitive per material, all sharing the vertices and the morph targets.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use face_prep::obj_text;

/// Largest texture embedded (64 MiB); a larger one is a warning and left out.
pub const MAX_TEXTURE_BYTES: u64 = 64 << 20;
/// Largest material library read (4 MiB).
pub const MAX_MTL_BYTES: u64 = 4 << 20;

/// Errors reading an OBJ's materials: only a path that leaves the OBJ's folder.
#[derive(Debug, thiserror::Error, PartialEq)]
#[non_exhaustive]
pub enum MaterialError {
    /// A material library or texture path leaves the OBJ's folder.
    #[error("{what} {path:?} is outside the OBJ's folder {}: refused (facebem reads nothing outside an input's folder)", folder.display())]
    OutsideFolder {
        /// `material library` or `texture`.
        what: &'static str,
        /// The path as written.
        path: String,
        /// The OBJ's folder.
        folder: PathBuf,
    },
    /// The OBJ text itself does not parse ([`face_prep::obj_text`]).
    #[error(transparent)]
    Obj(#[from] face_prep::ObjLineError),
}

/// An embedded texture.
#[derive(Clone, Debug, PartialEq)]
pub struct Texture {
    /// The file's bytes, shared: export parameters are cloned on their way to the writer, and
    /// a texture may be 64 MiB.
    pub bytes: std::sync::Arc<[u8]>,
    /// `image/png` or `image/jpeg`.
    pub mime: &'static str,
}

/// One material of a library.
#[derive(Clone, Debug, PartialEq)]
pub struct UserMaterial {
    /// `newmtl` name.
    pub name: String,
    /// `Kd` (linear RGB as written; glTF's baseColorFactor), white when a texture is given
    /// without `Kd`.
    pub base_color: [f32; 3],
    /// `map_Kd`, when it could be read.
    pub texture: Option<Texture>,
}

/// The materials of an OBJ and which triangle uses which.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ObjMaterials {
    /// The materials used, in order of first use.
    pub materials: Vec<UserMaterial>,
    /// Per triangle of the OBJ (faces fan-triangulated in file order, as
    /// [`super::ExportLayout`] does): an index into `materials`, or `None` for the skin.
    pub triangle_material: Vec<Option<u32>>,
    /// Every file read (libraries and textures): inputs an output must not overwrite.
    pub files_read: Vec<PathBuf>,
    /// What could not be used, one line each.
    pub warnings: Vec<String>,
}

impl ObjMaterials {
    /// Reads the materials of the OBJ `text` from `folder`, the OBJ's own.
    ///
    /// ```
    /// use facebem::export::material::ObjMaterials;
    /// let dir = tempfile::tempdir().unwrap();
    /// std::fs::write(dir.path().join("skin.mtl"), "newmtl skin\nKd 0.8 0.6 0.5\n").unwrap();
    /// let obj = "mtllib skin.mtl\nv 0 0 0\nv 1 0 0\nv 0 1 0\nusemtl skin\nf 1 2 3\n";
    /// let m = ObjMaterials::load(obj, dir.path()).unwrap();
    /// assert_eq!(m.materials[0].base_color, [0.8, 0.6, 0.5]);
    /// assert_eq!(m.triangle_material, [Some(0)]);
    /// let escape = "mtllib ../skin.mtl\nv 0 0 0\nf 1 1 1\n";
    /// assert!(ObjMaterials::load(escape, dir.path()).is_err());
    /// ```
    pub fn load(text: &str, folder: &Path) -> Result<ObjMaterials, MaterialError> {
        let mut out = ObjMaterials::default();
        let mut library: HashMap<String, Library> = HashMap::new();
        let mut current: Option<String> = None;
        let mut used: HashMap<String, Option<u32>> = HashMap::new();
        let mut face_material: HashMap<usize, Option<u32>> = HashMap::new();
        for (index, line) in text.lines().enumerate() {
            let mut words = line.split_whitespace();
            match words.next() {
                Some("mtllib") => {
                    for name in words {
                        let path = inside(folder, name, "material library")?;
                        out.read_library(&path, name, &mut library);
                    }
                }
                Some("usemtl") => current = Some(rest_of(line, "usemtl")),
                Some("f") => {
                    let material = match &current {
                        None => None,
                        Some(name) => match used.get(name) {
                            Some(m) => *m,
                            None => {
                                let m = out.use_material(name, &library, folder)?;
                                used.insert(name.clone(), m);
                                m
                            }
                        },
                    };
                    face_material.insert(index + 1, material);
                }
                _ => {}
            }
        }
        for face in obj_text::parse(text)?.faces {
            let m = face_material.get(&face.line).copied().flatten();
            for _ in 2..face.corners.len() {
                out.triangle_material.push(m);
            }
        }
        Ok(out)
    }

    /// Reads the library at `path` into `library` (a warning when it cannot be read).
    fn read_library(&mut self, path: &Path, name: &str, library: &mut HashMap<String, Library>) {
        let text = match read_limited(path, MAX_MTL_BYTES) {
            Ok(bytes) => String::from_utf8_lossy(&bytes).into_owned(),
            Err(why) => {
                self.warnings
                    .push(format!("material library {name}: {why}; the skin is used"));
                return;
            }
        };
        self.files_read.push(path.to_path_buf());
        let mut name: Option<String> = None;
        for line in text.lines() {
            let mut words = line.split_whitespace();
            match words.next() {
                Some("newmtl") => {
                    let n = rest_of(line, "newmtl");
                    library.insert(n.clone(), Library::default());
                    name = Some(n);
                }
                Some("Kd") => {
                    let kd: Vec<f32> = words.filter_map(|w| w.parse().ok()).collect();
                    if let (Some(n), [r, g, b]) = (&name, kd.as_slice())
                        && [r, g, b].iter().all(|c| c.is_finite())
                        && let Some(entry) = library.get_mut(n)
                    {
                        entry.kd = Some([r.clamp(0.0, 1.0), g.clamp(0.0, 1.0), b.clamp(0.0, 1.0)]);
                    }
                }
                Some("map_Kd") => {
                    if let Some(entry) = name.as_ref().and_then(|n| library.get_mut(n)) {
                        entry.map_kd = texture_file_name(line);
                    }
                }
                _ => {}
            }
        }
    }

    /// The index of material `name` among those used (reading its texture), or `None` (the
    /// skin) when no library defines it.
    fn use_material(
        &mut self,
        name: &str,
        library: &HashMap<String, Library>,
        folder: &Path,
    ) -> Result<Option<u32>, MaterialError> {
        let Some(entry) = library.get(name) else {
            self.warnings.push(format!(
                "material {name:?} is not in a material library; the skin is used"
            ));
            return Ok(None);
        };
        let mut texture = None;
        if let Some(file) = &entry.map_kd {
            let path = inside(folder, file, "texture")?;
            match read_limited(&path, MAX_TEXTURE_BYTES) {
                Ok(bytes) => match image_mime(&bytes) {
                    Some(mime) => {
                        self.files_read.push(path);
                        texture = Some(Texture {
                            bytes: bytes.into(),
                            mime,
                        });
                    }
                    None => self.warnings.push(format!(
                        "texture {file} of material {name:?} is neither PNG nor JPEG (glTF's image formats); its colour is used"
                    )),
                },
                Err(why) => self
                    .warnings
                    .push(format!("texture {file} of material {name:?}: {why}")),
            }
        }
        let white = [1.0; 3];
        self.materials.push(UserMaterial {
            name: name.to_string(),
            base_color: entry.kd.unwrap_or(white),
            texture,
        });
        Ok(Some(self.materials.len() as u32 - 1))
    }
}

/// A material as its library defines it.
#[derive(Default)]
struct Library {
    kd: Option<[f32; 3]>,
    map_kd: Option<String>,
}

/// The rest of `line` after its keyword, trimmed (names may hold spaces).
fn rest_of(line: &str, keyword: &str) -> String {
    line.trim_start()
        .strip_prefix(keyword)
        .unwrap_or("")
        .trim()
        .to_string()
}

/// The file name of a `map_Kd` line, after its options (`-s 1 1 1`, `-clamp on`, …).
fn texture_file_name(line: &str) -> Option<String> {
    let words: Vec<&str> = line.split_whitespace().skip(1).collect();
    let mut k = 0;
    while k < words.len() && words[k].starts_with('-') {
        let takes = match words[k] {
            "-o" | "-s" | "-t" => 3,
            "-mm" => 2,
            _ => 1,
        };
        k += 1;
        // Options take up to `takes` numbers (`-o u [v [w]]`), or one word.
        let mut taken = 0;
        while taken < takes
            && k < words.len()
            && (words[k].parse::<f64>().is_ok() || (takes == 1 && taken == 0))
        {
            k += 1;
            taken += 1;
        }
    }
    let name = words[k.min(words.len())..].join(" ");
    (!name.is_empty()).then_some(name)
}

/// `name` (as written in the OBJ or a library) inside `folder`, or the refusal: absolute paths,
/// `..` and symbolic links that lead out are refused. A file that does not exist is returned
/// as it is (reading it then fails with a warning).
fn inside(folder: &Path, name: &str, what: &'static str) -> Result<PathBuf, MaterialError> {
    let refuse = || MaterialError::OutsideFolder {
        what,
        path: name.to_string(),
        folder: folder.to_path_buf(),
    };
    // Windows-style separators, as many exporters write them.
    let relative = PathBuf::from(name.replace('\\', "/"));
    let plain = relative.components().all(|c| {
        matches!(
            c,
            std::path::Component::Normal(_) | std::path::Component::CurDir
        )
    });
    if !plain {
        return Err(refuse());
    }
    let path = folder.join(&relative);
    if let (Ok(real), Ok(real_folder)) = (path.canonicalize(), folder.canonicalize())
        && !real.starts_with(&real_folder)
    {
        return Err(refuse());
    }
    Ok(path)
}

/// The bytes of `path`, at most `limit` of them (a larger file is refused).
fn read_limited(path: &Path, limit: u64) -> Result<Vec<u8>, String> {
    use std::io::Read;
    let file = std::fs::File::open(path).map_err(|e| format!("cannot be read ({e})"))?;
    let meta = file
        .metadata()
        .map_err(|e| format!("cannot be read ({e})"))?;
    if !meta.is_file() {
        return Err("is not a regular file".into());
    }
    if meta.len() > limit {
        return Err(format!("is over the {} MiB limit", limit >> 20));
    }
    let mut bytes = Vec::with_capacity(meta.len() as usize);
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(|e| format!("cannot be read ({e})"))?;
    if bytes.len() as u64 > limit {
        return Err(format!("is over the {} MiB limit", limit >> 20));
    }
    Ok(bytes)
}

/// glTF's MIME type of an image by its signature: PNG or JPEG, else `None`.
fn image_mime(bytes: &[u8]) -> Option<&'static str> {
    if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
        Some("image/png")
    } else if bytes.starts_with(&[0xFF, 0xD8, 0xFF]) {
        Some("image/jpeg")
    } else {
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn map_kd_options_are_skipped() {
        assert_eq!(
            texture_file_name("map_Kd skin.png").as_deref(),
            Some("skin.png")
        );
        assert_eq!(
            texture_file_name("map_Kd -s 1 1 1 -clamp on my skin.png").as_deref(),
            Some("my skin.png")
        );
        assert_eq!(
            texture_file_name("map_Kd -o 0.5 tex.jpg").as_deref(),
            Some("tex.jpg")
        );
        assert_eq!(texture_file_name("map_Kd"), None);
    }

    #[test]
    fn paths_that_leave_the_folder_are_refused() {
        let dir = tempfile::tempdir().unwrap();
        for bad in ["../x.png", "/etc/passwd", "a/../../x.png", "..\\x.png"] {
            assert!(inside(dir.path(), bad, "texture").is_err(), "{bad}");
        }
        assert!(inside(dir.path(), "tex/skin.png", "texture").is_ok());
        #[cfg(unix)]
        {
            let outside = tempfile::tempdir().unwrap();
            std::fs::write(outside.path().join("x.png"), b"x").unwrap();
            std::os::unix::fs::symlink(outside.path().join("x.png"), dir.path().join("l.png"))
                .unwrap();
            assert!(inside(dir.path(), "l.png", "texture").is_err());
        }
    }
}
