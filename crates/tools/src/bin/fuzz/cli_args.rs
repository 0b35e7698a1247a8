//! The cases of the `cli` target: hostile command lines of the `facebem` binary (every
//! subcommand and option of `crates/cli/src/args.rs`, with hostile numbers and strings,
//! repeated, dropped and swapped arguments, outputs equal to inputs or onto folders, links and
//! FIFOs) and the files they name (the bundled face, its rig, mutated faces, rigs and muscle
//! files).

use facebem::FaceModel;
use facebem::expressions::{self, NameSet, presets};

use crate::mutate::{Rng, mutate_gltf, mutate_rig, mutate_text};

/// Where a case's input file comes from.
pub(crate) enum Content {
    /// A copy of the file of this name in the fuzz folder (`face.obj`, `face.rig`).
    Shared(&'static str),
    /// These bytes (a mutated input), saved with a finding.
    Bytes(Vec<u8>),
}

/// A file a case writes into its folder before running.
pub(crate) struct CaseFile {
    pub(crate) name: String,
    pub(crate) content: Content,
}

/// One command line and the files it reads.
pub(crate) struct CliCase {
    pub(crate) args: Vec<String>,
    pub(crate) files: Vec<CaseFile>,
}

impl CliCase {
    /// Whether an argument names one of the FIFOs (made only then: `mkfifo` is a process).
    pub(crate) fn wants_fifos(&self) -> bool {
        self.args.iter().any(|a| a.contains("fifo"))
    }
}

/// Folders made in every case's folder (outputs onto folders, into a subfolder).
pub(crate) const DIRS: [&str; 5] = ["sub", "dir.obj", "dir.rig", "dir.glb", "dir.muscles"];
/// Symbolic links made in every case's folder (link, target): outputs onto links, dangling
/// ones included.
pub(crate) const LINKS: [(&str, &str); 5] = [
    ("link.obj", "face.obj"),
    ("link.rig", "face.rig"),
    ("link.glb", "face.glb"),
    ("link.muscles", "missing.muscles"),
    ("link.png", "/dev/null"),
];
/// FIFOs made when an argument names one.
pub(crate) const FIFOS: [&str; 4] = ["fifo.obj", "fifo.rig", "fifo.glb", "fifo.muscles"];

/// What the cases are made from.
pub(crate) struct Corpus {
    pub(crate) face_obj: String,
    /// The face with `vt` and `vn` lines ([`crate::seeds::textured_obj`]).
    pub(crate) face_vt: String,
    pub(crate) muscles: String,
    pub(crate) gltf: Vec<Vec<u8>>,
    /// The faces and muscle files of `tests/bad_inputs/` (name, bytes).
    pub(crate) bad_faces: Vec<(String, Vec<u8>)>,
    pub(crate) bad_muscles: Vec<(String, Vec<u8>)>,
    pub(crate) rig_bytes: Vec<u8>,
    pub(crate) model: FaceModel,
    pub(crate) presets: Vec<String>,
}

impl Corpus {
    pub(crate) fn new(
        face_obj: String,
        gltf: Vec<Vec<u8>>,
        rig_bytes: Vec<u8>,
        model: FaceModel,
    ) -> Result<Corpus, String> {
        let muscles = facebem::face_prep::muscle_file::to_string(&model.rig.muscles)
            .map_err(|e| e.to_string())?;
        let mut names: Vec<String> = presets::names().iter().map(|s| s.to_string()).collect();
        for set in [NameSet::Arkit, NameSet::Vrm] {
            names.extend(expressions::of_set(set).iter().map(|e| e.name.to_string()));
        }
        Ok(Corpus {
            bad_faces: crate::seeds::bad_inputs(&["obj", "gltf", "glb"]),
            bad_muscles: crate::seeds::bad_inputs(&["muscles"]),
            face_vt: crate::seeds::textured_obj(&face_obj),
            face_obj,
            muscles,
            gltf,
            rig_bytes,
            model,
            presets: names,
        })
    }
}

/// Hostile numbers that parse as `f64`.
const FLOATS: &[&str] = &[
    "0",
    "-0",
    "1e-320",
    "-1e-320",
    "5e-324",
    "1e-300",
    "1e-9",
    "0.0004999",
    "0.0005",
    "0.001",
    "0.01",
    "0.05",
    "0.1",
    "0.2",
    "0.2000001",
    "0.45",
    "0.4999999",
    "0.49",
    "0.5",
    "0.51",
    "1",
    "2",
    "-1",
    "-0.5",
    "1e300",
    "1e308",
    "1.8e308",
    "inf",
    "-inf",
    "+inf",
    "infinity",
    "nan",
    "NaN",
    "+0.2",
];

/// Counts that parse as `usize`: around the face's own 852 triangles (836 simulated, about 426
/// in a mirrored half), the default 1500, and the integer limits.
const INTS: &[&str] = &[
    "0",
    "1",
    "2",
    "3",
    "4",
    "10",
    "99",
    "100",
    "101",
    "199",
    "200",
    "201",
    "425",
    "426",
    "427",
    "800",
    "835",
    "836",
    "837",
    "851",
    "852",
    "853",
    "1000",
    "1499",
    "1500",
    "1501",
    "5999",
    "6000",
    "6001",
    "65536",
    "100000",
    "1000000",
    "20000000",
    "4294967295",
    "4294967296",
    "9223372036854775807",
    "18446744073709551615",
    "+800",
];

/// Numbers that do not parse (as `f64` or as `usize`).
const NOT_NUMBERS: &[&str] = &[
    "",
    "x",
    "1,5",
    "0x10",
    "1e",
    "--1",
    " 0.1",
    "-1",
    "-800",
    "1e3",
    "800.0",
    "nan",
    "18446744073709551616",
];

fn pick<'a>(r: &mut Rng, list: &[&'a str]) -> &'a str {
    list[r.below(list.len())]
}

