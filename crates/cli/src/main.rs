//! `facebem`: rig a face, inspect it, pose it, export it.
//!
//! ```text
//! facebem rig face.obj -o face.rig [--muscles face.muscles]
//! facebem info face.obj|face.rig
//! facebem pose face.rig --preset happy --set zygomaticus_major_l=-0.8 -o out.obj
//! facebem export face.rig --gltf out.glb [--names facebem|arkit|vrm|all]
//! facebem muscles face.obj -o face.muscles
//! facebem sheet face.rig -o sheet.png [--only muscles|presets|arkit|vrm]
//! ```
//!
//! Errors print one line naming the problem and exit with status 1 (2 for usage errors).

/// `println!` that does not panic when stdout is closed ([`write_stdout`]).
macro_rules! outln {
    ($($t:tt)*) => { $crate::write_stdout(format_args!("{}\n", format_args!($($t)*))) };
}

/// `print!` that does not panic when stdout is closed ([`write_stdout`]).
macro_rules! out {
    ($($t:tt)*) => { $crate::write_stdout(format_args!($($t)*)) };
}

mod args;
mod head;
mod json;
mod pose;
mod rig;
mod sheet;

use std::path::Path;
use std::process::ExitCode;

use anyhow::Result;
use clap::Parser;
use facebem::input::Opened;

use args::{Cli, Command};
use pose::{export, pose};
use rig::{info, muscles, rig};
use sheet::sheet;

/// Input size limits from the command line (set once in `main`).
static LIMITS: std::sync::OnceLock<face_prep::InputLimits> = std::sync::OnceLock::new();

/// Opens a face mesh or rig under the command line's input limits.
fn open(path: &Path) -> Result<Opened> {
    open_or_describe(path, false)
}

/// Opens a face or rig file, with the face reader's own error.
fn open_face(path: &Path) -> Result<Opened, facebem::input::OpenError> {
    let limits = LIMITS.get().copied().unwrap_or_default();
    facebem::input::OpenOptions { limits }.open(path)
}

/// Opens a face or rig file; a file of several parts (a head, an avatar) is refused saying so,
/// after `describe` lists its parts.
fn open_or_describe(path: &Path, describe: bool) -> Result<Opened> {
    open_face(path).map_err(|e| rig::whole_file_parts(path, e, describe))
}

/// Writes a report line to stdout. Regression (found piping `facebem export … | head -1`):
/// `println!` panicked ("failed printing to stdout: Broken pipe") once the reader had gone.
/// A closed pipe now only ends the report: the command goes on and writes its files (the
/// reader asked for no more text, not for less work); any other write error is one line on
/// stderr and exit code 1.
pub(crate) fn write_stdout(args: std::fmt::Arguments) {
    use std::io::Write;
    use std::sync::atomic::{AtomicBool, Ordering};
    static CLOSED: AtomicBool = AtomicBool::new(false);
    if crate::json::mode() || CLOSED.load(Ordering::Relaxed) {
        return;
    }
    let mut stdout = std::io::stdout().lock();
    if let Err(e) = stdout.write_fmt(args).and_then(|()| stdout.flush()) {
        if e.kind() == std::io::ErrorKind::BrokenPipe {
            CLOSED.store(true, Ordering::Relaxed);
            return;
        }
        eprintln!("error: writing to stdout: {e}");
        std::process::exit(1);
    }
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(e) => {
            let code = if e.use_stderr() { 2 } else { 0 };
            let _ = e.print();
            return ExitCode::from(code);
        }
    };
    match run(cli) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("error: {}", one_line(&e));
            ExitCode::FAILURE
        }
    }
}

/// The error and its causes on one line, leaving out causes whose text the message already
/// contains (many error types print their source inside their own message).
fn one_line(e: &anyhow::Error) -> String {
    let mut msg = String::new();
    for cause in e.chain() {
        let text = cause.to_string().replace('\n', " ");
        if msg.contains(&text) {
            continue;
        }
        if !msg.is_empty() {
            msg.push_str(": ");
        }
        msg.push_str(&text);
    }
    msg
}

/// Refuses `value` of `option` outside `range`, naming both, before any work.
pub(crate) fn check_range<T: PartialOrd + std::fmt::Display>(
    option: &str,
    value: T,
    range: std::ops::RangeInclusive<T>,
) -> Result<()> {
    if !range.contains(&value) {
        anyhow::bail!(
            "{option} {value} is out of range: must be in [{}, {}]",
            range.start(),
            range.end()
        );
    }
    Ok(())
}

fn run(cli: Cli) -> Result<()> {
    check_range("--max-input-mb", cli.max_input_mb, 0..=4096)?;
    check_range(
        "--max-input-triangles",
        cli.max_input_triangles,
        1..=20_000_000,
    )?;
    check_range("--max-muscles", cli.max_muscles, 1..=10_000)?;
    let _ = LIMITS.set(face_prep::InputLimits {
        max_file_bytes: cli.max_input_mb.saturating_mul(1 << 20),
        max_positions: cli.max_input_triangles,
        max_triangles: cli.max_input_triangles,
        max_muscles: cli.max_muscles,
    });
    match cli.command {
        Command::Rig {
            face,
            output,
            muscles,
            solver,
            force,
            json,
        } => {
            json::set_mode(json);
            rig(&face, &output, muscles.as_deref(), &solver, force)
        }
        Command::Info { file, json } => {
            json::set_mode(json);
            info(&file)
        }
        Command::Completions { shell } => {
            use clap::CommandFactory;
            let mut text = Vec::new();
            clap_complete::generate(shell, &mut Cli::command(), "facebem", &mut text);
            out!("{}", String::from_utf8_lossy(&text));
            Ok(())
        }
        Command::Pose {
            rig,
            sets,
            preset,
            output,
            solver,
            force,
        } => pose(&rig, &sets, preset.as_deref(), &output, &solver, force),
        Command::Export {
            rig,
            gltf,
            animation,
            names,
            naming,
            compress,
            solver,
            force,
            json,
        } => {
            json::set_mode(json);
            let params = facebem::export::GltfParams {
                animation,
                names,
                arkit_naming: naming,
                compress,
                ..Default::default()
            };
            export(&rig, &gltf, params, &solver, force)
        }
        Command::Muscles { face, output } => muscles(&face, &output),
        Command::Sheet(args) => sheet(&args),
    }
}
