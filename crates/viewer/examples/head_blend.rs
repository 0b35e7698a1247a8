//! Measures what a slider change costs the viewer on a whole head (ICT-FaceKit's, 26 719
//! vertices, `assets/heads/`): the CPU blend of the head's fields, and the blend with the lids
//! kept on the eyeballs (`EyeContact::apply` on the mix), over 40 mixes of a blink, a squint
//! and a smile at random weights. The head's rig is computed first (into a temporary cache).
//!
//! `cargo run --release -p viewer --example head_blend [HEAD]`

use std::time::Instant;

use viewer::head::{HeadSource, display_basis};
use viewer::posed_mesh::PosedMesh;

fn main() -> anyhow::Result<()> {
    let path = std::env::args().nth(1).map_or_else(
        || {
            std::path::Path::new(env!("CARGO_MANIFEST_DIR"))
                .join("../../assets/heads/ict_generic_head.obj")
        },
        std::path::PathBuf::from,
    );
    let whole = facebem::input::heads::WholeFile::read(&path)
        .ok_or_else(|| anyhow::anyhow!("{}: not a head", path.display()))?;
    let source = HeadSource::new(&path, whole).map_err(anyhow::Error::msg)?;
    let cache = tempfile::tempdir()?;
    let started = Instant::now();
    let rig = source
        .rig(&Default::default(), cache.path(), &facebem::Control::new())
        .map_err(anyhow::Error::msg)?;
    println!(
        "{}: rigged and carried in {:.1} s",
        path.display(),
        started.elapsed().as_secs_f64()
    );
    let basis = display_basis(&rig.head);
    let index = |id: &str| basis.muscle_ids.iter().position(|m| m == id);
    let pressing = [
        "orbicularis_oculi_palpebral_l",
        "orbicularis_oculi_orbital_l",
        "zygomaticus_major_l",
    ];
    let mut sliders = vec![0.0; basis.muscle_count()];
    let (mut plain, mut contact) = (Vec::new(), Vec::new());
    let mut mesh = PosedMesh::default();
    let mut seed = 0x9E37_79B9u32;
    for _ in 0..40 {
        for id in pressing {
            seed ^= seed << 13;
            seed ^= seed >> 17;
            seed ^= seed << 5;
            if let Some(k) = index(id) {
                sliders[k] = -f64::from(seed % 1000) / 1000.0;
            }
        }
        let t = Instant::now();
        mesh.update(&basis, &sliders)?;
        plain.push(t.elapsed().as_secs_f64() * 1e3);
        let t = Instant::now();
        mesh.update_with_contact(&basis, &sliders, Some(&rig.head.contact))?;
        contact.push(t.elapsed().as_secs_f64() * 1e3);
    }
    let median = |v: &mut Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v[v.len() / 2]
    };
    println!(
        "{} vertices, {} sliders: blend {:.2} ms, blend + lids on the eyes {:.2} ms (medians of 40)",
        basis.neutral.len(),
        basis.muscle_count(),
        median(&mut plain),
        median(&mut contact)
    );
    Ok(())
}
