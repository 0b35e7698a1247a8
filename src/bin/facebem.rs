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

use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Duration;

use anyhow::{Context, Result, anyhow, bail};
use clap::{Args, Parser, Subcommand};
use face_prep::RigParams;
use facebem::expression_sets::{self, NameSet, NameSets};
use facebem::large_face::LargeFaceParams;
use facebem::open::Opened;
use facebem::{Control, FaceModel, PipelineParams, build_face_model, cache, presets};
use indicatif::{ProgressBar, ProgressStyle};

#[derive(Parser)]
#[command(
    name = "facebem",
    version,
    about = "Physically based facial muscle rig from one neutral face mesh"
)]
struct Cli {
    #[command(subcommand)]
    command: Command,
    /// Largest input file read, in MiB (face meshes and muscle files; rigs up to 1024).
    #[arg(long, global = true, default_value_t = face_prep::InputLimits::default().max_file_bytes >> 20)]
    max_input_mb: u64,
    /// Most positions and triangles a face mesh may have.
    #[arg(long, global = true, default_value_t = face_prep::InputLimits::default().max_triangles)]
    max_input_triangles: usize,
    /// Most muscles a muscle file may hold (`rig --muscles`).
    #[arg(long, global = true, default_value_t = face_prep::InputLimits::default().max_muscles)]
    max_muscles: usize,
}

/// Input size limits from the command line (set once in `main`).
static LIMITS: std::sync::OnceLock<face_prep::InputLimits> = std::sync::OnceLock::new();

/// Opens a face mesh or rig under the command line's input limits.
fn open(path: &Path) -> Result<Opened, facebem::open::OpenError> {
    let limits = LIMITS.get().copied().unwrap_or_default();
    facebem::open::open_with_limits(path, &limits)
}

