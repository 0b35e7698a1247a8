//! Issue 32's table: for every ARKit target, the cosine of facebem's displacement field with
//! ICT-FaceKit's captured one, on the narrow face rigged alone and on the whole head
//! ([`facebem::report::captures::head_and_narrow_face`]), with the largest motions in mm.
//!
//! ```text
//! cargo run --release -p facebem-tools --bin head_cosines
//! ```

use std::path::Path;

fn main() -> anyhow::Result<()> {
    let root = Path::new(concat!(env!("CARGO_MANIFEST_DIR"), "/../.."));
    let rows = facebem::report::captures::head_and_narrow_face(root)
        .map_err(|e| anyhow::anyhow!("{e}"))?;
    println!("| target | narrow face | whole head | head − narrow | head max mm (captured) |");
    println!("|---|---|---|---|---|");
    let mut worse = 0;
    for r in &rows {
        let diff = r.narrow_face.map(|n| r.whole_head - n);
        if diff.is_some_and(|d| d < -0.05) {
            worse += 1;
        }
        println!(
            "| {} | {} | {:.2} | {} | {:.1} ({:.1}) |",
            r.name,
            r.narrow_face.map_or("—".into(), |x| format!("{x:.2}")),
            r.whole_head,
            diff.map_or("—".into(), |x| format!("{x:+.2}")),
            r.head_largest_mm,
            r.captured_largest_mm
        );
    }
    println!(
        "\n{worse} of {} targets lower on the whole head than on the narrow face by more than 0.05",
        rows.len()
    );
    Ok(())
}
