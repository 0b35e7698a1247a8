//! The `cli` target: runs the release `facebem` binary on hostile command lines
//! ([`crate::cli_args`]), each in a fresh folder under `DIR/work`, as a subprocess with a CPU
//! and a wall-clock limit and an address-space limit (`ulimit -v`).
//!
//! Exit status 0, 1 and 2 are answers; a signal (abort, segfault, memory limit) or another
//! status is a crash, 101 a panic, a run over `--case-seconds` of CPU or `--hang-seconds` of
//! wall-clock time is killed (timeout), one over `--slow-seconds` of CPU is slow. Status 1 must
//! print exactly one `error:` line on standard error, after any `warning:` lines. After status
//! 0 every file written is checked ([`crate::output_check`]) and standard output must not
//! print a non-finite number. A finding is saved as `DIR/KIND-HASH/` with `repro.sh` (which
//! rebuilds the case's folder from the saved inputs and `DIR/face.obj`, `DIR/face.rig`),
//! `note.txt`, and the run's `stdout.txt` and `stderr.txt`. With `FUZZ_TRACE` set in the
//! environment, every run's command line, status and standard error are printed.

use std::collections::HashMap;
use std::os::unix::process::ExitStatusExt;
use std::path::{Path, PathBuf};
use std::process::{Command, ExitStatus, Stdio};
use std::time::{Duration, Instant};

use facebem::cache;
use facebem::face_prep::FaceMesh;

use crate::cli_args::{CliCase, Content, Corpus, DIRS, FIFOS, LINKS, generate};
use crate::mutate::Rng;
use crate::opts::{Clock, Opts, process_cpu_seconds};
use crate::output_check::{check_dir, non_finite_words};
use crate::seeds::{face_path, gltf_seeds};
use crate::stats::Stats;

/// Findings saved per kind and worker run (the rest are counted only).
const MAX_SAVED: usize = 25;

/// The `facebem` binary: `--facebem`, else the one next to this program.
pub(crate) fn facebem_exe(o: &Opts) -> Result<PathBuf, String> {
    let exe = match &o.facebem {
        Some(p) => p.clone(),
        None => {
            let me = std::env::current_exe().map_err(|e| e.to_string())?;
            me.with_file_name("facebem")
        }
    };
    if !exe.is_file() {
        return Err(format!(
            "no facebem binary at {} (build it first: cargo build --release -p facebem-cli, \
             or give --facebem PATH)",
            exe.display()
        ));
    }
    std::path::absolute(&exe).map_err(|e| e.to_string())
}

/// Writes `DIR/face.obj` (the bundled face) and `DIR/face.rig` (its rig, made once by
/// `facebem rig`).
pub(crate) fn prepare(o: &Opts) -> Result<(), String> {
    let exe = facebem_exe(o)?;
    std::fs::create_dir_all(o.out.join("work")).map_err(|e| e.to_string())?;
    let face = o.out.join("face.obj");
    std::fs::copy(face_path(), &face).map_err(|e| e.to_string())?;
    eprintln!(
        "fuzz: making the rig {} …",
        o.out.join("face.rig").display()
    );
    let out = Command::new(&exe)
        .arg("rig")
        .arg(&face)
        .arg("-o")
        .arg(o.out.join("face.rig"))
        .stdin(Stdio::null())
        .output()
        .map_err(|e| format!("{}: {e}", exe.display()))?;
    if !out.status.success() {
        return Err(format!(
            "facebem rig of the bundled face failed ({}): {}",
            out.status,
            String::from_utf8_lossy(&out.stderr).trim()
        ));
    }
    Ok(())
}

fn corpus(o: &Opts) -> Result<Corpus, String> {
    let err = |e: &dyn std::fmt::Display| e.to_string();
    let face_obj = std::fs::read_to_string(o.out.join("face.obj")).map_err(|e| err(&e))?;
    let rig_bytes = std::fs::read(o.out.join("face.rig")).map_err(|e| err(&e))?;
    let model = cache::from_bytes(Path::new("face.rig"), &rig_bytes).map_err(|e| err(&e))?;
    let face = FaceMesh::from_obj_str(&face_obj).map_err(|e| err(&e))?;
    let (glb, data, _, _) = gltf_seeds(&face);
    Corpus::new(face_obj, vec![glb, data.into_bytes()], rig_bytes, model)
}