#[derive(Subcommand)]
enum Command {
    /// Build the rig and precompute the muscle basis; save it as a rig file.
    Rig {
        /// Face mesh (.obj, .gltf, .glb).
        face: PathBuf,
        /// Output rig file.
        #[arg(short, long)]
        output: PathBuf,
        /// Use this (edited) muscle file instead of the automatic muscles.
        #[arg(long)]
        muscles: Option<PathBuf>,
        #[command(flatten)]
        solver: SolverArgs,
    },
    /// Print loops, feature boxes, muscles and sizes of a face or rig file.
    Info {
        /// Face mesh or rig file.
        file: PathBuf,
    },
    /// Write an OBJ of a pose (a preset, then individual sliders on top).
    #[command(after_help = presets_help())]
    Pose {
        /// Rig file (or a face mesh, which is then computed first).
        rig: PathBuf,
        /// Slider value `muscle_id=value`, value in [-1, 1], negative contracts. Repeatable.
        #[arg(long = "set", value_name = "ID=VALUE")]
        sets: Vec<String>,
        /// Expression applied first: a facebem preset (neutral, happy, smile, laugh, sad, angry,
        /// surprised, disgust, fear), an ARKit blendshape name (mouthSmileLeft, jawOpen, …) or a
        /// VRM 1.0 preset (relaxed, aa, ih, ou, ee, oh, blink, blinkLeft, blinkRight, …).
        #[arg(long)]
        preset: Option<String>,
        /// Output OBJ.
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Export glTF 2.0 (metres, the input's vertex order and texture coordinates) with one
    /// morph target per muscle action and preset.
    #[command(after_help = presets_help())]
    Export {
        /// Rig file (or a face mesh, which is then computed first).
        rig: PathBuf,
        /// Output .glb or .gltf.
        #[arg(long)]
        gltf: PathBuf,
        /// Add one animation clip per preset, named after it (neutral → preset → neutral).
        #[arg(long)]
        animation: bool,
        /// Morph target names to write: `arkit` (ARKit blendshapes), `vrm` (VRM 1.0 presets),
        /// `facebem` (each muscle's `_contract`/`_relax` and `preset_<name>`), `all`, or a
        /// comma-separated list. ARKit and VRM targets come first.
        #[arg(long, default_value = "all", value_parser = NameSets::parse)]
        names: NameSets,
    },
    /// Write the automatically placed muscles of a face as a muscle file (thesis format).
    Muscles {
        /// Face mesh (.obj, .gltf, .glb) or rig file.
        face: PathBuf,
        /// Output muscle file.
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Render a contact sheet PNG: neutral, each muscle contracted, each preset; front and 3/4
    /// view, coloured by displacement in mm.
    Sheet(SheetArgs),
}

#[derive(Args)]
struct SheetArgs {
    /// Rig file (or a face mesh, which is then computed first).
    rig: PathBuf,
    /// Output PNG.
    #[arg(short, long)]
    output: PathBuf,
    /// Only the muscles (with neutral), only the presets, or one page of named expressions: the
    /// ARKit blendshapes or the VRM 1.0 presets the rig can make.
    #[arg(long, value_parser = ["muscles", "presets", "arkit", "vrm"])]
    only: Option<String>,
}

#[derive(Args)]
struct SolverArgs {
    /// Poisson ratio of the tissue, in [0, 0.5).
    #[arg(long, default_value_t = 0.45, allow_negative_numbers = true)]
    poisson: f64,
    /// Faces with more front triangles than this are simulated on a simplified copy.
    #[arg(long, default_value_t = LargeFaceParams::default().max_triangles, allow_negative_numbers = true)]
    max_triangles: usize,
    /// Triangle count of the simplified copy.
    #[arg(long, default_value_t = LargeFaceParams::default().target_triangles, allow_negative_numbers = true)]
    target_triangles: usize,
    /// How a large face's copy is made: `collapse` (edge collapses that keep input vertices)
    /// or `remesh` (near-equilateral triangles, finer at the mouth and eyes, mirrored on a
    /// mirror-symmetric face).
    #[arg(long, default_value = "collapse", value_parser = parse_copy_method)]
    copy: facebem::large_face::CopyMethod,
    /// Back-face offset of the shell, as a fraction of the face size.
    #[arg(long, default_value_t = RigParams::default().offset, allow_negative_numbers = true)]
    offset: f64,
    /// Rim thickness of the shell, as a fraction of the face size.
    #[arg(long, default_value_t = RigParams::default().thickness, allow_negative_numbers = true)]
    thickness: f64,
    /// Simulate eyelids and lips that roll in behind the eye and mouth contours too (by
    /// default they are peeled off the simulated copy and follow the nearest simulated point).
    #[arg(long)]
    keep_rolled_in: bool,
    /// Length unit of the face mesh's coordinates: mm, cm, m, in, or auto (estimated from the
    /// distance between the eyes, adult mean 63 mm; `info` says what was chosen).
    #[arg(long, default_value = "auto", value_parser = parse_units)]
    units: face_prep::units::Units,
    /// Muscle model: `anatomical` (origin on bone, insertion in skin, shortening as a strain,
    /// in mm) or `thesis` (the 2002 thesis's chain rule, reproduced exactly).
    #[arg(long, default_value = "anatomical", value_parser = parse_muscle_model)]
    muscle_model: face_prep::muscle_model::MuscleModel,
}

fn parse_copy_method(s: &str) -> Result<facebem::large_face::CopyMethod, String> {
    facebem::large_face::CopyMethod::parse(s)
        .ok_or_else(|| format!("unknown copy method {s:?}: use collapse or remesh"))
}

fn parse_muscle_model(s: &str) -> Result<face_prep::muscle_model::MuscleModel, String> {
    face_prep::muscle_model::MuscleModel::parse(s)
        .ok_or_else(|| format!("unknown muscle model {s:?}: use anatomical or thesis"))
}

fn parse_units(s: &str) -> Result<face_prep::units::Units, String> {
    face_prep::units::Units::parse(s)
        .ok_or_else(|| format!("unknown unit {s:?}: use mm, cm, m, in or auto"))
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

fn run(cli: Cli) -> Result<()> {
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
        } => rig(&face, &output, muscles.as_deref(), &solver),
        Command::Info { file } => info(&file),
        Command::Pose {
            rig,
            sets,
            preset,
            output,
        } => pose(&rig, &sets, preset.as_deref(), &output),
        Command::Export {
            rig,
            gltf,
            animation,
            names,
        } => export(&rig, &gltf, animation, names),
        Command::Muscles { face, output } => muscles(&face, &output),
        Command::Sheet(args) => sheet(&args),
    }
}

/// The presets with their FACS action units, for `--help`.
fn presets_help() -> String {
    let mut out = String::from("Presets (FACS action units; negative sliders contract):\n");
    for p in &presets::ALL {
        out.push_str(&format!(
            "  {:<10} {:<24} {}\n",
            p.name, p.action_units, p.description
        ));
    }
    for set in [NameSet::Arkit, NameSet::Vrm] {
        let names: Vec<&str> = expression_sets::of_set(set)
            .iter()
            .map(|e| e.name)
            .collect();
        out.push_str(&format!(
            "{} names (also accepted by --preset; defined in facebem::expression_sets):\n  {}\n",
            set.display_name(),
            names.join(" ")
        ));
    }
    out
}

fn progress_control() -> (Control, ProgressBar) {
    let bar = ProgressBar::new(1);
    bar.set_style(
        ProgressStyle::with_template("{spinner} {elapsed:>4} {msg:>13} [{bar:30}] {pos}/{len}")
            .unwrap_or_else(|_| ProgressStyle::default_bar())
            .progress_chars("=> "),
    );
    bar.enable_steady_tick(Duration::from_millis(200));
    let b = bar.clone();
    let control = Control::new().with_progress(move |p| {
        b.set_message(p.stage.label());
        b.set_length(p.total);
        b.set_position(p.done);
    });
    (control, bar)
}

fn compute(
    mesh: &face_prep::FaceMesh,
    obj_source: Option<String>,
    params: &PipelineParams,
) -> Result<FaceModel> {
    let (control, bar) = progress_control();
    let result = build_face_model(mesh, params, &control);
    bar.finish_and_clear();
    let mut model = result?;
    model.obj_source = obj_source;
    Ok(model)
}

/// A posable model from a rig file, or from a face mesh computed with default parameters.
fn model_from(path: &Path) -> Result<FaceModel> {
    model_from_opened(path, open(path)?)
}

/// Like [`model_from`], for a file already opened.
fn model_from_opened(path: &Path, opened: Opened) -> Result<FaceModel> {
    match opened {
        Opened::Model(model) => Ok(*model),
        Opened::Face { mesh, obj_source } => {
            eprintln!("{} is a face mesh: computing its rig first", path.display());
            compute(&mesh, obj_source, &PipelineParams::default())
        }
    }
}

fn rig(face: &Path, output: &Path, muscles: Option<&Path>, solver: &SolverArgs) -> Result<()> {
    let inputs: Vec<&Path> = std::iter::once(face).chain(muscles).collect();
    facebem::check_output(output, &inputs, &["rig"], "a rig file")?;
    let (mesh, obj_source) = match open(face)? {
        Opened::Face { mesh, obj_source } => (mesh, obj_source),
        Opened::Model(_) => bail!("{} is already a rig file; give a face mesh", face.display()),
    };
    let mut params = PipelineParams {
        rig: RigParams {
            offset: solver.offset,
            thickness: solver.thickness,
            units: solver.units,
            muscle_model: solver.muscle_model,
            ..RigParams::default()
        },
        poisson: solver.poisson,
        peel_rolled_in: !solver.keep_rolled_in,
        large_face: LargeFaceParams {
            max_triangles: solver.max_triangles,
            target_triangles: solver.target_triangles,
            method: solver.copy,
            ..LargeFaceParams::default()
        },
        ..PipelineParams::default()
    };
    if let Some(file) = muscles {
        let rig = facebem::prep_rig(&mesh, &params)?;
        let limits = LIMITS.get().copied().unwrap_or_default();
        let list =
            face_prep::muscle_file::load_with_limits(file, rig.shell.element_count(), &limits)
                .with_context(|| format!("muscle file {}", file.display()))?;
        params.muscles = Some(list);
    }
    let model = compute(&mesh, obj_source, &params)?;
    cache::save(output, &model)?;
    let r = &model.report;
    for w in r.warnings() {
        eprintln!("warning: {w}");
    }
    let simplified = r
        .simplify_path
        .map(|p| format!(", simplified {}", p.describe()))
        .unwrap_or_default();
    println!(
        "{}: {} front triangles ({} simulated{simplified}), {} shell elements, {} muscles; prep {:.2} s, solve {:.2} s",
        output.display(),
        r.input_triangles,
        r.simulated_triangles,
        r.shell_elements,
        model.basis.muscle_count(),
        r.prep_seconds,
        r.solve_seconds
    );
    Ok(())
}

fn info(file: &Path) -> Result<()> {
    let opened = open(file)?;
    let (rig, mesh, model) = match &opened {
        Opened::Model(model) => (model.rig.clone(), &model.mesh, Some(model.as_ref())),
        Opened::Face { mesh, .. } => match facebem::prep_rig(mesh, &PipelineParams::default()) {
            Ok(rig) => (rig, mesh, None),
            Err(e) => {
                // Still describe what was found, then the error.
                print!("{}", facebem::describe::describe_loops(file, mesh));
                return Err(e.into());
            }
        },
    };
    print!("{}", facebem::describe::describe(file, mesh, &rig, model));
    Ok(())
}

fn parse_set(s: &str) -> Result<(String, f64)> {
    let (id, value) = s
        .split_once('=')
        .ok_or_else(|| anyhow!("--set {s:?}: expected muscle_id=value"))?;
    let value: f64 = value
        .trim()
        .parse()
        .with_context(|| format!("--set {s:?}: {value:?} is not a number"))?;
    if !(-1.0..=1.0).contains(&value) {
        bail!("--set {s:?}: value {value} is outside [-1, 1]");
    }
    Ok((id.trim().to_string(), value))
}

fn pose(rig: &Path, sets: &[String], preset: Option<&str>, output: &Path) -> Result<()> {
    facebem::check_output(output, &[rig], &["obj"], "a pose (OBJ)")?;
    let parsed: Vec<(String, f64)> = sets.iter().map(|s| parse_set(s)).collect::<Result<_>>()?;
    if let Some(name) = preset
        && presets::find(name).is_none()
        && expression_sets::find(name).is_none()
    {
        bail!(
            "unknown preset {name:?} (known: {}, or an ARKit or VRM 1.0 name, see --help)",
            presets::names().join(", ")
        );
    }
    let opened = open(rig)?;
    // Unknown muscle names are found before a face mesh's rig is computed.
    let known: Vec<String> = match &opened {
        Opened::Model(model) => model.muscle_ids().to_vec(),
        Opened::Face { .. } => face_prep::MuscleKind::ALL
            .iter()
            .map(|k| k.id().to_string())
            .collect(),
    };
    if let Some((id, _)) = parsed.iter().find(|(id, _)| !known.contains(id)) {
        // At most ten names in a one-line message (the anatomical rig has 27 controls).
        let shown: Vec<&str> = known.iter().take(10).map(String::as_str).collect();
        let more = match known.len().saturating_sub(shown.len()) {
            0 => String::new(),
            n => format!(", and {n} more: `facebem info` lists them"),
        };
        bail!("unknown muscle {id:?} (known: {}{more})", shown.join(", "));
    }
    let model = model_from_opened(rig, opened)?;
    let ids = model.muscle_ids().to_vec();
    let mut sliders = vec![0.0; ids.len()];
    if let Some(name) = preset {
        let (values, missing) = expression_sets::sliders_for_name(name, &ids)?;
        if !missing.is_empty() {
            eprintln!(
                "warning: {name}: this rig has no {}; posed from its other controls",
                missing.join(", ")
            );
        }
        sliders = values;
    }
    for (id, value) in parsed {
        let k = model
            .basis
            .muscle_index(&id)
            .ok_or_else(|| anyhow!("unknown muscle {id:?} (known: {})", ids.join(", ")))?;
        sliders[k] = value;
    }
    model.write_obj(output, &sliders)?;
    println!(
        "{}: posed {} vertices",
        output.display(),
        model.mesh.vertices.len()
    );
    Ok(())
}

fn export(rig: &Path, gltf: &Path, animation: bool, names: NameSets) -> Result<()> {
    facebem::check_output(gltf, &[rig], &["glb", "gltf"], "a glTF export")?;
    let model = model_from(rig)?;
    let params = facebem::export::GltfParams {
        animation,
        names,
        ..Default::default()
    };
    model.write_gltf(gltf, &params)?;
    let (made, left_out) = expression_sets::for_rig(names, model.muscle_ids());
    let own = if names.facebem {
        2 * model.basis.muscle_count() + presets::ALL.len() - 1
    } else {
        0
    };
    println!("{}: {} morph targets", gltf.display(), made.len() + own);
    for set in [NameSet::Arkit, NameSet::Vrm] {
        if !names.contains(set) {
            continue;
        }
        let count = made.iter().filter(|m| m.expression.set == set).count();
        let partial: Vec<&str> = made
            .iter()
            .filter(|m| m.expression.set == set && !m.resolved.missing.is_empty())
            .map(|m| m.expression.name)
            .collect();
        let missing: Vec<&str> = left_out
            .iter()
            .filter(|(e, _)| e.set == set)
            .map(|(e, _)| e.name)
            .collect();
        println!(
            "  {}: {count} of {} names ({} not modelled: no eyeballs/tongue)",
            set.display_name(),
            set.standard_size(),
            set.standard_size() - expression_sets::of_set(set).len()
        );
        if !partial.is_empty() {
            println!(
                "    from only some of their controls: {}",
                partial.join(" ")
            );
        }
        if !missing.is_empty() {
            println!(
                "    left out, their controls are not in this rig: {}",
                missing.join(" ")
            );
        }
    }
    Ok(())
}

fn muscles(face: &Path, output: &Path) -> Result<()> {
    facebem::check_output(output, &[face], &["muscles"], "a muscle file")?;
    let rig = match open(face)? {
        Opened::Model(model) => model.rig,
        Opened::Face { mesh, .. } => facebem::prep_rig(&mesh, &PipelineParams::default())?,
    };
    face_prep::muscle_file::save(output, &rig.muscles)
        .with_context(|| format!("cannot write {}", output.display()))?;
    println!("{}: {} muscles", output.display(), rig.muscles.len());
    Ok(())
}

fn sheet(args: &SheetArgs) -> Result<()> {
    use facebem::contact_sheet::{self, Selection, SheetOptions};
    facebem::check_output(
        &args.output,
        &[&args.rig],
        &["png"],
        "a contact sheet (PNG)",
    )?;
    let model = model_from(&args.rig)?;
    let selection = match args.only.as_deref() {
        Some("muscles") => Selection::Muscles,
        Some("presets") => Selection::Presets,
        Some("arkit") => Selection::Named(NameSet::Arkit),
        Some("vrm") => Selection::Named(NameSet::Vrm),
        _ => Selection::All,
    };
    let cells = contact_sheet::standard_cells(&model, selection);
    if let Selection::Named(set) = selection {
        let (_, left_out) = expression_sets::for_rig(
            NameSets {
                facebem: false,
                arkit: set == NameSet::Arkit,
                vrm: set == NameSet::Vrm,
            },
            model.muscle_ids(),
        );
        if !left_out.is_empty() {
            let names: Vec<&str> = left_out.iter().map(|(e, _)| e.name).collect();
            println!(
                "{} names left out (their controls are not in this rig): {}",
                set.display_name(),
                names.join(" ")
            );
        }
    }
    let name = args.rig.file_name().map_or_else(
        || args.rig.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let unit = &model.rig.unit;
    let detected = if model.rig.unit_detected {
        ", detected"
    } else {
        ""
    };
    let page = match selection {
        Selection::Named(set) => format!(
            "  {} names: {} of {}",
            set.display_name(),
            cells.len(),
            set.standard_size()
        ),
        _ => String::new(),
    };
    let opts = SheetOptions {
        title: format!("{name}  (unit: {unit}{detected}){page}"),
        ..SheetOptions::default()
    };
    let start = std::time::Instant::now();
    let image = contact_sheet::render(&model, &cells, &opts)?;
    contact_sheet::write_png(&args.output, &image)?;
    println!(
        "{}: {} cells, {} x {} px, drawn and written in {:.2} s",
        args.output.display(),
        cells.len(),
        image.width,
        image.height,
        start.elapsed().as_secs_f64()
    );
    Ok(())
}
