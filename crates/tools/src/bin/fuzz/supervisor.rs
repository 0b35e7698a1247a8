//! The supervisor: runs worker processes until the time is up, saves what killed them, and
//! sums up.

use std::path::PathBuf;

use crate::opts::{Clock, Opts};
use crate::seeds::prepare_seeds;
use crate::stats::Stats;

/// One worker run with the options of `o`, starting at `seed`, for `minutes` of CPU time.
fn worker_command(o: &Opts, exe: &PathBuf, minutes: f64, seed: u64) -> std::process::Command {
    let mut cmd = std::process::Command::new(exe);
    if std::env::var_os("RAYON_NUM_THREADS").is_none() {
        cmd.env("RAYON_NUM_THREADS", "1");
    }
    cmd.args(["--worker", "--target", &o.target, "--out"])
        .arg(&o.out)
        .args([
            "--minutes",
            &minutes.to_string(),
            "--seed",
            &seed.to_string(),
        ])
        .args([
            "--case-seconds",
            &o.case_seconds.to_string(),
            "--hang-seconds",
            &o.hang_seconds.to_string(),
            "--case-mb",
            &o.case_mb.to_string(),
            "--slow-seconds",
            &o.slow_seconds.to_string(),
        ]);
    if let Some(f) = &o.facebem {
        cmd.arg("--facebem").arg(f);
    }
    cmd.stderr(std::process::Stdio::inherit());
    cmd
}

pub(crate) fn supervisor(o: &Opts) -> Result<(), String> {
    if o.target == "cli" {
        crate::cli_target::prepare(o)?;
    } else {
        prepare_seeds(o)?;
    }
    // The workers' CPU time (this process's waited-for children, and theirs: the `facebem`
    // runs of the cli target), wall-clock without /proc.
    let clock = Clock::start(false);
    let budget_s = o.minutes * 60.0;
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let mut total = Stats::default();
    let mut restarts = 0u64;
    while clock.cpu() < budget_s {
        let left = (budget_s - clock.cpu()) / 60.0;
        let out = worker_command(o, &exe, left, o.seed + restarts)
            .output()
            .map_err(|e| e.to_string())?;
        restarts += 1;
        if let Some(s) = Stats::from_output(&String::from_utf8_lossy(&out.stdout)) {
            total.add(&s);
        }
        match out.status.code() {
            Some(0) => {}
            Some(3) => total.timeouts += 1,
            _ => {
                total.aborts += 1;
                for e in ["obj", "gltf", "glb", "rig", "muscles", "cli"] {
                    let inflight = o.out.join(format!("inflight.{e}"));
                    if inflight.exists() {
                        let to = o.out.join(format!("crash-{}.{e}", total.aborts));
                        let _ = std::fs::rename(&inflight, &to);
                        eprintln!(
                            "worker died ({}); input saved as {}",
                            out.status,
                            to.display()
                        );
                    }
                }
            }
        }
        if o.target == "cli" && out.status.code() == Some(0) {
            // A cli worker runs its whole budget unless it dies.
            break;
        }
    }
    let summary = summary(o, &clock, &total, restarts);
    print!("{summary}");
    let _ = std::fs::write(o.out.join("summary.txt"), &summary);
    if total.findings() > 0 {
        return Err("findings: see above".into());
    }
    Ok(())
}

fn summary(o: &Opts, clock: &Clock, t: &Stats, restarts: u64) -> String {
    let cpu = clock.cpu();
    let limit = if o.target == "cli" {
        format!("{} MiB of address space", o.case_mb)
    } else {
        let extra = if o.target == "obj" || o.target == "gltf" {
            " (+2048 while a face is rigged)"
        } else {
            ""
        };
        format!(
            "{} MiB of heap{extra}; largest per-case peak {} MiB",
            o.case_mb, t.max_peak_mib
        )
    };
    format!(
        "target {}: {:.1} CPU min ({:.1} min wall), {} cases ({:.1}/CPU s, {:.0} ms CPU each on \
         average), {restarts} worker runs\n  panics or wrong results {}, aborts {}, timeouts \
         (over {} s CPU / {} s wall) {}, slow (over {} s CPU) {}, non-finite outputs {}, \
         multi-line errors {}\n  slowest case {:.0} ms CPU ({:.0} ms wall); per-case limit {limit}\
         \n  findings in {}\n",
        o.target,
        cpu / 60.0,
        clock.wall() / 60.0,
        t.cases,
        t.cases as f64 / cpu.max(1e-9),
        cpu * 1e3 / (t.cases.max(1) as f64),
        t.panics,
        t.aborts,
        o.case_seconds,
        o.hang_seconds,
        t.timeouts,
        o.slow_seconds,
        t.slow,
        t.nonfinite,
        t.multiline,
        t.max_ms,
        t.max_wall_ms,
        o.out.display()
    )
}