/// A uniform number in `[lo, hi)`.
fn uniform(r: &mut Rng, lo: f64, hi: f64) -> f64 {
    lo + (hi - lo) * (r.next() >> 11) as f64 / (1u64 << 53) as f64
}

/// A number in `[lo, hi)` (45%), a hostile one (45%) or none (10%).
fn float(r: &mut Rng, lo: f64, hi: f64) -> String {
    match r.below(20) {
        0..9 => format!("{}", uniform(r, lo, hi)),
        9..18 => pick(r, FLOATS).to_owned(),
        _ => pick(r, NOT_NUMBERS).to_owned(),
    }
}

/// A count in [100, 2000) (45%), a hostile one (45%) or none (10%).
fn int(r: &mut Rng) -> String {
    match r.below(20) {
        0..9 => (100 + r.below(1900)).to_string(),
        9..18 => pick(r, INTS).to_owned(),
        _ => pick(r, NOT_NUMBERS).to_owned(),
    }
}

/// Odd strings for any argument.
fn odd(r: &mut Rng) -> String {
    const ODD: &[&str] = &[
        "",
        " ",
        "-",
        "--",
        "-h",
        "--help",
        "=",
        "é",
        "名前",
        "a\nb",
        "a\rb",
        "\t",
        "%s%n",
        "../face.rig",
        "/dev/null",
        "/dev/zero",
        "/proc/self/mem",
        ".",
        "..",
        "--force",
        "-o",
        "face.rig",
        "face.obj",
        "\u{202e}x",
        "\u{7f}",
        "\u{1b}[31m",
        "--max-input-mb",
        "happy",
    ];
    if r.chance(20) {
        "x".repeat(1 + r.below(20_000))
    } else {
        pick(r, ODD).to_owned()
    }
}

/// An output path for a file of extension `ext`: usually `out.EXT`, sometimes a hostile one
/// (an input, a folder, a link, a FIFO, a missing folder, no extension, a device).
fn output(r: &mut Rng, ext: &str, input: &str) -> String {
    if !r.chance(6) {
        return format!("out.{ext}");
    }
    match r.below(16) {
        0 => input.to_owned(),
        1 => "face.rig".into(),
        2 => "face.obj".into(),
        3 => "sub".into(),
        4 => format!("sub/x.{ext}"),
        5 => format!("missing/x.{ext}"),
        6 => format!("link.{ext}"),
        7 => format!("fifo.{ext}"),
        8 => format!("dir.{ext}"),
        9 => "/dev/null".into(),
        10 => "out".into(),
        11 => format!("out.{ext}/"),
        12 => format!("{}.{ext}", "x".repeat(250 + r.below(20))),
        13 => format!("out.{}", ext.to_ascii_uppercase()),
        14 => format!("../out.{ext}"),
        _ => odd(r),
    }
}

