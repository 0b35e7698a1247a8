//! Prints, per muscle, the largest vertex displacement of a saved rig relative to the face size.
//! `cargo run --release -p viewer --example basis_stats -- FILE.rig`
fn main() -> anyhow::Result<()> {
    let path = std::env::args_os()
        .nth(1)
        .ok_or_else(|| anyhow::anyhow!("usage: basis_stats FILE.rig"))?;
    let model = facebem::cache::load(std::path::Path::new(&path))?;
    let size = model.rig.face_size;
    println!(
        "face size {size:.3}, {} vertices, simplified: {}",
        model.basis.neutral.len(),
        model.simplified.is_some()
    );
    for (id, field) in model
        .basis
        .muscle_ids
        .iter()
        .zip(&model.basis.displacements)
    {
        let (i, max) = field
            .iter()
            .enumerate()
            .map(|(i, d)| (i, d.length()))
            .fold((0, 0.0f64), |a, b| if b.1 > a.1 { b } else { a });
        let mut lengths: Vec<f64> = field.iter().map(|d| d.length()).collect();
        lengths.sort_by(f64::total_cmp);
        let p99 = lengths[lengths.len() * 99 / 100];
        println!(
            "{id:32} max {:.4} (vertex {i}) p99 {:.4}  (× face size)",
            max / size,
            p99 / size
        );
    }
    Ok(())
}
