//! Wavefront OBJ export of a pose.
//!
//! When the face came from an OBJ file, the pose is written by re-emitting the original text with
//! only the `v` lines' coordinates replaced: vertex order, `vt`/`vn` lines, faces, groups,
//! materials and comments stay exactly as the user wrote them. Otherwise a plain OBJ is written
//! from the welded vertices and triangles.
//!
//! Neither writer emits a NaN or an infinity: a non-finite posed position, or a non-finite
//! number in a template's `v`, `vt` or `vn` line, is an [`ObjExportError::NonFinite`].

use face_prep::obj_text::{is_vertex_line, non_finite_word};
use glam::DVec3;

/// Errors from OBJ export.
#[derive(Debug, thiserror::Error)]
#[non_exhaustive]
pub enum ObjExportError {
    /// The template OBJ has a different number of `v` lines than the input map expects.
    #[error("the original OBJ has {found} `v` lines but the face was loaded from {expected}")]
    VertexLineCount {
        /// Number of input positions the face mesh was loaded from.
        expected: usize,
        /// Number of `v` lines found in the template.
        found: usize,
    },
    /// An input position maps to a vertex outside the posed positions.
    #[error("`v` line {line} maps to vertex {vertex}, but the pose has only {count} vertices")]
    VertexOutOfRange {
        /// 1-based line number in the template.
        line: usize,
        /// The welded vertex index it maps to.
        vertex: usize,
        /// Number of posed positions.
        count: usize,
    },
    /// A number to write is NaN or infinite (a posed position, or a number of the template's
    /// `v`, `vt` or `vn` line `line`).
    #[error("line {line} of the OBJ would hold a number that is not finite ({what})")]
    NonFinite {
        /// 1-based line number in the output.
        line: usize,
        /// What is not finite (`posed vertex 12`, `"nan"`).
        what: String,
    },
    /// A `v` line has fewer than three coordinates.
    #[error("`v` line {line} has fewer than three coordinates")]
    MalformedVertexLine {
        /// 1-based line number in the template.
        line: usize,
    },
}

/// Re-emits `template` (the original OBJ text) with every `v` line's x y z replaced by the
/// posed position of the welded vertex it maps to.
///
/// `input_to_vertex[k]` is the welded vertex of the k-th `v` line, or `None` for an input
/// position that was dropped (unused); such lines are kept unchanged. Extra tokens after x y z
/// (a `w` or vertex colours) are kept.
///
/// ```
/// use facebem::export::obj::pose_from_template;
/// use glam::DVec3;
/// let obj = "# tri\nv 0 0 0\nv 1 0 0\nvt 0.5 0.5\nv 0 1 0 0.2 0.3 0.4\nf 1/1 2/1 3/1\n";
/// let posed = [DVec3::new(0.0, 0.0, 1.0), DVec3::X, DVec3::Y];
/// let out = pose_from_template(obj, &[Some(0), Some(1), Some(2)], &posed).unwrap();
/// assert_eq!(out, "# tri\nv 0 0 1\nv 1 0 0\nvt 0.5 0.5\nv 0 1 0 0.2 0.3 0.4\nf 1/1 2/1 3/1\n");
/// ```
pub fn pose_from_template(
    template: &str,
    input_to_vertex: &[Option<u32>],
    positions: &[DVec3],
) -> Result<String, ObjExportError> {
    let found = template.lines().filter(|l| is_vertex_line(l)).count();
    if found != input_to_vertex.len() {
        return Err(ObjExportError::VertexLineCount {
            expected: input_to_vertex.len(),
            found,
        });
    }
    let mut out = String::with_capacity(template.len() + template.len() / 4);
    let mut k = 0;
    for (line_index, raw) in template.split_inclusive('\n').enumerate() {
        let line = raw.trim_end_matches(['\n', '\r']);
        let ending = &raw[line.len()..];
        let trimmed = line.trim_start();
        if matches!(trimmed.split_whitespace().next(), Some("v" | "vt" | "vn"))
            && let Some(word) = non_finite_word(trimmed)
        {
            return Err(ObjExportError::NonFinite {
                line: line_index + 1,
                what: format!("{word:?}"),
            });
        }
        if !is_vertex_line(trimmed) {
            out.push_str(raw);
            continue;
        }
        let target = input_to_vertex[k];
        k += 1;
        let Some(vertex) = target else {
            out.push_str(raw);
            continue;
        };
        let vertex = vertex as usize;
        let p = positions
            .get(vertex)
            .ok_or(ObjExportError::VertexOutOfRange {
                line: line_index + 1,
                vertex,
                count: positions.len(),
            })?;
        let tokens: Vec<&str> = trimmed.split_whitespace().collect();
        if tokens.len() < 4 {
            return Err(ObjExportError::MalformedVertexLine {
                line: line_index + 1,
            });
        }
        if !p.is_finite() {
            return Err(ObjExportError::NonFinite {
                line: line_index + 1,
                what: format!("posed vertex {vertex}"),
            });
        }
        out.push_str(&format!("v {} {} {}", p.x, p.y, p.z));
        for extra in &tokens[4..] {
            out.push(' ');
            out.push_str(extra);
        }
        out.push_str(ending);
    }
    Ok(out)
}