/// The face or rig a case reads, and its file; `rig_kind` prefers the rig file.
fn input(r: &mut Rng, c: &Corpus, rig_kind: bool, files: &mut Vec<CaseFile>) -> String {
    let shared = |files: &mut Vec<CaseFile>, name: &'static str| {
        files.push(CaseFile {
            name: name.into(),
            content: Content::Shared(name),
        });
        name.to_owned()
    };
    let own = |files: &mut Vec<CaseFile>, name: &str, bytes: Vec<u8>| {
        files.push(CaseFile {
            name: name.into(),
            content: Content::Bytes(bytes),
        });
        name.to_owned()
    };
    // Rig kind: the rig 60%, a mutated OBJ 5%, a glTF 5%, a mutated rig 10%, the face 8%;
    // face kind: the face 50%, a mutated OBJ 15%, a glTF 10%, a mutated rig 5%, the rig 8%;
    // else an odd path.
    let bounds: [usize; 5] = if rig_kind {
        [60, 65, 70, 80, 88]
    } else {
        [50, 65, 75, 80, 88]
    };
    let roll = r.below(100);
    let kind = bounds.iter().position(|&b| roll < b);
    match kind {
        Some(0) if rig_kind => shared(files, "face.rig"),
        Some(0) => shared(files, "face.obj"),
        Some(1) if r.chance(4) && !c.bad_faces.is_empty() => {
            // A hostile file found earlier, as it is or mutated.
            let (name, bytes) = &c.bad_faces[r.below(c.bad_faces.len())];
            let ext = name.rsplit('.').next().unwrap_or("obj");
            let bytes = match (r.chance(3), ext) {
                (true, _) => bytes.clone(),
                (false, "obj") => mutate_text(r, &String::from_utf8_lossy(bytes)),
                (false, _) => mutate_gltf(r, bytes),
            };
            own(files, &format!("bad.{ext}"), bytes)
        }
        Some(1) => {
            let base = if r.chance(2) { &c.face_vt } else { &c.face_obj };
            let bytes = if r.chance(5) {
                base.clone().into_bytes()
            } else {
                mutate_text(r, base)
            };
            own(files, "mut.obj", bytes)
        }
        Some(2) => {
            let seed = c.gltf.get(r.below(c.gltf.len())).cloned();
            let seed = seed.unwrap_or_default();
            let bytes = if r.chance(3) {
                seed
            } else {
                mutate_gltf(r, &seed)
            };
            let name = if bytes.starts_with(b"glTF") {
                "face.glb"
            } else {
                "face.gltf"
            };
            own(files, name, bytes)
        }
        Some(3) => {
            let bytes = mutate_rig(r, &c.rig_bytes, &c.model);
            own(files, "mut.rig", bytes)
        }
        Some(4) if rig_kind => shared(files, "face.obj"),
        Some(4) => shared(files, "face.rig"),
        _ => match r.below(8) {
            0 => "missing.obj".into(),
            1 => "sub".into(),
            2 => "fifo.obj".into(),
            3 => "/dev/zero".into(),
            4 => own(files, "face.txt", c.face_obj.clone().into_bytes()),
            5 => own(files, "FACE.OBJ", c.face_obj.clone().into_bytes()),
            6 => own(files, "empty.obj", Vec::new()),
            _ => odd(r),
        },
    }
}

/// A random case.
pub(crate) fn generate(r: &mut Rng, c: &Corpus) -> CliCase {
    let mut files = Vec::new();
    let mut args: Vec<String> = Vec::new();
    let s = |x: &str| x.to_owned();
    match r.below(100) {
        0..30 => {
            let face = input(r, c, false, &mut files);
            args.extend([s("rig"), face.clone(), s("-o"), output(r, "rig", &face)]);
            rig_options(r, c, &mut args, &mut files);
        }
        30..50 => {
            let rig = input(r, c, true, &mut files);
            args.extend([s("pose"), rig.clone(), s("-o"), output(r, "obj", &rig)]);
            pose_options(r, c, &mut args);
        }
        50..70 => {
            let rig = input(r, c, true, &mut files);
            let ext = if r.chance(3) { "gltf" } else { "glb" };
            args.extend([s("export"), rig.clone(), s("--gltf"), output(r, ext, &rig)]);
            export_options(r, &mut args);
        }
        70..80 => {
            let rig_kind = r.chance(2);
            let file = input(r, c, rig_kind, &mut files);
            args.extend([s("info"), file]);
        }
        80..90 => {
            let rig_kind = r.chance(3);
            let face = input(r, c, rig_kind, &mut files);
            args.extend([
                s("muscles"),
                face.clone(),
                s("-o"),
                output(r, "muscles", &face),
            ]);
        }
        90..95 => {
            let rig = input(r, c, true, &mut files);
            args.extend([s("sheet"), rig.clone(), s("-o"), output(r, "png", &rig)]);
            if r.chance(2) {
                let only = ["muscles", "presets", "arkit", "vrm", "x"];
                args.extend([s("--only"), s(pick(r, &only))]);
            }
        }
        _ => {
            let junk = [
                "",
                "RIG",
                "help",
                "rig2",
                "--version",
                "-V",
                "--help",
                "pose",
            ];
            args.push(s(pick(r, &junk)));
        }
    }
    global_options(r, &mut args);
    mutate_args(r, &mut args);
    CliCase { args, files }
}

