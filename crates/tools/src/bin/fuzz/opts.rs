//! Command-line options and the CPU-time clock.

use std::path::PathBuf;
use std::time::Instant;

#[derive(Clone)]
pub(crate) struct Opts {
    pub(crate) minutes: f64,
    pub(crate) target: String,
    pub(crate) out: PathBuf,
    pub(crate) seed: u64,
    pub(crate) case_seconds: f64,
    pub(crate) hang_seconds: f64,
    /// In-process targets: the per-case heap limit; `cli`: the address-space limit of each
    /// `facebem` run (`ulimit -v`).
    pub(crate) case_mb: usize,
    /// A case that finishes but uses more CPU seconds than this is a finding ("slow").
    pub(crate) slow_seconds: f64,
    /// The `facebem` binary of the `cli` target (default: next to this one).
    pub(crate) facebem: Option<PathBuf>,
    pub(crate) worker: bool,
}

/// The targets, in-process ones first.
pub(crate) const TARGETS: [&str; 5] = ["obj", "gltf", "rig", "muscles", "cli"];

pub(crate) fn parse_opts() -> Result<Opts, String> {
    let mut o = Opts {
        minutes: 1.0,
        target: "obj".into(),
        out: PathBuf::new(),
        seed: 1,
        case_seconds: f64::NAN,
        hang_seconds: 60.0,
        case_mb: 0,
        slow_seconds: 10.0,
        facebem: None,
        worker: false,
    };
    let mut args = std::env::args().skip(1);
    while let Some(a) = args.next() {
        let mut val = || args.next().ok_or(format!("{a} needs a value"));
        match a.as_str() {
            "--minutes" => o.minutes = val()?.parse().map_err(|e| format!("--minutes: {e}"))?,
            "--target" => o.target = val()?,
            "--out" => o.out = PathBuf::from(val()?),
            "--seed" => o.seed = val()?.parse().map_err(|e| format!("--seed: {e}"))?,
            "--case-seconds" => o.case_seconds = val()?.parse().map_err(|e| format!("{e}"))?,
            "--hang-seconds" => o.hang_seconds = val()?.parse().map_err(|e| format!("{e}"))?,
            "--case-mb" => o.case_mb = val()?.parse().map_err(|e| format!("{e}"))?,
            "--slow-seconds" => o.slow_seconds = val()?.parse().map_err(|e| format!("{e}"))?,
            "--facebem" => o.facebem = Some(PathBuf::from(val()?)),
            "--worker" => o.worker = true,
            other => return Err(format!("unknown argument {other}")),
        }
    }
    if !TARGETS.contains(&o.target.as_str()) {
        return Err(format!(
            "--target {} (obj, gltf, rig, muscles or cli)",
            o.target
        ));
    }
    let cli = o.target == "cli";
    if o.case_seconds.is_nan() {
        // A `facebem` run is a whole program (a rig of the bundled face takes ~2.5 s).
        o.case_seconds = if cli { 30.0 } else { 5.0 };
    }
    if o.case_mb == 0 {
        o.case_mb = if cli { 4096 } else { 500 };
    }
    if o.out.as_os_str().is_empty() {
        o.out = std::env::temp_dir().join(format!("facebem-fuzz-{}", o.target));
    }
    Ok(o)
}

/// CPU seconds of this process (`self_` true: its own threads) or of its waited-for children
/// (`self_` false), from `/proc/self/stat` (clock ticks of 1/100 s, Linux's USER_HZ).
fn cpu_seconds(self_: bool) -> Option<f64> {
    stat_cpu_seconds("/proc/self/stat", self_)
}

/// CPU seconds of the running process `pid` (all its threads), from `/proc/PID/stat`.
pub(crate) fn process_cpu_seconds(pid: u32) -> Option<f64> {
    stat_cpu_seconds(&format!("/proc/{pid}/stat"), true)
}

fn stat_cpu_seconds(path: &str, self_: bool) -> Option<f64> {
    let stat = std::fs::read_to_string(path).ok()?;
    // Fields after the command name "(…)": state is field 3, utime 14, stime 15, cutime 16,
    // cstime 17 (proc(5)).
    let rest = &stat[stat.rfind(')')? + 2..];
    let f: Vec<&str> = rest.split(' ').collect();
    let (a, b) = if self_ { (11, 12) } else { (13, 14) };
    let ticks = f.get(a)?.parse::<f64>().ok()? + f.get(b)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

/// A clock of CPU seconds ([`cpu_seconds`]), or of wall-clock seconds where `/proc` is missing.
pub(crate) struct Clock {
    self_: bool,
    cpu0: Option<f64>,
    wall0: Instant,
}

impl Clock {
    pub(crate) fn start(self_: bool) -> Clock {
        Clock {
            self_,
            cpu0: cpu_seconds(self_),
            wall0: Instant::now(),
        }
    }
    /// CPU seconds since `start` (wall-clock seconds without `/proc`).
    pub(crate) fn cpu(&self) -> f64 {
        match (self.cpu0, cpu_seconds(self.self_)) {
            (Some(a), Some(b)) => b - a,
            _ => self.wall(),
        }
    }
    pub(crate) fn wall(&self) -> f64 {
        self.wall0.elapsed().as_secs_f64()
    }
}