/// How a run ended.
struct Run {
    status: ExitStatus,
    /// `Some(why)` when it was killed at a limit.
    killed: Option<String>,
    cpu: f64,
    wall: f64,
    stdout: String,
    stderr: String,
}

pub(crate) fn worker(o: &Opts) -> Result<(), String> {
    let exe = facebem_exe(o)?;
    let corpus = corpus(o)?;
    // The budget is this process's CPU time plus that of the runs it waited for.
    let (own, runs) = (Clock::start(true), Clock::start(false));
    let budget_s = o.minutes * 60.0;
    let mut r = Rng(o.seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
    let mut stats = Stats::default();
    let mut saved: HashMap<&'static str, usize> = HashMap::new();
    while own.cpu() + runs.cpu() < budget_s {
        let case = generate(&mut r, &corpus);
        let repro = repro_script(o, &exe, &case, stats.cases);
        let _ = std::fs::write(o.out.join("inflight.cli"), &repro);
        let dir = tempfile::Builder::new()
            .prefix("case-")
            .tempdir_in(o.out.join("work"))
            .map_err(|e| e.to_string())?;
        let inputs = setup(dir.path(), &case, &corpus)?;
        let run = run(o, &exe, dir.path(), &case.args)?;
        stats.cases += 1;
        if std::env::var_os("FUZZ_TRACE").is_some() {
            let (status, args) = (run.status, shown_args(&case.args));
            eprintln!("trace: {status}, {:.2} s CPU: facebem {args}", run.cpu);
            eprintln!("trace: stderr: {:.300}", run.stderr.trim_end());
        }
        stats.max_ms = stats.max_ms.max(run.cpu * 1e3);
        stats.max_wall_ms = stats.max_wall_ms.max(run.wall * 1e3);
        let input_refs: Vec<(&str, &[u8])> = inputs
            .iter()
            .map(|(n, b)| (n.as_str(), b.as_slice()))
            .collect();
        for (kind, note) in classify(o, &run, dir.path(), &input_refs, &mut stats) {
            let n = saved.entry(kind).or_default();
            *n += 1;
            let at = if *n <= MAX_SAVED {
                save(o, kind, &note, &case, &repro, &run)
            } else {
                "(not saved: enough of this kind)".into()
            };
            eprintln!(
                "fuzz cli: {kind}: {} {at}\n  facebem {}",
                note.lines().next().unwrap_or(""),
                shown_args(&case.args)
            );
        }
        if stats.cases.is_multiple_of(20) {
            stats.print();
        }
    }
    let _ = std::fs::remove_file(o.out.join("inflight.cli"));
    stats.print();
    Ok(())
}

/// Writes the case's files into `ROOT/run` (the run's working folder) with the folders, links
/// and FIFOs arguments may name; returns the inputs as `run/NAME` and bytes.
fn setup(root: &Path, case: &CliCase, c: &Corpus) -> Result<Vec<(String, Vec<u8>)>, String> {
    let err = |e: std::io::Error| e.to_string();
    let run = root.join("run");
    std::fs::create_dir(&run).map_err(err)?;
    let mut inputs = Vec::new();
    for f in &case.files {
        let bytes = match &f.content {
            Content::Shared("face.rig") => c.rig_bytes.clone(),
            Content::Shared(_) => c.face_obj.clone().into_bytes(),
            Content::Bytes(b) => b.clone(),
        };
        std::fs::write(run.join(&f.name), &bytes).map_err(err)?;
        inputs.push((format!("run/{}", f.name), bytes));
    }
    for d in DIRS {
        std::fs::create_dir_all(run.join(d)).map_err(err)?;
    }
    for (link, target) in LINKS {
        std::os::unix::fs::symlink(target, run.join(link)).map_err(err)?;
    }
    if case.wants_fifos() {
        let _ = Command::new("mkfifo")
            .args(FIFOS)
            .current_dir(&run)
            .status();
    }
    Ok(inputs)
}

/// Runs `facebem ARGS` in `ROOT/run` under the limits, its output in `ROOT/std{out,err}.txt`.
fn run(o: &Opts, exe: &Path, root: &Path, args: &[String]) -> Result<Run, String> {
    let err = |e: std::io::Error| e.to_string();
    let stdout = std::fs::File::create(root.join("stdout.txt")).map_err(err)?;
    let stderr = std::fs::File::create(root.join("stderr.txt")).map_err(err)?;
    let runs = Clock::start(false);
    let wall = Instant::now();
    let mut child = Command::new("sh")
        .arg("-c")
        .arg(format!("ulimit -v {}; exec \"$0\" \"$@\"", o.case_mb << 10))
        .arg(exe)
        .args(args)
        .current_dir(root.join("run"))
        // The rig cache of faces the cases compute: the run's own, not the user's.
        .env("XDG_CACHE_HOME", o.out.join("cache"))
        .stdin(Stdio::null())
        .stdout(stdout)
        .stderr(stderr)
        .spawn()
        .map_err(err)?;
    let mut nap = Duration::from_millis(1);
    let mut killed = None;
    let status = loop {
        if let Some(status) = child.try_wait().map_err(err)? {
            break status;
        }
        let cpu = process_cpu_seconds(child.id()).unwrap_or(0.0);
        let w = wall.elapsed().as_secs_f64();
        if cpu > o.case_seconds || w > o.hang_seconds {
            killed = Some(format!(
                "killed at {cpu:.1} s CPU, {w:.1} s wall (limits {} s CPU, {} s wall)",
                o.case_seconds, o.hang_seconds
            ));
            let _ = child.kill();
            break child.wait().map_err(err)?;
        }
        std::thread::sleep(nap);
        nap = (nap * 2).min(Duration::from_millis(50));
    };
    let read = |name: &str| {
        let b = std::fs::read(root.join(name)).unwrap_or_default();
        String::from_utf8_lossy(&b).into_owned()
    };
    Ok(Run {
        status,
        killed,
        cpu: runs.cpu(),
        wall: wall.elapsed().as_secs_f64(),
        stdout: read("stdout.txt"),
        stderr: read("stderr.txt"),
    })
}

/// Whether standard error is one `error:` line after any number of `warning:` lines.
fn one_error_line(stderr: &str) -> bool {
    let lines: Vec<&str> = stderr.lines().collect();
    match lines.split_last() {
        Some((last, rest)) => {
            last.starts_with("error: ") && rest.iter().all(|l| l.starts_with("warning:"))
        }
        None => false,
    }
}

/// The findings of a run (kind, note), counted into `stats`.
fn classify(
    o: &Opts,
    run: &Run,
    root: &Path,
    inputs: &[(&str, &[u8])],
    stats: &mut Stats,
) -> Vec<(&'static str, String)> {
    let mut found = Vec::new();
    let timing = format!("{:.2} s CPU, {:.2} s wall", run.cpu, run.wall);
    let tail = |s: &str| {
        let lines: Vec<&str> = s.lines().collect();
        lines[lines.len().saturating_sub(3)..].join("\n")
    };
    if let Some(why) = &run.killed {
        stats.timeouts += 1;
        found.push(("timeout", why.clone()));
        return found;
    }
    if run.cpu > o.slow_seconds {
        stats.slow += 1;
        found.push((
            "slow",
            format!("over {} s of CPU: {timing}", o.slow_seconds),
        ));
    }
    match (run.status.signal(), run.status.code()) {
        (Some(sig), _) => {
            stats.aborts += 1;
            let what = match sig {
                6 => " (abort)",
                9 => " (kill: memory?)",
                11 => " (segmentation fault)",
                _ => "",
            };
            let note = format!("signal {sig}{what}, {timing}\n{}", tail(&run.stderr));
            found.push(("crash", note));
        }
        (None, Some(0)) => {
            let mut problems = check_dir(root, inputs);
            let words = non_finite_words(&run.stdout);
            if !words.is_empty() {
                problems.push(format!("standard output prints {}", words.join(" ")));
            }
            if !problems.is_empty() {
                stats.nonfinite += 1;
                found.push(("nonfinite", problems.join("\n")));
            }
        }
        (None, Some(1)) if !one_error_line(&run.stderr) => {
            stats.multiline += 1;
            let note = format!("multi-line error:\n{}", run.stderr.trim_end());
            found.push(("multiline", note));
        }
        (None, Some(1 | 2)) => {}
        (None, Some(101)) => {
            stats.panics += 1;
            found.push((
                "panic",
                format!("exit 101, {timing}\n{}", tail(&run.stderr)),
            ));
        }
        (None, code) => {
            stats.aborts += 1;
            let note = format!("exit status {code:?}, {timing}\n{}", tail(&run.stderr));
            found.push(("crash", note));
        }
    }
    found
}

fn shell_quote(s: &str) -> String {
    if !s.is_empty()
        && s.bytes()
            .all(|b| b.is_ascii_alphanumeric() || b"-_./=,+:".contains(&b))
    {
        return s.to_owned();
    }
    format!("'{}'", s.replace('\'', r"'\''"))
}

/// The arguments as a shell command line, long ones shortened (for messages).
fn shown_args(args: &[String]) -> String {
    let words: Vec<String> = args
        .iter()
        .map(|a| {
            if a.len() > 60 {
                format!("'<{} bytes>'", a.len())
            } else {
                shell_quote(a)
            }
        })
        .collect();
    words.join(" ")
}

/// A shell script that rebuilds the case's folder in a temporary folder and runs it (saved
/// inputs next to the script, shared ones from the fuzz folder).
fn repro_script(o: &Opts, exe: &Path, case: &CliCase, index: u64) -> String {
    let mut s = format!(
        "#!/bin/sh\n# facebem fuzz, target cli, seed {} (worker), case {index}.\n\
         # Usage: sh repro.sh [path/to/facebem]\nset -e\n\
         here=$(cd \"$(dirname \"$0\")\" && pwd)\nexe=${{1:-{}}}\n\
         run=$(mktemp -d)\ncd \"$run\"\necho \"case folder: $run\" >&2\n",
        o.seed,
        shell_quote(&exe.to_string_lossy())
    );
    for f in &case.files {
        let from = match f.content {
            Content::Shared(name) => format!("\"$here/../{name}\""),
            Content::Bytes(_) => format!("\"$here/{}\"", shell_quote(&f.name)),
        };
        s.push_str(&format!("cp {from} {}\n", shell_quote(&f.name)));
    }
    s.push_str(&format!("mkdir {}\n", DIRS.join(" ")));
    for (link, target) in LINKS {
        s.push_str(&format!("ln -s {target} {link}\n"));
    }
    if case.wants_fifos() {
        s.push_str(&format!("mkfifo {}\n", FIFOS.join(" ")));
    }
    let args: Vec<String> = case.args.iter().map(|a| shell_quote(a)).collect();
    s.push_str(&format!(
        "ulimit -v {}\nexec \"$exe\" {}\n",
        o.case_mb << 10,
        args.join(" ")
    ));
    s
}

/// Saves a finding as `DIR/KIND-HASH/`; returns where.
fn save(o: &Opts, kind: &str, note: &str, case: &CliCase, repro: &str, run: &Run) -> String {
    let mut h = blake3::Hasher::new();
    h.update(kind.as_bytes());
    for a in &case.args {
        h.update(a.as_bytes());
        h.update(&[0]);
    }
    for f in &case.files {
        if let Content::Bytes(b) = &f.content {
            h.update(b);
        }
    }
    let dir = o
        .out
        .join(format!("{kind}-{}", &h.finalize().to_hex()[..16]));
    let _ = std::fs::create_dir_all(&dir);
    for f in &case.files {
        if let Content::Bytes(b) = &f.content {
            let _ = std::fs::write(dir.join(&f.name), b);
        }
    }
    let _ = std::fs::write(dir.join("repro.sh"), repro);
    let _ = std::fs::write(dir.join("note.txt"), format!("{kind}: {note}\n"));
    let _ = std::fs::write(dir.join("stdout.txt"), &run.stdout);
    let _ = std::fs::write(dir.join("stderr.txt"), &run.stderr);
    dir.display().to_string()
}
