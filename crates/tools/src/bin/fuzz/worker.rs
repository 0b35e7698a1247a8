//! A worker process: mutates the seeds and runs each case in a thread under `catch_unwind`,
//! with a time limit and a memory limit, saving what fails.

use std::path::{Path, PathBuf};
use std::sync::atomic::Ordering::Relaxed;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use facebem::copy::LargeFaceParams;
use facebem::export::gltf::{GltfFormat, GltfParams};
use facebem::face_prep::{self, FaceMesh, muscle_file};
use facebem::{Control, FaceModel, PipelineParams, cache};

use crate::alloc::{LIMIT, LIVE, PEAK};
use crate::mutate::{Rng, mutate_gltf, mutate_rig, mutate_text};
use crate::opts::{Clock, Opts};
use crate::output_check::{check_gltf, check_muscles, check_obj};
use crate::seeds::ext;
use crate::stats::Stats;

struct Ctx {
    target: String,
    work: PathBuf,
    model: Option<FaceModel>,
    element_count: usize,
}

/// What a case does beyond reading its input (drawn by the worker, so a seed replays it).
#[derive(Clone, Copy)]
struct Depth {
    /// A valid face also goes through the rig prep.
    prep: bool,
    /// A valid face is also rigged cheaply and exported (pose OBJ and glTF, outputs checked).
    export: bool,
    /// glTF exports as `.gltf` text (else GLB), with animation clips.
    embedded: bool,
    animation: bool,
}

