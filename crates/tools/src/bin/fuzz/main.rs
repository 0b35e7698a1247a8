//! Structure-aware mutation fuzzer of facebem's input readers, on stable Rust.
//!
//! ```text
//! cargo run --release -p facebem-tools --bin fuzz -- --minutes 30 --target obj|gltf|rig|muscles \
//!     [--out DIR] [--seed N] [--case-seconds 5] [--hang-seconds 60] [--case-mb 500]
//! ```
//!
//! Time is CPU time on Linux (from `/proc`): `--minutes` is the workers' CPU time, and a case
//! is slow when it uses more than `--case-seconds` of CPU, so a loaded machine does not turn
//! starvation into findings; a case that blocks without using CPU (a FIFO, a lock) is caught
//! by the wall-clock `--hang-seconds`. Workers run with `RAYON_NUM_THREADS=1` unless it is set,
//! i.e. on one core. Elsewhere both fall back to wall-clock time.
//!
//! A supervisor process runs worker processes (this binary with `--worker`) until the time is
//! up. A worker mutates the bundled MediaPipe face as the target kind (OBJ text lines and
//! numbers; glTF JSON fields, URIs and GLB bytes; rig payloads with recomputed checksums, and
//! decoded rigs with one field changed; muscle file lines and numbers) and runs each case in a
//! thread under `catch_unwind`, with a time limit and a memory limit (a counting allocator that
//! refuses allocations beyond it, which aborts the worker). Before each case the input is written
//! to `DIR/inflight.EXT`; a panic is saved as `DIR/panic-HASH.EXT` (+ `.txt` message), a case
//! over the time limit as `DIR/slow-HASH.EXT` (the worker then exits and is restarted), and an
//! abort (memory limit, stack overflow) as `DIR/crash-N.EXT` by the supervisor. Valid meshes
//! also go through the rig prep (`facebem::prep_rig`), valid rigs through posing and both
//! exports, valid muscle files through `FaceRig::with_muscles`. The summary (cases, failures,
//! slowest case, largest per-case peak of live heap) is printed and written to
//! `DIR/summary.txt`. Every finding belongs in `tests/bad_inputs/` with its expected error.

mod alloc;
mod mutate;
mod opts;
mod seeds;
mod supervisor;
mod worker;

fn main() {
    let result = opts::parse_opts().and_then(|o| {
        if o.worker {
            worker::worker(&o)
        } else {
            supervisor::supervisor(&o)
        }
    });
    if let Err(e) = result {
        eprintln!("fuzz: {e}");
        std::process::exit(1);
    }
}
