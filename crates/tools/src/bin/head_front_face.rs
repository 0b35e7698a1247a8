//! Writes the front face that `face_prep::parts::front_face` cuts from a whole head (issue 32)
//! as an OBJ, to look at it or rig it (`facebem rig`, `facebem sheet`).
//!
//! ```text
//! cargo run --release -p facebem-tools --bin head_front_face -- head.obj face.obj
//! ```

use std::fmt::Write;
use std::path::PathBuf;

use anyhow::{Context, bail};
use face_prep::parts::{Scene, find_parts, front_face};

fn main() -> anyhow::Result<()> {
    let args: Vec<PathBuf> = std::env::args_os().skip(1).map(PathBuf::from).collect();
    let [head, out] = args.as_slice() else {
        bail!("usage: head_front_face HEAD OUT.obj");
    };
    let scene = Scene::read(head, &face_prep::InputLimits::default())?;
    let parts = find_parts(&scene)?;
    let face = front_face(&scene, &parts)?;
    let mut text = format!("# front face cut from {}\n", head.display());
    for p in &face.positions {
        let _ = writeln!(text, "v {} {} {}", p.x, p.y, p.z);
    }
    for t in &face.triangles {
        let _ = writeln!(text, "f {} {} {}", t[0] + 1, t[1] + 1, t[2] + 1);
    }
    face_prep::atomic_write::write_atomic(out, text.as_bytes())
        .with_context(|| format!("cannot write {}", out.display()))?;
    println!(
        "{}: {} vertices, {} triangles",
        out.display(),
        face.positions.len(),
        face.triangles.len()
    );
    Ok(())
}
