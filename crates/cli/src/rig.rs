//! `rig`, `info` and `muscles`, and computing a model from a face mesh with a progress bar.

use std::path::{Path, PathBuf};
use std::time::Duration;

use anyhow::{Context, Result, bail};
use face_prep::RigParams;
use facebem::copy::LargeFaceParams;
use facebem::input::{CacheStatus, Opened};
use facebem::{Control, FaceModel, PipelineParams, build_face_model, cache};
use indicatif::{ProgressBar, ProgressStyle};

use crate::args::SolverArgs;
use crate::{LIMITS, open};

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

/// Where a command's rig came from.
#[derive(Clone, Debug)]
pub(crate) enum RigSource {
    /// The rig file given.
    RigFile,
    /// The rig cache (`facebem::input::cache_file_for`).
    Cache(PathBuf),
    /// Computed now; saved in the cache there unless `--no-cache` (or saving failed).
    Computed(Option<PathBuf>),
}

impl RigSource {
    /// JSON: `{"from": "rig file" | "cache" | "computed", "cacheFile": …}`.
    pub(crate) fn json(&self) -> serde_json::Value {
        match self {
            RigSource::RigFile => serde_json::json!({ "from": "rig file" }),
            RigSource::Cache(p) => serde_json::json!({ "from": "cache", "cacheFile": p }),
            RigSource::Computed(p) => serde_json::json!({ "from": "computed", "cacheFile": p }),
        }
    }
}

/// The model of `mesh` with `params`: from the rig cache the viewer shares when it holds it
/// (unless `no_cache`), else computed with a progress bar and saved there.
pub(crate) fn compute(
    mesh: &face_prep::FaceMesh,
    obj_source: Option<String>,
    params: &PipelineParams,
    no_cache: bool,
) -> Result<(FaceModel, RigSource)> {
    let (control, bar) = progress_control();
    if no_cache {
        let result = build_face_model(mesh, params, &control);
        bar.finish_and_clear();
        let mut model = result?;
        model.obj_source = obj_source;
        return Ok((model, RigSource::Computed(None)));
    }
    let dir = facebem::input::default_cache_dir();
    // A cache that cannot be made is no error: `load_or_build` computes and says why.
    let _ = std::fs::create_dir_all(&dir);
    let path = facebem::input::cache_file_for(&dir, mesh, params);
    let result = facebem::input::load_or_build(mesh, obj_source, params, &path, &control);
    bar.finish_and_clear();
    let (model, status) = result?;
    Ok(match status {
        CacheStatus::Loaded => {
            outln!(
                "rig loaded from the cache {} (--no-cache computes it again)",
                path.display()
            );
            (model, RigSource::Cache(path))
        }
        CacheStatus::Computed {
            save_error: Some(e),
            ..
        } => {
            eprintln!("warning: the rig was not cached: {e}");
            (model, RigSource::Computed(None))
        }
        CacheStatus::Computed { .. } => (model, RigSource::Computed(Some(path))),
    })
}

/// A posable model from a rig file, or from a face mesh computed first with `params` (the
/// command line's rig options, [`pipeline_params`]; the rig cache unless `no_cache`), for a
/// file already opened, saying where the rig came from. A rig file
/// was computed with its own options: rig options other than the defaults are refused with
/// one, rather than ignored.
pub(crate) fn model_from_opened(
    path: &Path,
    opened: Opened,
    params: &PipelineParams,
    no_cache: bool,
) -> Result<(FaceModel, RigSource)> {
    match opened {
        Opened::Model(model) => {
            if *params != PipelineParams::default() {
                bail!(
                    "{} is a rig file, computed with its own options: --units, --muscle-model \
                     and the other rig options apply to a face mesh",
                    path.display()
                );
            }
            Ok((*model, RigSource::RigFile))
        }
        Opened::Face { mesh, obj_source } => {
            // On stdout: stderr holds only warnings and the one error line (issue 36).
            outln!("{} is a face mesh: computing its rig first", path.display());
            compute(&mesh, obj_source, params, no_cache)
        }
    }
}

/// Refuses an untrustworthy rig ([`facebem::model::distrust`]) with one line naming every
/// cause, unless `force`: then each cause is printed as a warning and the caller goes on.
pub(crate) fn check_trust(model: &FaceModel, force: bool) -> Result<()> {
    let causes = facebem::model::distrust(model);
    if causes.is_empty() {
        return Ok(());
    }
    if force {
        for cause in &causes {
            eprintln!("warning: untrustworthy rig, written because of --force: {cause}");
        }
        return Ok(());
    }
    bail!(
        "the rig is not trustworthy: {} (--force writes it anyway)",
        causes.join("; ")
    )
}