/// A failed oracle: its kind (`wrong`, `nonfinite`) and what it found.
type Finding = (&'static str, String);

/// Runs one case; `Err` is an oracle failure (a wrong result rather than a refusal).
fn run_case(ctx: &Ctx, data: &[u8], d: Depth) -> Result<(), Finding> {
    let params = PipelineParams::default();
    let prep = |mesh: &FaceMesh| {
        if d.prep
            && let Ok(rig) = facebem::prep_rig(mesh, &params)
        {
            let _ = facebem::report::describe::describe(Path::new("x"), mesh, &rig, None);
        }
    };
    match ctx.target.as_str() {
        "obj" => {
            if let Ok(mesh) = FaceMesh::from_obj_bytes(data, &Default::default()) {
                prep(&mesh);
                if d.export {
                    let source = String::from_utf8_lossy(data).into_owned();
                    export_face(&mesh, Some(source), d)?;
                }
            }
        }
        "gltf" => {
            let path = ctx.work.join(format!("case.{}", ext("gltf", data)));
            std::fs::write(&path, data).map_err(|e| ("wrong", e.to_string()))?;
            if let Ok(mesh) = face_prep::load_face(&path) {
                prep(&mesh);
                if d.export
                    && let Ok((mesh, source)) = facebem::input::read_face(&path)
                {
                    export_face(&mesh, source, d)?;
                }
            }
        }
        "rig" => {
            if let Ok(model) = cache::from_bytes(Path::new("case.rig"), data) {
                let sliders = happy(&model);
                if let Ok(posed) = model.pose(&sliders)
                    && posed.iter().any(|p| !p.is_finite())
                {
                    let e = "a validated rig posed to non-finite coordinates";
                    return Err(("wrong", e.into()));
                }
                check_exports(&model, d)?;
            }
        }
        _ => {
            let text = String::from_utf8_lossy(data);
            if let Ok(list) = muscle_file::read_str(&text, ctx.element_count)
                && let Some(m) = &ctx.model
            {
                if let Ok(out) = muscle_file::to_string(&list) {
                    check_muscles(out.as_bytes())
                        .map_err(|e| ("nonfinite", format!("muscle file written: {e}")))?;
                }
                let _ = m.rig.clone().with_muscles(list);
            }
        }
    }
    Ok(())
}

/// Heap allowed on top of `--case-mb` while a face is rigged (see [`export_face`]).
const SOLVE_SCRATCH: usize = 2 << 30;

fn happy(model: &FaceModel) -> Vec<f64> {
    facebem::expressions::presets::find("happy")
        .map(|p| p.sliders_for(model.muscle_ids()))
        .unwrap_or_default()
}

/// Rigs a face cheaply (simulated on a copy of at most 200 triangles, ~0.2 s for the bundled
/// face) and checks its exports.
fn export_face(mesh: &FaceMesh, obj_source: Option<String>, d: Depth) -> Result<(), Finding> {
    let params = PipelineParams {
        large_face: LargeFaceParams {
            max_triangles: 200,
            target_triangles: 200,
            ..LargeFaceParams::default()
        },
        ..PipelineParams::default()
    };
    // The dense LU's matrix products (gemm) keep a thread-local packing buffer of twice the
    // L3 cache the CPU reports (960 MiB on a VM that reports 480 MiB), allocated but barely
    // touched, and kept by the thread: allowed on top of the case's heap limit from here on.
    LIMIT.fetch_add(SOLVE_SCRATCH, Relaxed);
    let built = facebem::build_face_model(mesh, &params, &Control::new());
    let Ok(mut model) = built else {
        return Ok(());
    };
    model.obj_source = obj_source;
    check_exports(&model, d)
}

/// The pose OBJ (preset `happy`) and the glTF export of `model` (as `facebem pose` and
/// `facebem export --force` make them) have only finite numbers.
fn check_exports(model: &FaceModel, d: Depth) -> Result<(), Finding> {
    let bad = |what: &str, e: String| ("nonfinite", format!("{what}: {e}"));
    if let Ok(text) = model.obj_text(&happy(model)) {
        check_obj(text.as_bytes()).map_err(|e| bad("pose OBJ", e))?;
    }
    let params = GltfParams {
        format: if d.embedded {
            GltfFormat::Embedded
        } else {
            GltfFormat::Binary
        },
        animation: d.animation,
        ..GltfParams::default()
    };
    if let Ok(bytes) = model.gltf_bytes(&params) {
        check_gltf(&bytes, None).map_err(|e| bad("glTF export", e))?;
    }
    Ok(())
}

fn hash(data: &[u8]) -> String {
    blake3::hash(data).to_hex()[..16].to_owned()
}

/// A case run: what it came to, and the CPU and wall-clock milliseconds it took.
struct Run {
    /// `None` when the case was slow (or its thread vanished), else its result under
    /// `catch_unwind`.
    outcome: Option<std::thread::Result<Result<(), Finding>>>,
    ms: f64,
    wall_ms: f64,
}

pub(crate) fn worker(o: &Opts) -> Result<(), String> {
    let clock = Clock::start(true);
    let budget_s = o.minutes * 60.0;
    let seeds = read_seeds(o)?;
    let ctx = Arc::new(context(o)?);
    let message = panic_messages();
    let mut r = Rng(o.seed.wrapping_mul(0x9E37_79B9_7F4A_7C15) | 1);
    let mut stats = Stats::default();
    while clock.cpu() < budget_s {
        let seed = &seeds[r.below(seeds.len())];
        let data = match o.target.as_str() {
            "obj" | "muscles" => mutate_text(&mut r, &String::from_utf8_lossy(seed)),
            "gltf" => mutate_gltf(&mut r, seed),
            _ => mutate_rig(&mut r, seed, ctx.model.as_ref().ok_or("no model")?),
        };
        let e = ext(&o.target, &data);
        std::fs::write(o.out.join(format!("inflight.{e}")), &data).map_err(|e| e.to_string())?;
        let in_face = o.target == "obj" || o.target == "gltf";
        let depth = Depth {
            prep: !in_face || r.chance(4),
            export: in_face && r.chance(128),
            embedded: r.chance(3),
            animation: r.chance(3),
        };
        let run = run_limited(o, &ctx, &data, depth, &mut stats)?;
        record(o, run, &data, e, &message, &mut stats);
        if stats.cases % 500 == 0 {
            stats.print();
        }
    }
    stats.print();
    Ok(())
}

/// The seeds `prepare_seeds` wrote (every file of `DIR/seeds` but `.bin` ones), sorted.
fn read_seeds(o: &Opts) -> Result<Vec<Vec<u8>>, String> {
    let seeds_dir = o.out.join("seeds");
    let mut seeds: Vec<Vec<u8>> = Vec::new();
    for e in std::fs::read_dir(&seeds_dir).map_err(|e| e.to_string())? {
        let p = e.map_err(|e| e.to_string())?.path();
        if p.extension().is_some_and(|x| x != "bin") {
            seeds.push(std::fs::read(&p).map_err(|e| e.to_string())?);
        }
    }
    seeds.sort();
    Ok(seeds)
}

/// The cases' context, with the model `prepare_seeds` saved as `DIR/model.rig` if any.
fn context(o: &Opts) -> Result<Ctx, String> {
    let model = match std::fs::read(o.out.join("model.rig")) {
        Ok(b) => Some(cache::from_bytes(Path::new("model.rig"), &b).map_err(|e| e.to_string())?),
        Err(_) => None,
    };
    Ok(Ctx {
        target: o.target.clone(),
        work: o.out.join("work"),
        element_count: model.as_ref().map_or(0, |m| m.rig.shell.element_count()),
        model,
    })
}

/// Installs a panic hook that keeps the last panic's message (instead of printing it).
fn panic_messages() -> Arc<Mutex<String>> {
    let message = Arc::new(Mutex::new(String::new()));
    let m2 = message.clone();
    std::panic::set_hook(Box::new(move |info| {
        if let Ok(mut m) = m2.lock() {
            *m = info.to_string();
        }
    }));
    message
}

/// Runs one case in its own thread under the memory limit, polling until it ends or is slow;
/// updates the figures.
fn run_limited(
    o: &Opts,
    ctx: &Arc<Ctx>,
    data: &[u8],
    depth: Depth,
    stats: &mut Stats,
) -> Result<Run, String> {
    let base = LIVE.load(Relaxed);
    PEAK.store(base, Relaxed);
    LIMIT.store(base + (o.case_mb << 20), Relaxed);
    let (tx, rx) = std::sync::mpsc::channel();
    let (c2, d2) = (ctx.clone(), data.to_vec());
    let case_clock = Clock::start(true);
    std::thread::Builder::new()
        .stack_size(8 << 20)
        .spawn(move || {
            let res = std::panic::catch_unwind(|| run_case(&c2, &d2, depth));
            let _ = tx.send(res);
        })
        .map_err(|e| e.to_string())?;
    // Poll: slow is over `case_seconds` of CPU, or over `hang_seconds` of wall-clock time.
    let outcome = loop {
        match rx.recv_timeout(Duration::from_millis(50)) {
            Err(std::sync::mpsc::RecvTimeoutError::Timeout) => {
                if case_clock.cpu() > o.case_seconds || case_clock.wall() > o.hang_seconds {
                    break None;
                }
            }
            Ok(r) => break Some(r),
            Err(std::sync::mpsc::RecvTimeoutError::Disconnected) => break None,
        }
    };
    let ms = case_clock.cpu() * 1e3;
    let wall_ms = case_clock.wall() * 1e3;
    LIMIT.store(usize::MAX, Relaxed);
    let peak_mib = (PEAK.load(Relaxed).saturating_sub(base) >> 20) as u64;
    stats.max_peak_mib = stats.max_peak_mib.max(peak_mib);
    stats.max_ms = stats.max_ms.max(ms);
    stats.max_wall_ms = stats.max_wall_ms.max(wall_ms);
    stats.cases += 1;
    Ok(Run {
        outcome,
        ms,
        wall_ms,
    })
}

/// Counts a case's outcome and saves a failing case (`wrong-`, `nonfinite-`, `panic-`,
/// `slow-HASH.EXT` with a `.txt` note); a slow case ends the worker with status 3.
fn record(o: &Opts, run: Run, data: &[u8], e: &str, message: &Mutex<String>, stats: &mut Stats) {
    let Run {
        outcome,
        ms,
        wall_ms,
    } = run;
    let save = |kind: &str, note: &str| {
        let name = format!("{kind}-{}.{e}", hash(data));
        let _ = std::fs::write(o.out.join(&name), data);
        let _ = std::fs::write(o.out.join(format!("{name}.txt")), note);
    };
    if outcome.is_some() && ms > o.slow_seconds * 1e3 {
        stats.slow += 1;
        save(
            "slow",
            &format!(
                "finished in {:.1} s CPU ({:.1} s wall)",
                ms / 1e3,
                wall_ms / 1e3
            ),
        );
    }
    match outcome {
        Some(Ok(Ok(()))) => {}
        Some(Ok(Err((kind, oracle)))) => {
            if kind == "nonfinite" {
                stats.nonfinite += 1;
            } else {
                stats.panics += 1;
            }
            save(kind, &oracle);
        }
        Some(Err(_)) => {
            stats.panics += 1;
            save(
                "panic",
                &message.lock().map(|m| m.clone()).unwrap_or_default(),
            );
        }
        None => {
            save(
                "slow",
                &format!(
                    "over {} s of CPU or {} s of wall-clock time ({:.1} s CPU, {:.1} s wall)",
                    o.case_seconds,
                    o.hang_seconds,
                    ms / 1e3,
                    wall_ms / 1e3
                ),
            );
            stats.print();
            std::process::exit(3);
        }
    }
}
