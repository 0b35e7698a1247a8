//! The supervisor: runs worker processes until the time is up, saves what killed them, and
//! sums up.

use crate::opts::{Clock, Opts};
use crate::seeds::prepare_seeds;

pub(crate) fn supervisor(o: &Opts) -> Result<(), String> {
    prepare_seeds(o)?;
    // The workers' CPU time (this process's waited-for children), wall-clock without /proc.
    let clock = Clock::start(false);
    let budget_s = o.minutes * 60.0;
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let (mut cases, mut panics, mut max_ms, mut max_peak) = (0u64, 0u64, 0f64, 0u64);
    let mut max_wall_ms = 0f64;
    let (mut crashes, mut slow, mut restarts) = (0u64, 0u64, 0u64);
    while clock.cpu() < budget_s {
        let left = (budget_s - clock.cpu()) / 60.0;
        let mut cmd = std::process::Command::new(&exe);
        if std::env::var_os("RAYON_NUM_THREADS").is_none() {
            cmd.env("RAYON_NUM_THREADS", "1");
        }
        let out = cmd
            .args(["--worker", "--target", &o.target, "--out"])
            .arg(&o.out)
            .args([
                "--minutes",
                &left.to_string(),
                "--seed",
                &(o.seed + restarts).to_string(),
            ])
            .args([
                "--case-seconds",
                &o.case_seconds.to_string(),
                "--hang-seconds",
                &o.hang_seconds.to_string(),
                "--case-mb",
                &o.case_mb.to_string(),
            ])
            .stderr(std::process::Stdio::inherit())
            .output()
            .map_err(|e| e.to_string())?;
        restarts += 1;
        let stdout = String::from_utf8_lossy(&out.stdout);
        if let Some(last) = stdout.lines().rev().find(|l| l.starts_with("STATS ")) {
            let f: Vec<f64> = last
                .split(' ')
                .skip(1)
                .filter_map(|x| x.parse().ok())
                .collect();
            if f.len() == 5 {
                cases += f[0] as u64;
                panics += f[1] as u64;
                max_ms = max_ms.max(f[2]);
                max_peak = max_peak.max(f[3] as u64);
                max_wall_ms = max_wall_ms.max(f[4]);
            }
        }
        match out.status.code() {
            Some(0) => {}
            Some(3) => slow += 1,
            _ => {
                crashes += 1;
                for e in ["obj", "gltf", "glb", "rig", "muscles"] {
                    let inflight = o.out.join(format!("inflight.{e}"));
                    if inflight.exists() {
                        let to = o.out.join(format!("crash-{crashes}.{e}"));
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
    }
    let summary = format!(
        "target {}: {:.1} CPU min ({:.1} min wall), {cases} cases ({:.0}/CPU s), {panics} panics \
         or wrong results, {crashes} aborts, {slow} cases over {} s CPU / {} s wall, slowest case \
         {max_ms:.0} ms CPU ({max_wall_ms:.0} ms wall), largest per-case heap peak {max_peak} MiB \
         (limit {} MiB), {restarts} worker runs; findings in {}\n",
        o.target,
        clock.cpu() / 60.0,
        clock.wall() / 60.0,
        cases as f64 / clock.cpu().max(1e-9),
        o.case_seconds,
        o.hang_seconds,
        o.case_mb,
        o.out.display()
    );
    print!("{summary}");
    let _ = std::fs::write(o.out.join("summary.txt"), &summary);
    if panics + crashes + slow > 0 {
        return Err("findings: see above".into());
    }
    Ok(())
}
