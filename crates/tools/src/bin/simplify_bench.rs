//! Time of the large-face simplification step on the bundled large faces: meshoptimizer on the
//! mesh as written (`large_face::simplify`, before issue 10's invariance work) against
//! `face_simplify::simplify_face` (canonical order, mirrored half for symmetric faces), on the
//! copy the pipeline simplifies (rolled-in parts peeled). Median of 5 runs each.
//!
//! ```text
//! cargo run --release -p facebem-tools --bin simplify_bench
//! ```

use facebem::copy::rolled_in::peel_rolled_in;
use facebem::copy::simplify::simplify_face;
use facebem::copy::{LargeFaceParams, Simplified, simplify};
use std::time::Instant;

fn median_ms(mut run: impl FnMut()) -> f64 {
    let mut t: Vec<f64> = (0..5)
        .map(|_| {
            let t0 = Instant::now();
            run();
            t0.elapsed().as_secs_f64() * 1e3
        })
        .collect();
    t.sort_by(f64::total_cmp);
    t[2]
}

fn main() -> anyhow::Result<()> {
    let dir = std::path::Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../..")).join("assets");
    let params = LargeFaceParams::default();
    println!("| face | triangles simplified | as written | canonical / mirrored | path |");
    println!("|---|---|---|---|---|");
    for name in [
        "ict_narrow_face_dec2500_4loop.obj",
        "leeperrysmith_face_open_4loop.obj",
        "ict_narrow_face_4loop.obj",
    ] {
        let mesh = face_prep::load_face(&dir.join(name))?;
        let whole = Simplified::whole(&mesh.vertices, &mesh.triangles);
        let base = peel_rolled_in(&whole).unwrap_or(whole);
        let old = median_ms(|| {
            let _ = simplify(&base.vertices, &base.triangles, &params);
        });
        let mut path = None;
        let new = median_ms(|| {
            path = simplify_face(&base.vertices, &base.triangles, &params, &[])
                .ok()
                .map(|(_, p)| p);
        });
        println!(
            "| {name} | {} | {old:.0} ms | {new:.0} ms | {path:?} |",
            base.triangles.len()
        );
    }
    Ok(())
}
