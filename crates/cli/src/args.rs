//! The command line's arguments, flags and help text.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};
use face_prep::RigParams;
use facebem::copy::LargeFaceParams;
use facebem::expressions::{self, NameSet, NameSets, presets};

#[derive(Parser)]
#[command(
    name = "facebem",
    version,
    about = "Physically based facial muscle rig from one neutral face mesh"
)]
pub(crate) struct Cli {
    #[command(subcommand)]
    pub(crate) command: Command,
    /// Largest input file read, in MiB (face meshes and muscle files; rigs up to 1024), in
    /// [0, 4096].
    #[arg(long, global = true, default_value_t = face_prep::InputLimits::default().max_file_bytes >> 20)]
    pub(crate) max_input_mb: u64,
    /// Most positions and triangles a face mesh may have, in [1, 20000000].
    #[arg(long, global = true, default_value_t = face_prep::InputLimits::default().max_triangles)]
    pub(crate) max_input_triangles: usize,
    /// Most muscles a muscle file may hold (`rig --muscles`), in [1, 10000].
    #[arg(long, global = true, default_value_t = face_prep::InputLimits::default().max_muscles)]
    pub(crate) max_muscles: usize,
}

#[derive(Subcommand)]
pub(crate) enum Command {
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
        /// Write it even when the rig is not trustworthy (a near-singular solve, a shell that
        /// crosses itself, a control that moves the skin past the documented limits); the
        /// causes are printed as warnings.
        #[arg(long)]
        force: bool,
        /// Print one JSON object (what was found, warnings, trust, sizes, times) instead of
        /// the text report.
        #[arg(long)]
        json: bool,
    },
    /// Print loops, feature boxes, muscles and sizes of a face or rig file.
    Info {
        /// Face mesh or rig file.
        file: PathBuf,
        /// Print one JSON object (the file, its unit, loops, muscles, controls, the names it
        /// makes, warnings, trust) instead of the text report.
        #[arg(long)]
        json: bool,
    },
    /// Print a shell completion script: `facebem completions bash > /etc/bash_completion.d/facebem`
    /// (or zsh, fish, elvish, powershell).
    Completions {
        /// The shell.
        shell: clap_complete::Shell,
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
        /// Rig options, used when RIG is a face mesh (a rig file keeps its own).
        #[command(flatten)]
        solver: SolverArgs,
        /// Write it even when the rig is not trustworthy (a near-singular solve, a shell that
        /// crosses itself, a control that moves the skin past the documented limits); the
        /// causes are printed as warnings.
        #[arg(long)]
        force: bool,
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
        /// `facebem` (each muscle's `_contract` and `preset_<name>`), `all`, or a
        /// comma-separated list. ARKit and VRM targets come first; a target equal to an earlier
        /// one, its negative or all zero is left out and named in the file's
        /// `mesh.extras.sameAs` / `negativeOf` / `leftOutTargets`.
        #[arg(long, default_value = "arkit,vrm", value_parser = NameSets::parse)]
        names: NameSets,
        /// How the ARKit targets are spelled: `arkit` (`eyeBlinkLeft`, as glTF and three.js
        /// avatars name them) or `arkit-raw` (`eyeBlink_L`, ARKit's raw location strings, as
        /// Live Link Face and Face Cap send them). `pose --preset` accepts both.
        #[arg(long, default_value = "arkit", value_parser = facebem::export::ArkitNaming::parse)]
        naming: facebem::export::ArkitNaming,
        /// Print one JSON object (the targets written, the repeats left out, warnings, trust,
        /// times) instead of the text report.
        #[arg(long)]
        json: bool,
        /// Compress the file with `EXT_meshopt_compression` (a third of the size; three.js
        /// needs `loader.setMeshoptDecoder(MeshoptDecoder)`, Blender 3.4 cannot read it).
        /// Positions are kept to 2^-19 of the largest coordinate (0.6 µm on a 0.3 m head), a
        /// target's deltas to 2^-15 of its largest, normals to 2^-11.
        #[arg(long)]
        compress: bool,
        /// Rig options, used when RIG is a face mesh (a rig file keeps its own).
        #[command(flatten)]
        solver: SolverArgs,
        /// Write it even when the rig is not trustworthy (a near-singular solve, a shell that
        /// crosses itself, a control that moves the skin past the documented limits); the
        /// causes are printed as warnings.
        #[arg(long)]
        force: bool,
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
pub(crate) struct SheetArgs {
    /// Rig file (or a face mesh, which is then computed first).
    pub(crate) rig: PathBuf,
    /// Output PNG.
    #[arg(short, long)]
    pub(crate) output: PathBuf,
    /// Only the muscles (with neutral), only the presets, or one page of named expressions: the
    /// ARKit blendshapes or the VRM 1.0 presets the rig can make.
    #[arg(long, value_parser = ["muscles", "presets", "arkit", "vrm"])]
    pub(crate) only: Option<String>,
    /// Rig options, used when RIG is a face mesh (a rig file keeps its own).
    #[command(flatten)]
    pub(crate) solver: SolverArgs,
}

#[derive(Args)]
pub(crate) struct SolverArgs {
    /// Poisson ratio of the tissue, in [0, 0.49].
    #[arg(long, default_value_t = 0.45, allow_negative_numbers = true)]
    pub(crate) poisson: f64,
    /// Faces with more front triangles than this are simulated on a simplified copy; in
    /// [100, 6000] (the dense solve grows with its square: 6000 needs about 12 GB).
    #[arg(long, default_value_t = LargeFaceParams::default().max_triangles, allow_negative_numbers = true)]
    pub(crate) max_triangles: usize,
    /// Triangle count of the simplified copy, in [100, 6000]; default the smaller of 1500 and
    /// --max-triangles.
    #[arg(long, allow_negative_numbers = true)]
    pub(crate) target_triangles: Option<usize>,
    /// How a large face's copy is made: `collapse` (edge collapses that keep input vertices)
    /// or `remesh` (near-equilateral triangles, finer at the mouth and eyes, mirrored on a
    /// mirror-symmetric face).
    #[arg(long, default_value = "collapse", value_parser = parse_copy_method)]
    pub(crate) copy: facebem::copy::CopyMethod,
    /// Back-face offset of the shell, as a fraction of the face size, in [0.0005, 0.2].
    #[arg(long, default_value_t = RigParams::default().offset, allow_negative_numbers = true)]
    pub(crate) offset: f64,
    /// Rim thickness of the shell, as a fraction of the face size, in [0.0005, 0.2].
    #[arg(long, default_value_t = RigParams::default().thickness, allow_negative_numbers = true)]
    pub(crate) thickness: f64,
    /// Simulate eyelids and lips that roll in behind the eye and mouth contours too (by
    /// default they are peeled off the simulated copy and follow the nearest simulated point).
    #[arg(long)]
    pub(crate) keep_rolled_in: bool,
    /// Length unit of the face mesh's coordinates: mm, cm, m, in, or auto (estimated from the
    /// distance between the eyes, adult mean 63 mm; `info` says what was chosen).
    #[arg(long, default_value = "auto", value_parser = parse_units)]
    pub(crate) units: face_prep::units::Units,
    /// Muscle model: `anatomical` (origin on bone, insertion in skin, shortening as a strain,
    /// in mm) or `thesis` (the 2002 thesis's chain rule, reproduced exactly).
    #[arg(long, default_value = "anatomical", value_parser = parse_muscle_model)]
    pub(crate) muscle_model: face_prep::muscle_model::MuscleModel,
    /// Compute a face mesh's rig even when the rig cache holds it, and do not save it there
    /// (the cache, shared with the viewer, is $XDG_CACHE_HOME/facebem or ~/.cache/facebem:
    /// one file per mesh and set of rig options, the 32 most recent kept).
    #[arg(long)]
    pub(crate) no_cache: bool,
}

fn parse_copy_method(s: &str) -> Result<facebem::copy::CopyMethod, String> {
    facebem::copy::CopyMethod::parse(s)
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
        let names: Vec<&str> = expressions::of_set(set).iter().map(|e| e.name).collect();
        let raw = if set == NameSet::Arkit {
            " and in ARKit's raw spelling, e.g. eyeBlink_L"
        } else {
            ""
        };
        out.push_str(&format!(
            "{} names (also accepted by --preset{raw}; defined in facebem::expressions):\n  {}\n",
            set.display_name(),
            names.join(" ")
        ));
    }
    out
}
