//! Muscle files in the thesis format (§7.6): blocks of `[Name]`, `[Size]`, `[Data]` with one
//! polygon (shell element) index per line.
//!
//! Each muscle is written as
//!
//! ```text
//! [Name]
//! Zygomaticus major L
//! [Size]
//! 3
//! [Data]
//! 120
//! 121
//! 133
//! [BackSize]
//! 2
//! [BackData]
//! 2950
//! 2951
//! ```
//!
//! `[Data]` is the front chain in order from start to end. The `[BackSize]`/`[BackData]` pair is
//! this project's extension for the back chain; it is optional when reading, so thesis files
//! (front chain only) load unchanged. Blank lines between blocks are ignored, and so is a UTF-8
//! byte order mark at the start. The name of a standard muscle (display name such as
//! "Frontalis L", or id such as `frontalis_l`) sets [`Muscle::kind`]; any other name gives a
//! custom muscle. The whole file is checked when read: names are unique ([`Muscle::id`]: two
//! names of one standard muscle are the same muscle) and writable, sizes match the lists, and
//! elements exist and appear once per chain.
//!
//! ```
//! use face_prep::{Muscle, muscle_file};
//! let m = vec![Muscle { name: "Frontalis L".into(), kind: None, front_chain: vec![4, 2], back_chain: vec![] }];
//! let text = muscle_file::to_string(&m).unwrap();
//! let back = muscle_file::read_str(&text, 10).unwrap();
//! assert_eq!(back[0].front_chain, vec![4, 2]);
//! assert_eq!(back[0].kind, Some(face_prep::MuscleKind::FrontalisL));
//! ```

use crate::controls::muscle_kind::MuscleKind;
use crate::controls::muscles::Muscle;
use crate::error::MuscleFileError;
use std::collections::{HashMap, HashSet};
use std::io::{Read, Write};
use std::path::Path;

/// The standard muscle a name denotes (display name or id, case-insensitive).
pub(crate) fn kind_from_name(name: &str) -> Option<MuscleKind> {
    let n = name.trim();
    MuscleKind::ALL
        .into_iter()
        .find(|k| k.display_name().eq_ignore_ascii_case(n))
        .or_else(|| MuscleKind::from_id(n))
}

struct Lines<'a> {
    lines: Vec<(usize, &'a str)>,
    pos: usize,
}

