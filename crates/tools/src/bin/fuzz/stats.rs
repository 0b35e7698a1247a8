//! The figures a worker reports to the supervisor: a `STATS` line on its standard output
//! (cumulative, the last one counts).

/// A worker's figures so far.
#[derive(Clone, Copy, Default)]
pub(crate) struct Stats {
    pub(crate) cases: u64,
    /// Panics, and wrong results of an oracle (in-process targets); exit status 101 (cli).
    pub(crate) panics: u64,
    /// Slowest case, CPU milliseconds.
    pub(crate) max_ms: f64,
    /// Largest per-case peak of live heap, MiB (in-process targets).
    pub(crate) max_peak_mib: u64,
    /// Slowest case, wall-clock milliseconds.
    pub(crate) max_wall_ms: f64,
    /// Cases ended by a signal or an unexpected exit status (cli; the supervisor counts the
    /// in-process workers that die).
    pub(crate) aborts: u64,
    /// Cases over the per-case time limit (cli; the supervisor counts in-process ones).
    pub(crate) timeouts: u64,
    /// Cases that finished but took more than `--slow-seconds` of CPU.
    pub(crate) slow: u64,
    /// Outputs with a non-finite number (or malformed, or not re-opening).
    pub(crate) nonfinite: u64,
    /// Failures whose standard error is not one `error:` line after `warning:` lines (cli).
    pub(crate) multiline: u64,
}

impl Stats {
    pub(crate) fn print(&self) {
        let s = self;
        println!(
            "STATS {} {} {:.1} {} {:.1} {} {} {} {} {}",
            s.cases,
            s.panics,
            s.max_ms,
            s.max_peak_mib,
            s.max_wall_ms,
            s.aborts,
            s.timeouts,
            s.slow,
            s.nonfinite,
            s.multiline
        );
    }

    /// The figures of the last `STATS` line of a worker's output.
    pub(crate) fn from_output(stdout: &str) -> Option<Stats> {
        let last = stdout.lines().rev().find(|l| l.starts_with("STATS "))?;
        let f: Vec<f64> = last
            .split(' ')
            .skip(1)
            .filter_map(|x| x.parse().ok())
            .collect();
        if f.len() != 10 {
            return None;
        }
        let n = |i: usize| f[i] as u64;
        Some(Stats {
            cases: n(0),
            panics: n(1),
            max_ms: f[2],
            max_peak_mib: n(3),
            max_wall_ms: f[4],
            aborts: n(5),
            timeouts: n(6),
            slow: n(7),
            nonfinite: n(8),
            multiline: n(9),
        })
    }

    /// Adds a worker's figures (counts summed, maxima kept).
    pub(crate) fn add(&mut self, o: &Stats) {
        self.cases += o.cases;
        self.panics += o.panics;
        self.max_ms = self.max_ms.max(o.max_ms);
        self.max_peak_mib = self.max_peak_mib.max(o.max_peak_mib);
        self.max_wall_ms = self.max_wall_ms.max(o.max_wall_ms);
        self.aborts += o.aborts;
        self.timeouts += o.timeouts;
        self.slow += o.slow;
        self.nonfinite += o.nonfinite;
        self.multiline += o.multiline;
    }

    pub(crate) fn findings(&self) -> u64 {
        self.panics + self.aborts + self.timeouts + self.slow + self.nonfinite + self.multiline
    }
}
