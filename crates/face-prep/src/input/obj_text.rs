//! The statements of an OBJ text facebem uses (`v`, `vt`, `vn`, `f`), read line by line with
//! one set of rules shared by the face reader ([`crate::FaceMesh::from_obj_bytes`]) and by
//! whatever reads the user's OBJ text again later (facebem's exports keep the user's layout), so
//! that a file the reader accepts is one the exports can read.
//!
//! The rules, on top of tobj's (which parses the geometry):
//!
//! - every number of a `v`, `vt` or `vn` line is finite (no `nan`, `inf`), and so is a position
//!   once divided by its w; a w is not zero; a texture coordinate fits in a 32-bit float (as
//!   glTF stores it);
//! - a face corner refers only to `v`, `vt` and `vn` lines that come BEFORE the face, counted
//!   from the start (`1` is the first) or back from the face (`-1` is the last one above it).
//!
//! A line is a statement when its first whitespace-separated word is the keyword (`v`, `vt`,
//! `vn`, `f`); every other line (comments, groups, materials, `l`, `p`) is ignored here.
//!
//! ```
//! use face_prep::obj_text::{self, ObjCorner};
//! let obj = obj_text::parse("v 0 0 0\nv 2 0 0 2\nv 0 1 0\nvt 0.5 0.5\nf 1/1 2/1 -1/1\n").unwrap();
//! assert_eq!(obj.positions[1], glam::DVec3::X); // divided by w
//! assert_eq!(obj.faces[0].corners[2], ObjCorner { v: 2, vt: Some(0), vn: None });
//! let err = obj_text::parse("v 0 0 0\nf 1 2 3\nv 1 0 0\nv 0 1 0\n").unwrap_err();
//! assert_eq!(err.to_string(), "OBJ line 2: face corner \"2\" refers to a `v` line that does not come before the face (there are 1 above it)");
//! ```

use glam::DVec3;

use crate::error::{ObjLineError, PrepError};
use crate::input::limits::InputLimits;

/// One face corner: 0-based indices of its `v`, `vt` and `vn` lines (in the order of each kind).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ObjCorner {
    /// Index of the position (`v` line).
    pub v: usize,
    /// Index of the texture coordinate (`vt` line), if the corner names one.
    pub vt: Option<usize>,
    /// Index of the normal (`vn` line), if the corner names one.
    pub vn: Option<usize>,
}

/// One `f` line.
#[derive(Clone, Debug, PartialEq)]
pub struct ObjFace {
    /// 1-based line number.
    pub line: usize,
    /// Its corners in order (a polygon; fewer than three for a degenerate `f` line).
    pub corners: Vec<ObjCorner>,
}

/// The statements of an OBJ text, in file order per kind.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct ObjStatements {
    /// Positions of the `v` lines (divided by their w when they have one).
    pub positions: Vec<DVec3>,
    /// Texture coordinates `(u, v)` of the `vt` lines, OBJ convention.
    pub texcoords: Vec<[f64; 2]>,
    /// Normals of the `vn` lines, as written (not normalised).
    pub normals: Vec<DVec3>,
    /// The `f` lines.
    pub faces: Vec<ObjFace>,
}

/// Whether `line` is a `v` line (its first word is `v`), the rule every reader and writer of a
/// user's OBJ text counts positions by.
///
/// ```
/// use face_prep::obj_text::is_vertex_line;
/// assert!(is_vertex_line("  v 1 2 3"));
/// assert!(is_vertex_line("v\u{c}1 2 3"));
/// assert!(!is_vertex_line("vt 1 2"));
/// ```
pub fn is_vertex_line(line: &str) -> bool {
    line.split_whitespace().next() == Some("v")
}

/// The first word of `line` that parses as a number but is not finite (`nan`, `inf`,
/// `-infinity`, or a literal too large for an f64), if any.
///
/// ```
/// use face_prep::obj_text::non_finite_word;
/// assert_eq!(non_finite_word("vt 0.5 NaN"), Some("NaN"));
/// assert_eq!(non_finite_word("vn 0 1e999 0"), Some("1e999"));
/// assert_eq!(non_finite_word("v 1 2 3"), None);
/// ```
pub fn non_finite_word(line: &str) -> Option<&str> {
    line.split_whitespace()
        .find(|w| w.parse::<f64>().is_ok_and(|x| !x.is_finite()))
}

/// Parses the `v`, `vt`, `vn` and `f` lines of `text` under the rules of the module docs.
pub fn parse(text: &str) -> Result<ObjStatements, ObjLineError> {
    let mut out = ObjStatements::default();
    let mut scanner = Scanner::default();
    for (index, line) in text.lines().enumerate() {
        match scanner.line(index + 1, line)? {
            Some(Statement::Position(p)) => out.positions.push(p),
            Some(Statement::Texcoord(t)) => out.texcoords.push(t),
            Some(Statement::Normal(n)) => out.normals.push(n),
            Some(Statement::Face(face)) => out.faces.push(face),
            None => {}
        }
    }
    Ok(out)
}