/// The pipeline's parameters from the command line, every one checked against its documented
/// range ([`PipelineParams::validate`]) before any file is read; an error names the option.
pub(crate) fn pipeline_params(solver: &SolverArgs) -> Result<PipelineParams> {
    let default_target = LargeFaceParams::default().target_triangles;
    let params = PipelineParams {
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
            target_triangles: solver
                .target_triangles
                .unwrap_or(default_target.min(solver.max_triangles)),
            method: solver.copy,
            ..LargeFaceParams::default()
        },
        ..PipelineParams::default()
    };
    if let Err(e) = params.validate() {
        let option = match e.name.as_str() {
            "poisson" => "--poisson",
            "large_face.max_triangles" => "--max-triangles",
            "large_face.target_triangles" => "--target-triangles",
            "rig.offset" => "--offset",
            "rig.thickness" => "--thickness",
            _ => bail!("{e}"),
        };
        bail!(
            "{option} {} is out of range: must be in {}",
            e.value,
            e.range
        );
    }
    Ok(params)
}

pub(crate) fn rig(
    face: &Path,
    output: &Path,
    muscles: Option<&Path>,
    solver: &SolverArgs,
    force: bool,
) -> Result<()> {
    let started = std::time::Instant::now();
    let mut params = pipeline_params(solver)?;
    let inputs: Vec<&Path> = std::iter::once(face).chain(muscles).collect();
    facebem::check_output(output, &inputs, &["rig"], "a rig file")?;
    let (mesh, obj_source) = match open(face)? {
        Opened::Face { mesh, obj_source } => (mesh, obj_source),
        Opened::Model(_) => bail!("{} is already a rig file; give a face mesh", face.display()),
    };
    cache::check_rig_size(output, &mesh)?;
    if let Some(file) = muscles {
        let rig = facebem::prep_rig(&mesh, &params)?;
        let limits = LIMITS.get().copied().unwrap_or_default();
        let list = face_prep::muscle_file::ReadOptions {
            element_count: rig.shell.element_count(),
            limits,
        }
        .load(file)
        .with_context(|| format!("muscle file {}", file.display()))?;
        params.muscles = Some(list);
    }
    let (model, source) = compute(&mesh, obj_source, &params, solver.no_cache)?;
    check_trust(&model, force)?;
    cache::save(output, &model)?;
    if crate::json::mode() {
        let report =
            crate::json::command_report("rig", &model, face, output, source.json(), started);
        crate::json::print(&report);
        return Ok(());
    }
    let r = &model.report;
    for w in r.warnings() {
        eprintln!("warning: {w}");
    }
    let simplified = r
        .simplify_path
        .map(|p| format!(", simplified {}", p.describe()))
        .unwrap_or_default();
    outln!(
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

pub(crate) fn info(file: &Path) -> Result<()> {
    let opened = crate::open_or_describe(file, true)?;
    let (rig, mesh, model) = match &opened {
        Opened::Model(model) => (model.rig.clone(), &model.mesh, Some(model.as_ref())),
        Opened::Face { mesh, .. } => match facebem::prep_rig(mesh, &PipelineParams::default()) {
            Ok(rig) => (rig, mesh, None),
            Err(e) => {
                // Still describe what was found, then the error.
                out!("{}", facebem::report::describe::describe_loops(file, mesh));
                return Err(e.into());
            }
        },
    };
    if crate::json::mode() {
        crate::json::print(&crate::json::info_report(file, mesh, &rig, model));
        return Ok(());
    }
    out!(
        "{}",
        facebem::report::describe::describe(file, mesh, &rig, model)
    );
    Ok(())
}

pub(crate) fn muscles(face: &Path, output: &Path) -> Result<()> {
    facebem::check_output(output, &[face], &["muscles"], "a muscle file")?;
    let rig = match open(face)? {
        Opened::Model(model) => model.rig,
        Opened::Face { mesh, .. } => facebem::prep_rig(&mesh, &PipelineParams::default())?,
    };
    face_prep::muscle_file::save(output, &rig.muscles)
        .with_context(|| format!("cannot write {}", output.display()))?;
    outln!("{}: {} muscles", output.display(), rig.muscles.len());
    Ok(())
}

/// A file that is not one face: if it holds several parts (a head or an avatar), why it is not
/// rigged (and, with `describe`, what the parts are, on stdout); otherwise the reading error as
/// it is.
pub(crate) fn whole_file_parts(
    file: &Path,
    e: facebem::input::OpenError,
    describe: bool,
) -> anyhow::Error {
    if !matches!(&e, facebem::input::OpenError::Face { .. }) {
        return e.into();
    }
    let whole = match facebem::input::heads::WholeFile::examine(file) {
        None => return e.into(),
        Some(Err(refusal)) => return anyhow::anyhow!("{refusal}"),
        Some(Ok(whole)) => whole,
    };
    let refusal = whole.refusal(file);
    if describe {
        let parts = &whole.parts;
        if crate::json::mode() {
            let report = crate::json::parts_report(file, &whole.scene, parts, &refusal);
            crate::json::print(&report);
        } else {
            out!(
                "{}",
                facebem::report::describe::describe_parts(file, &whole.scene, parts)
            );
        }
    }
    anyhow::anyhow!("{refusal}")
}