impl<'a> Lines<'a> {
    fn new(text: &'a str) -> Lines<'a> {
        Lines {
            lines: text
                .lines()
                .enumerate()
                .map(|(i, l)| (i + 1, l.trim()))
                .collect(),
            pos: 0,
        }
    }
    /// Next line, skipping blank ones between blocks.
    fn next_nonblank(&mut self) -> Option<(usize, &'a str)> {
        while let Some(&(n, l)) = self.lines.get(self.pos) {
            self.pos += 1;
            if !l.is_empty() {
                return Some((n, l));
            }
        }
        None
    }
    fn peek_nonblank(&self) -> Option<(usize, &'a str)> {
        self.lines[self.pos.min(self.lines.len())..]
            .iter()
            .find(|(_, l)| !l.is_empty())
            .copied()
    }
    fn last_line(&self) -> usize {
        self.lines.last().map(|l| l.0).unwrap_or(0)
    }
}

fn expect_header(
    lines: &mut Lines,
    header: &'static str,
    muscle: &str,
    missing: &'static str,
) -> Result<(), MuscleFileError> {
    match lines.next_nonblank() {
        Some((_, l)) if l.eq_ignore_ascii_case(header) => Ok(()),
        Some((line, l)) => Err(MuscleFileError::Unexpected {
            line,
            text: l.to_owned(),
            expected: missing,
        }),
        None => Err(MuscleFileError::Truncated {
            line: lines.last_line(),
            muscle: muscle.to_owned(),
            missing,
        }),
    }
}

/// Whether [`to_string`] can write `name` (and read it back unchanged): not empty, no leading
/// or trailing whitespace, no line break, not starting with `[`.
fn writable_name(name: &str) -> bool {
    !name.is_empty()
        && !name.starts_with('[')
        && !name.contains(['\n', '\r'])
        && name.trim() == name
}

/// Reads the name after a `[Name]` header (a writable one, [`writable_name`]).
fn read_name(lines: &mut Lines) -> Result<(usize, String), MuscleFileError> {
    match lines.next_nonblank() {
        Some((line, n)) if !writable_name(n) => Err(MuscleFileError::Unexpected {
            line,
            text: n.to_owned(),
            expected: "a muscle name (on one line, not starting with '[')",
        }),
        Some((line, n)) => Ok((line, n.to_owned())),
        None => Err(MuscleFileError::Truncated {
            line: lines.last_line(),
            muscle: String::new(),
            missing: "the name",
        }),
    }
}

fn number(line: usize, text: &str) -> Result<u32, MuscleFileError> {
    text.parse::<u32>().map_err(|_| MuscleFileError::BadNumber {
        line,
        text: text.to_owned(),
    })
}

/// Reads a chain: `[<size_header>] n [<data_header>] n indices`.
fn read_chain(
    lines: &mut Lines,
    muscle: &str,
    data_header: &'static str,
    element_count: usize,
) -> Result<Vec<u32>, MuscleFileError> {
    let declared = match lines.next_nonblank() {
        Some((line, l)) => number(line, l)? as usize,
        None => {
            return Err(MuscleFileError::Truncated {
                line: lines.last_line(),
                muscle: muscle.to_owned(),
                missing: "the size value",
            });
        }
    };
    expect_header(lines, data_header, muscle, data_header)?;
    // No capacity from the declared size: a file may declare 4294967295 and list nothing.
    let mut chain = Vec::new();
    let mut seen = HashSet::new();
    loop {
        match lines.peek_nonblank() {
            Some((line, l)) if !l.starts_with('[') => {
                lines.next_nonblank();
                let index = number(line, l)?;
                if chain.len() >= declared {
                    // Count the surplus for the message.
                    let mut found = chain.len() + 1;
                    while let Some((_, l)) = lines.peek_nonblank() {
                        if l.starts_with('[') {
                            break;
                        }
                        lines.next_nonblank();
                        found += 1;
                    }
                    return Err(MuscleFileError::SizeMismatch {
                        line,
                        muscle: muscle.to_owned(),
                        declared,
                        found,
                    });
                }
                if index as usize >= element_count {
                    return Err(MuscleFileError::IndexOutOfRange {
                        line,
                        muscle: muscle.to_owned(),
                        index,
                        element_count,
                    });
                }
                if !seen.insert(index) {
                    return Err(MuscleFileError::DuplicateElement {
                        line,
                        muscle: muscle.to_owned(),
                        index,
                    });
                }
                chain.push(index);
            }
            other => {
                if chain.len() != declared {
                    return Err(MuscleFileError::SizeMismatch {
                        line: other.map(|o| o.0).unwrap_or_else(|| lines.last_line()),
                        muscle: muscle.to_owned(),
                        declared,
                        found: chain.len(),
                    });
                }
                return Ok(chain);
            }
        }
    }
}

/// Parses a muscle file; every index must be below `element_count` (the shell's element count).
/// At most [`crate::InputLimits::max_muscles`] muscles of the default limits; see
/// [`ReadOptions`] for others.
pub fn read_str(text: &str, element_count: usize) -> Result<Vec<Muscle>, MuscleFileError> {
    ReadOptions::new(element_count).read_str(text)
}

/// How a muscle file is read: the shell's element count every index must be below, and the
/// input limits (file bytes, muscle count; the chains are bounded by `element_count`, since an
/// element may appear once per chain). [`read_str`], [`read`] and [`load`] use the default
/// limits.
///
/// ```
/// use face_prep::{InputLimits, muscle_file::{self, ReadOptions}};
/// let text = "[Name]\nA\n[Size]\n1\n[Data]\n0\n[Name]\nB\n[Size]\n1\n[Data]\n1\n";
/// let one = ReadOptions {
///     limits: InputLimits { max_muscles: 1, ..InputLimits::default() },
///     ..ReadOptions::new(2)
/// };
/// let err = one.read_str(text).unwrap_err();
/// assert!(err.to_string().contains("more than 1 muscles"), "{err}");
/// assert_eq!(muscle_file::read_str(text, 2).unwrap().len(), 2);
/// ```
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ReadOptions {
    /// The shell's element count: every index must be below it.
    pub element_count: usize,
    /// File size and muscle count limits.
    pub limits: crate::InputLimits,
}

impl ReadOptions {
    /// Options for a shell of `element_count` elements, under the default limits.
    pub fn new(element_count: usize) -> ReadOptions {
        ReadOptions {
            element_count,
            limits: crate::InputLimits::default(),
        }
    }

    /// Parses a muscle file's text.
    pub fn read_str(&self, text: &str) -> Result<Vec<Muscle>, MuscleFileError> {
        parse(text, self.element_count, &self.limits)
    }

    /// Reads a muscle file from a reader (at most `limits.max_file_bytes` bytes).
    pub fn read(&self, reader: impl Read) -> Result<Vec<Muscle>, MuscleFileError> {
        let limit = self.limits.max_file_bytes;
        let mut text = String::new();
        reader
            .take(limit.saturating_add(1))
            .read_to_string(&mut text)?;
        if text.len() as u64 > limit {
            return Err(MuscleFileError::Io(std::io::Error::other(format!(
                "muscle file larger than the input limit of {limit} bytes"
            ))));
        }
        self.read_str(&text)
    }

