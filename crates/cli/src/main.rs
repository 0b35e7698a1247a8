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

mod args;
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
fn open(path: &Path) -> Result<Opened, facebem::input::OpenError> {
    let limits = LIMITS.get().copied().unwrap_or_default();
    facebem::input::OpenOptions { limits }.open(path)
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
        } => rig(&face, &output, muscles.as_deref(), &solver, force),
        Command::Info { file } => info(&file),
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
            solver,
            force,
        } => export(&rig, &gltf, animation, names, naming, &solver, force),
        Command::Muscles { face, output } => muscles(&face, &output),
        Command::Sheet(args) => sheet(&args),
    }
}
