//! A worker process: mutates the seeds and runs each case in a thread under `catch_unwind`,
//! with a time limit and a memory limit, saving what fails.

use std::path::{Path, PathBuf};
use std::sync::atomic::Ordering::Relaxed;
use std::sync::{Arc, Mutex};
use std::time::Duration;

use facebem::face_prep::{self, FaceMesh, muscle_file};
use facebem::{FaceModel, PipelineParams, cache};

use crate::alloc::{LIMIT, LIVE, PEAK};
use crate::mutate::{Rng, mutate_gltf, mutate_rig, mutate_text};
use crate::opts::{Clock, Opts};
use crate::seeds::ext;

struct Ctx {
    target: String,
    work: PathBuf,
    model: Option<FaceModel>,
    element_count: usize,
}

/// Runs one case; `Err` is an oracle failure (a wrong result rather than a refusal).
fn run_case(ctx: &Ctx, data: &[u8], deep: bool) -> Result<(), String> {
    let params = PipelineParams::default();
    let prep = |mesh: &FaceMesh| {
        if deep && let Ok(rig) = facebem::prep_rig(mesh, &params) {
            let _ = facebem::report::describe::describe(Path::new("x"), mesh, &rig, None);
        }
    };
    match ctx.target.as_str() {
        "obj" => {
            if let Ok(mesh) = FaceMesh::from_obj_bytes(data, &Default::default()) {
                prep(&mesh);
            }
        }
        "gltf" => {
            let path = ctx.work.join(format!("case.{}", ext("gltf", data)));
            std::fs::write(&path, data).map_err(|e| e.to_string())?;
            if let Ok(mesh) = face_prep::load_face(&path) {
                prep(&mesh);
            }
        }
        "rig" => {
            if let Ok(model) = cache::from_bytes(Path::new("case.rig"), data) {
                let sliders = facebem::expressions::presets::find("happy")
                    .map(|p| p.sliders_for(model.muscle_ids()))
                    .unwrap_or_default();
                if let Ok(posed) = model.pose(&sliders)
                    && posed.iter().any(|p| !p.is_finite())
                {
                    return Err("a validated rig posed to non-finite coordinates".into());
                }
                let _ = model.obj_text(&sliders);
                let _ = facebem::export::export_gltf(&model.basis, &Default::default());
            }
        }
        _ => {
            let text = String::from_utf8_lossy(data);
            if let Ok(list) = muscle_file::read_str(&text, ctx.element_count)
                && let Some(m) = &ctx.model
            {
                let _ = m.rig.clone().with_muscles(list);
            }
        }
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
    outcome: Option<std::thread::Result<Result<(), String>>>,
    ms: f64,
    wall_ms: f64,
}

/// The figures a worker reports to the supervisor (a `STATS` line on stdout).
#[derive(Default)]
struct Stats {
    cases: u64,
    panics: u64,
    max_ms: f64,
    max_wall_ms: f64,
    max_peak: usize,
}

impl Stats {
    fn print(&self) {
        let Stats {
            cases,
            panics,
            max_ms,
            max_wall_ms,
            max_peak,
        } = self;
        println!(
            "STATS {cases} {panics} {max_ms:.1} {} {max_wall_ms:.1}",
            max_peak >> 20
        );
    }
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
        let deep = o.target != "obj" && o.target != "gltf" || r.chance(4);
        let run = run_limited(o, &ctx, &data, deep, &mut stats)?;
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
    deep: bool,
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
            let res = std::panic::catch_unwind(|| run_case(&c2, &d2, deep));
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
    stats.max_peak = stats.max_peak.max(PEAK.load(Relaxed).saturating_sub(base));
    stats.max_ms = stats.max_ms.max(ms);
    stats.max_wall_ms = stats.max_wall_ms.max(wall_ms);
    stats.cases += 1;
    Ok(Run {
        outcome,
        ms,
        wall_ms,
    })
}

/// Counts a case's outcome and saves a failing case (`wrong-`, `panic-`, `slow-HASH.EXT` with
/// a `.txt` note); a slow case ends the worker with status 3.
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
    match outcome {
        Some(Ok(Ok(()))) => {}
        Some(Ok(Err(oracle))) => {
            stats.panics += 1;
            save("wrong", &oracle);
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