/// The positions of the `v` lines of `text` (as [`parse`] reads them), every line checked by
/// the rules of the module docs; at most `limits.max_positions` of them (the faces are checked
/// but not kept).
pub(crate) fn checked_positions(text: &str, limits: &InputLimits) -> Result<Vec<DVec3>, PrepError> {
    let mut positions = Vec::new();
    let mut scanner = Scanner::default();
    for (index, line) in text.lines().enumerate() {
        // Past the limit, positions are counted (for the message) but not kept.
        if let Some(Statement::Position(p)) = scanner.line(index + 1, line)?
            && positions.len() < limits.max_positions
        {
            positions.push(p);
        }
    }
    limits.check_count("positions", scanner.counts[0] as u64, limits.max_positions)?;
    Ok(positions)
}

/// One statement of an OBJ line.
enum Statement {
    Position(DVec3),
    Texcoord([f64; 2]),
    Normal(DVec3),
    Face(ObjFace),
}

/// Reads OBJ lines in order, counting the `v`, `vt` and `vn` lines seen so far.
#[derive(Default)]
struct Scanner {
    counts: [usize; 3],
}

impl Scanner {
    /// The statement of line `n` (1-based), or `None` for a line of another kind.
    fn line(&mut self, n: usize, line: &str) -> Result<Option<Statement>, ObjLineError> {
        let mut words = line.split_whitespace();
        let keyword = words.next();
        if matches!(keyword, Some("v" | "vt" | "vn")) && non_finite_word(line).is_some() {
            return Err(ObjLineError::NonFinite {
                line: n,
                text: line.trim().to_owned(),
            });
        }
        let statement = match keyword {
            Some("v") => Statement::Position(position(n, line)?),
            Some("vt") => {
                let [u, v] = numbers::<2>(n, line, "`vt u v`")?;
                if u.abs().max(v.abs()) > f64::from(f32::MAX) {
                    return Err(ObjLineError::TexcoordOutOfRange {
                        line: n,
                        text: line.trim().to_owned(),
                    });
                }
                Statement::Texcoord([u, v])
            }
            Some("vn") => Statement::Normal(DVec3::from(numbers::<3>(n, line, "`vn x y z`")?)),
            Some("f") => {
                let corners = words
                    .map(|w| corner(n, w, self.counts))
                    .collect::<Result<Vec<_>, _>>()?;
                return Ok(Some(Statement::Face(ObjFace { line: n, corners })));
            }
            _ => return Ok(None),
        };
        let k = match statement {
            Statement::Position(_) => 0,
            Statement::Texcoord(_) => 1,
            _ => 2,
        };
        self.counts[k] += 1;
        Ok(Some(statement))
    }
}

/// The first `N` numbers after the keyword of `line` (line number `n`); more words may follow.
fn numbers<const N: usize>(
    n: usize,
    line: &str,
    expected: &'static str,
) -> Result<[f64; N], ObjLineError> {
    let malformed = || ObjLineError::Malformed {
        line: n,
        text: line.trim().to_owned(),
        expected,
    };
    let mut words = line.split_whitespace().skip(1);
    let mut out = [0.0; N];
    for x in &mut out {
        *x = words
            .next()
            .and_then(|w| w.parse().ok())
            .ok_or_else(malformed)?;
    }
    Ok(out)
}

/// The position of a `v` line (number `n`): `x y z`, then nothing, a w (which divides the
/// position, as tobj does) or three colour components.
fn position(n: usize, line: &str) -> Result<DVec3, ObjLineError> {
    const EXPECTED: &str = "`v x y z`, `v x y z w` or `v x y z r g b`";
    let p = DVec3::from(numbers::<3>(n, line, EXPECTED)?);
    let rest: Vec<&str> = line.split_whitespace().skip(4).collect();
    let text = || line.trim().to_owned();
    let p = match rest.as_slice() {
        [] | [_, _, _] => p,
        [w] => match w.parse::<f64>() {
            Ok(0.0) => {
                return Err(ObjLineError::ZeroW {
                    line: n,
                    text: text(),
                });
            }
            Ok(w) => p / w,
            Err(_) => {
                return Err(ObjLineError::Malformed {
                    line: n,
                    text: text(),
                    expected: EXPECTED,
                });
            }
        },
        _ => {
            return Err(ObjLineError::Malformed {
                line: n,
                text: text(),
                expected: EXPECTED,
            });
        }
    };
    if !p.is_finite() {
        return Err(ObjLineError::NonFinite {
            line: n,
            text: text(),
        });
    }
    Ok(p)
}