    /// Reads a muscle file from disk: a regular file only (a FIFO or device is refused
    /// unopened), its size checked against `limits.max_file_bytes` before reading.
    pub fn load(&self, path: &Path) -> Result<Vec<Muscle>, MuscleFileError> {
        let meta = std::fs::metadata(path)?;
        if !meta.is_file() {
            return Err(MuscleFileError::Io(std::io::Error::other(format!(
                "{} is not a regular file",
                path.display()
            ))));
        }
        if meta.len() > self.limits.max_file_bytes {
            return Err(MuscleFileError::Io(std::io::Error::other(format!(
                "{} is {} bytes, above the input limit of {} bytes",
                path.display(),
                meta.len(),
                self.limits.max_file_bytes
            ))));
        }
        self.read(std::fs::File::open(path)?)
    }
}

fn parse(
    text: &str,
    element_count: usize,
    limits: &crate::InputLimits,
) -> Result<Vec<Muscle>, MuscleFileError> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let mut lines = Lines::new(text);
    let mut muscles = Vec::new();
    // Line of the name of the muscle of each id read so far.
    let mut first_line: HashMap<String, usize> = HashMap::new();
    let max_muscles = limits.max_muscles;
    while let Some((line, l)) = lines.next_nonblank() {
        if muscles.len() >= max_muscles {
            return Err(MuscleFileError::TooManyMuscles {
                line,
                limit: max_muscles,
            });
        }
        if !l.eq_ignore_ascii_case("[Name]") {
            return Err(MuscleFileError::Unexpected {
                line,
                text: l.to_owned(),
                expected: "[Name]",
            });
        }
        let (name_line, name) = read_name(&mut lines)?;
        let kind = kind_from_name(&name);
        // `Muscle::id` of the muscle being read.
        let id = kind.map_or_else(|| name.clone(), |k| k.id().to_owned());
        if let Some(&first) = first_line.get(&id) {
            return Err(MuscleFileError::DuplicateName {
                line: name_line,
                name,
                id,
                first_line: first,
            });
        }
        first_line.insert(id, name_line);
        expect_header(&mut lines, "[Size]", &name, "[Size]")?;
        let front_chain = read_chain(&mut lines, &name, "[Data]", element_count)?;
        let back_chain = match lines.peek_nonblank() {
            Some((_, l)) if l.eq_ignore_ascii_case("[BackSize]") => {
                lines.next_nonblank();
                read_chain(&mut lines, &name, "[BackData]", element_count)?
            }
            _ => Vec::new(),
        };
        muscles.push(Muscle {
            kind,
            name,
            front_chain,
            back_chain,
        });
    }
    Ok(muscles)
}

/// Like [`read_str`], from a reader (at most [`crate::InputLimits::max_file_bytes`] bytes).
pub fn read(reader: impl Read, element_count: usize) -> Result<Vec<Muscle>, MuscleFileError> {
    ReadOptions::new(element_count).read(reader)
}

/// Formats muscles in the file format (back chain blocks only for muscles that have one).
pub fn to_string(muscles: &[Muscle]) -> Result<String, MuscleFileError> {
    use std::fmt::Write as _;
    let mut s = String::new();
    for m in muscles {
        let name = m.name.as_str();
        if !writable_name(name) {
            return Err(MuscleFileError::BadName(m.name.clone()));
        }
        let _ = writeln!(s, "[Name]\n{name}\n[Size]\n{}\n[Data]", m.front_chain.len());
        for e in &m.front_chain {
            let _ = writeln!(s, "{e}");
        }
        if !m.back_chain.is_empty() {
            let _ = writeln!(s, "[BackSize]\n{}\n[BackData]", m.back_chain.len());
            for e in &m.back_chain {
                let _ = writeln!(s, "{e}");
            }
        }
    }
    Ok(s)
}

/// Writes muscles to a writer.
pub fn write(mut writer: impl Write, muscles: &[Muscle]) -> Result<(), MuscleFileError> {
    writer.write_all(to_string(muscles)?.as_bytes())?;
    Ok(())
}

/// Writes a muscle file atomically ([`crate::atomic_write::write_atomic`]: temporary file in
/// the same folder, then rename; the existing file's mode is kept; a symlink or device at
/// `path` is refused).
pub fn save(path: &Path, muscles: &[Muscle]) -> Result<(), MuscleFileError> {
    let text = to_string(muscles)?;
    crate::atomic_write::write_atomic(path, text.as_bytes())
        .map_err(|e| MuscleFileError::Io(std::io::Error::other(e.to_string())))
}

/// Reads a muscle file from disk (a regular file only: a FIFO or device is refused unopened),
/// under the default limits; see [`ReadOptions`] for others.
pub fn load(path: &Path, element_count: usize) -> Result<Vec<Muscle>, MuscleFileError> {
    ReadOptions::new(element_count).load(path)
}