fn rig_options(r: &mut Rng, c: &Corpus, args: &mut Vec<String>, files: &mut Vec<CaseFile>) {
    let mut opt = |r: &mut Rng, name: &str, value: String| {
        args.push(name.to_owned());
        args.push(value);
        if r.chance(40) {
            args.push(name.to_owned());
            args.push(int(r));
        }
    };
    if r.chance(3) {
        let v = float(r, 0.0, 0.49);
        opt(r, "--poisson", v);
    }
    if r.chance(2) {
        let v = int(r);
        opt(r, "--max-triangles", v);
    }
    if r.chance(2) {
        let v = int(r);
        opt(r, "--target-triangles", v);
    }
    if r.chance(4) {
        let v = pick(r, &["collapse", "remesh", "remesh", "remesh", "Remesh"]).to_owned();
        opt(r, "--copy", v);
    }
    if r.chance(4) {
        let v = float(r, 0.0005, 0.2);
        opt(r, "--offset", v);
    }
    if r.chance(4) {
        let v = float(r, 0.0, 0.2);
        opt(r, "--thickness", v);
    }
    if r.chance(5) {
        let v = pick(r, &["mm", "cm", "m", "in", "auto", "mm", "cm", "km"]).to_owned();
        opt(r, "--units", v);
    }
    if r.chance(5) {
        let v = pick(r, &["anatomical", "thesis", "thesis", "x"]).to_owned();
        opt(r, "--muscle-model", v);
    }
    if r.chance(6) {
        args.push("--keep-rolled-in".into());
    }
    if r.chance(4) {
        args.push("--force".into());
    }
    if r.chance(6) {
        let text = match r.below(8) {
            0 | 1 => c.muscles.clone().into_bytes(),
            2 if !c.bad_muscles.is_empty() => c.bad_muscles[r.below(c.bad_muscles.len())].1.clone(),
            _ => mutate_text(r, &c.muscles),
        };
        files.push(CaseFile {
            name: "m.muscles".into(),
            content: Content::Bytes(text),
        });
        args.extend(["--muscles".into(), "m.muscles".into()]);
    }
}

fn pose_options(r: &mut Rng, c: &Corpus, args: &mut Vec<String>) {
    let ids = c.model.muscle_ids();
    for _ in 0..r.below(5) {
        let id = if r.chance(5) || ids.is_empty() {
            odd(r)
        } else {
            ids[r.below(ids.len())].clone()
        };
        let v = if r.chance(2) {
            format!("{}", uniform(r, -1.2, 1.2))
        } else {
            pick(r, FLOATS).to_owned()
        };
        let set = match r.below(8) {
            0 => id,
            1 => format!("={v}"),
            2 => format!("{id}=={v}"),
            3 => format!(" {id} = {v} "),
            _ => format!("{id}={v}"),
        };
        args.extend(["--set".into(), set]);
    }
    if r.chance(2) {
        let name = if r.chance(6) {
            pick(
                r,
                &["HAPPY", "happy ", "", "neutral,happy", "jawOpen\n", "x"],
            )
            .to_owned()
        } else {
            c.presets[r.below(c.presets.len())].clone()
        };
        args.extend(["--preset".into(), name]);
    }
    if r.chance(4) {
        args.push("--force".into());
    }
}

fn export_options(r: &mut Rng, args: &mut Vec<String>) {
    if r.chance(3) {
        args.push("--animation".into());
    }
    if r.chance(2) {
        let names = [
            "all",
            "arkit",
            "vrm",
            "facebem",
            "arkit,vrm",
            "vrm,arkit",
            "facebem,arkit",
            "all,all",
            "ALL",
            "arkit,,vrm",
            "none",
        ];
        args.extend(["--names".into(), pick(r, &names).to_owned()]);
    }
    if r.chance(4) {
        args.push("--force".into());
    }
}

/// The input limits, before or after the subcommand.
fn global_options(r: &mut Rng, args: &mut Vec<String>) {
    for name in ["--max-input-mb", "--max-input-triangles", "--max-muscles"] {
        if r.chance(16) {
            let v = int(r);
            let at = if r.chance(2) { 0 } else { args.len() };
            args.splice(at..at, [name.to_owned(), v]);
        }
    }
}

/// Repeats, drops, swaps or replaces arguments.
fn mutate_args(r: &mut Rng, args: &mut Vec<String>) {
    if !r.chance(8) || args.is_empty() {
        return;
    }
    for _ in 0..1 + r.below(2) {
        let n = args.len();
        let i = r.below(n);
        match r.below(6) {
            0 => {
                // Repeat an option with its value (or any two arguments) at the end.
                let piece: Vec<String> = args[i..(i + 2).min(n)].to_vec();
                args.extend(piece);
            }
            1 if n > 1 => {
                args.remove(i);
            }
            2 => {
                let j = r.below(n);
                args.swap(i, j);
            }
            3 => {
                let x = odd(r);
                args.insert(i, x);
            }
            4 => args[i] = odd(r),
            _ => {
                args.push("--".into());
                args.push(odd(r));
            }
        }
    }
}