/// Writes a plain OBJ (`v` and `f` lines, 1-based) of `positions` and `triangles`; a
/// non-finite position is an error.
///
/// ```
/// use facebem::export::obj::plain_obj;
/// use glam::DVec3;
/// let s = plain_obj(&[DVec3::ZERO, DVec3::X, DVec3::Y], &[[0, 1, 2]]).unwrap();
/// assert!(s.ends_with("v 0 1 0\nf 1 2 3\n"));
/// assert!(plain_obj(&[DVec3::NAN], &[]).is_err());
/// ```
pub fn plain_obj(positions: &[DVec3], triangles: &[[u32; 3]]) -> Result<String, ObjExportError> {
    let mut out = String::from("# written by facebem\n");
    for (vertex, p) in positions.iter().enumerate() {
        if !p.is_finite() {
            return Err(ObjExportError::NonFinite {
                line: vertex + 2,
                what: format!("posed vertex {vertex}"),
            });
        }
        out.push_str(&format!("v {} {} {}\n", p.x, p.y, p.z));
    }
    for t in triangles {
        out.push_str(&format!("f {} {} {}\n", t[0] + 1, t[1] + 1, t[2] + 1));
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn keeps_crlf_comments_and_dropped_vertices() {
        let obj = "v 0 0 0\r\nv 9 9 9\r\n# c\r\nv 1 0 0\r\nf 1 3 1\r\n";
        let posed = [DVec3::new(0.5, 0.0, 0.0), DVec3::new(2.0, 0.0, 0.0)];
        let out = pose_from_template(obj, &[Some(0), None, Some(1)], &posed).unwrap();
        assert_eq!(out, "v 0.5 0 0\r\nv 9 9 9\r\n# c\r\nv 2 0 0\r\nf 1 3 1\r\n");
    }

    #[test]
    fn mismatched_templates_are_rejected() {
        let err = pose_from_template("v 0 0 0\n", &[Some(0), Some(1)], &[DVec3::ZERO]);
        assert!(matches!(
            err,
            Err(ObjExportError::VertexLineCount {
                expected: 2,
                found: 1
            })
        ));
        let err = pose_from_template("v 0 0 0\n", &[Some(3)], &[DVec3::ZERO]);
        assert!(matches!(
            err,
            Err(ObjExportError::VertexOutOfRange { line: 1, .. })
        ));
        let err = pose_from_template("v 0 0\n", &[Some(0)], &[DVec3::ZERO]);
        assert!(matches!(
            err,
            Err(ObjExportError::MalformedVertexLine { line: 1 })
        ));
    }

    #[test]
    fn pose_writer_refuses_to_write_non_finite_numbers() {
        let obj = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n";
        let map = [Some(0), Some(1), Some(2)];
        let posed = [DVec3::ZERO, DVec3::new(f64::INFINITY, 0.0, 0.0), DVec3::Y];
        let err = pose_from_template(obj, &map, &posed).unwrap_err();
        assert!(
            matches!(&err, ObjExportError::NonFinite { line: 2, what } if what == "posed vertex 1"),
            "{err}"
        );
        let good = [DVec3::ZERO, DVec3::X, DVec3::Y];
        for bad in ["vt nan 0", "vn inf 0 1", "v 0 0 0 inf", "v 0 0 0 1 NaN 1"] {
            let template = format!("{obj}{bad}\n");
            let map = if bad.starts_with("v ") {
                &[Some(0), Some(1), Some(2), None][..]
            } else {
                &map[..]
            };
            let err = pose_from_template(&template, map, &good).unwrap_err();
            assert!(
                matches!(err, ObjExportError::NonFinite { line: 5, .. }),
                "{bad}: {err}"
            );
        }
        let err = plain_obj(&[DVec3::ZERO, DVec3::new(0.0, f64::NAN, 0.0)], &[]).unwrap_err();
        assert!(
            matches!(err, ObjExportError::NonFinite { line: 3, .. }),
            "{err}"
        );
    }

    #[test]
    fn positions_round_trip_exactly_through_text() {
        let p = DVec3::new(0.1 + 0.2, -1.0 / 3.0, 1e-17);
        let out = plain_obj(&[p], &[]).unwrap();
        let line = out.lines().nth(1).unwrap();
        let xyz: Vec<f64> = line[2..].split(' ').map(|t| t.parse().unwrap()).collect();
        assert_eq!(DVec3::new(xyz[0], xyz[1], xyz[2]), p);
    }
}