/// Parses a face corner `v`, `v/vt`, `v//vn` or `v/vt/vn` of line `n` (1-based indices, or
/// negative ones counting back from the face); `counts` are the `v`, `vt` and `vn` lines above.
fn corner(n: usize, word: &str, counts: [usize; 3]) -> Result<ObjCorner, ObjLineError> {
    let bad = || ObjLineError::BadCorner {
        line: n,
        corner: word.to_owned(),
    };
    let parts: Vec<&str> = word.split('/').collect();
    if parts.len() > 3 || parts[0].is_empty() {
        return Err(bad());
    }
    let mut out = [None; 3];
    for (k, part) in parts.iter().enumerate() {
        if part.is_empty() {
            continue;
        }
        let i: i64 = part.parse().map_err(|_| bad())?;
        if i == 0 {
            return Err(bad());
        }
        let count = counts[k];
        let index = if i > 0 {
            usize::try_from(i - 1).ok().filter(|&x| x < count)
        } else {
            usize::try_from(i.unsigned_abs())
                .ok()
                .and_then(|back| count.checked_sub(back))
        };
        out[k] = Some(index.ok_or_else(|| ObjLineError::UndefinedCorner {
            line: n,
            corner: word.to_owned(),
            statement: ["v", "vt", "vn"][k],
            defined: count,
        })?);
    }
    Ok(ObjCorner {
        v: out[0].ok_or_else(bad)?,
        vt: out[1],
        vn: out[2],
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn corners_follow_the_lines_above_the_face() {
        let obj = "v 0 0 0\nv 1 0 0\nv 1 1 0\nvn 0 0 1\nf 1//1 -2//-1 3\n";
        let s = parse(obj).unwrap();
        assert_eq!(
            s.faces[0].corners,
            [
                ObjCorner {
                    v: 0,
                    vt: None,
                    vn: Some(0)
                },
                ObjCorner {
                    v: 1,
                    vt: None,
                    vn: Some(0)
                },
                ObjCorner {
                    v: 2,
                    vt: None,
                    vn: None
                },
            ]
        );
        for (face, statement) in [("f 1 2 4", "v"), ("f 1/1 2 3", "vt"), ("f 1//2 2 3", "vn")] {
            let err = parse(&format!("{obj}{face}\n")).unwrap_err();
            assert!(
                matches!(err, ObjLineError::UndefinedCorner { line: 6, statement: s, .. } if s == statement),
                "{face}: {err}"
            );
        }
        for face in [
            "f 0 1 2",
            "f 1/1/1/1 2 3",
            "f a 2 3",
            "f /1 2 3",
            "f -4 1 2",
        ] {
            let err = parse(&format!("{obj}{face}\n")).unwrap_err();
            assert!(
                matches!(
                    err,
                    ObjLineError::BadCorner { line: 6, .. }
                        | ObjLineError::UndefinedCorner { line: 6, .. }
                ),
                "{face}: {err}"
            );
        }
    }

    #[test]
    fn numbers_must_be_finite_and_w_not_zero() {
        for (line, zero_w) in [
            ("v nan 0 0", false),
            ("v 0 0 0 inf", false),
            ("v 1e300 0 0 1e-300", false),
            ("v 0 0 0 1 NaN 1", false),
            ("vt 0.5 nan", false),
            ("vt 0.5 0.5 inf", false),
            ("vn inf 0 1", false),
            ("v 1 2 3 0", true),
            ("v 1 2 3 -0.0", true),
        ] {
            let err = parse(&format!("v 0 0 0\n{line}\n")).unwrap_err();
            if zero_w {
                assert!(
                    matches!(err, ObjLineError::ZeroW { line: 2, .. }),
                    "{line}: {err}"
                );
            } else {
                assert!(
                    matches!(err, ObjLineError::NonFinite { line: 2, .. }),
                    "{line}: {err}"
                );
            }
        }
        let err = parse("vt 0.5 -1e39\n").unwrap_err();
        assert!(
            matches!(err, ObjLineError::TexcoordOutOfRange { line: 1, .. }),
            "{err}"
        );
        for line in ["v 1 2", "v 1 2 3 4 5", "v 1 2 3 w", "vt 1", "vn 0 1"] {
            let err = parse(line).unwrap_err();
            assert!(
                matches!(err, ObjLineError::Malformed { line: 1, .. }),
                "{line}: {err}"
            );
        }
        let s = parse("v 1 2 3 0.5 0.5 0.5\nvt 0.25 0.5 0\n# nan\nvn 0 0 2 x\n").unwrap();
        assert_eq!(s.positions, [DVec3::new(1.0, 2.0, 3.0)]);
        assert_eq!(s.texcoords, [[0.25, 0.5]]);
        assert_eq!(s.normals, [DVec3::new(0.0, 0.0, 2.0)]);
    }
}
