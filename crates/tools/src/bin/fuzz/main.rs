//! Structure-aware mutation fuzzer of facebem's input readers and of the `facebem` command
//! line, on stable Rust.
//!
//! ```text
//! cargo run --release -p facebem-tools --bin fuzz -- --minutes 30 \
//!     --target obj|gltf|rig|muscles|cli [--out DIR] [--seed N] [--case-seconds S] \
//!     [--hang-seconds 60] [--slow-seconds 10] [--case-mb M] [--facebem PATH]
//! ```
//!
//! Time is CPU time on Linux (from `/proc`): `--minutes` is the workers' CPU time (with the
//! `facebem` runs of the cli target), and a case is a timeout when it uses more than
//! `--case-seconds` of CPU (5 s in process, 30 s for a cli run), so a loaded machine does not
//! turn starvation into findings; a case that blocks without using CPU (a FIFO, a lock) is
//! caught by the wall-clock `--hang-seconds`. A case that finishes after more than
//! `--slow-seconds` of CPU is a "slow" finding. Workers run with `RAYON_NUM_THREADS=1` unless
//! it is set, i.e. on one core. Elsewhere both fall back to wall-clock time.
//!
//! A supervisor process runs worker processes (this binary with `--worker`) until the time is
//! up. A worker mutates the bundled MediaPipe face as the target kind (OBJ text lines and
//! numbers; glTF JSON fields, URIs and GLB bytes; rig payloads with recomputed checksums, and
//! decoded rigs with one field changed; muscle file lines and numbers) and runs each case in a
//! thread under `catch_unwind`, with a time limit and a memory limit (a counting allocator that
//! refuses allocations beyond `--case-mb`, 500 MiB, which aborts the worker). Before each case
//! the input is written to `DIR/inflight.EXT`; a panic is saved as `DIR/panic-HASH.EXT` (+
//! `.txt` message), a case over the time limit as `DIR/slow-HASH.EXT` (the worker then exits
//! and is restarted), and an abort (memory limit, stack overflow) as `DIR/crash-N.EXT` by the
//! supervisor. Valid meshes also go through the rig prep (`facebem::prep_rig`), and one in 128
//! is rigged cheaply (on a copy of at most 200 triangles) and exported; valid rigs are posed
//! and exported; valid muscle files go through `FaceRig::with_muscles` and are written again.
//! Every export is checked for non-finite numbers (`nonfinite-HASH.EXT`, [`output_check`]).
//!
//! The `cli` target runs the `facebem` binary next to this one (build it with `cargo build
//! --release -p facebem-cli`) on hostile command lines, each in a fresh folder with a time and
//! an address-space limit (`--case-mb`, 4096 MiB), and checks its exit status, its one-line
//! errors and every file it writes; see [`cli_target`].
//!
//! The summary (cases; panics, aborts, timeouts, slow cases, non-finite outputs, multi-line
//! errors; slowest case, largest per-case peak of live heap) is printed and written to
//! `DIR/summary.txt`. Every finding belongs in `tests/bad_inputs/` with its expected error.

mod alloc;
mod cli_args;
mod cli_target;
mod mutate;
mod opts;
mod output_check;
mod seeds;
mod stats;
mod supervisor;
mod worker;

fn main() {
    let result = opts::parse_opts().and_then(|o| {
        if o.worker && o.target == "cli" {
            cli_target::worker(&o)
        } else if o.worker {
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
