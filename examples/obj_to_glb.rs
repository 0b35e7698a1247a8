//! Your face mesh in, a GLB with ARKit (and VRM) morph targets out.
//!
//! ```sh
//! cargo run --release --example obj_to_glb -- face.obj face.glb
//! ```
//!
//! Reads an OBJ, glTF or GLB face (front face with four holes: outer contour, two eyes, mouth),
//! builds its muscle rig (a few seconds), and writes a binary glTF whose mesh has one morph
//! target per ARKit blend shape and VRM expression the rig can make, named as those standards
//! name them, in the user's own vertex layout. Blender imports them as shape keys, three.js as
//! `morphTargetDictionary` entries.

use std::path::PathBuf;

use facebem::export::GltfParams;
use facebem::expressions::NameSets;
use facebem::{Control, PipelineParams, build_face_model};

fn main() -> anyhow::Result<()> {
    let mut args = std::env::args_os().skip(1);
    let (Some(input), Some(output)) = (args.next(), args.next()) else {
        anyhow::bail!("usage: obj_to_glb FACE.obj|.gltf|.glb OUT.glb");
    };
    let (input, output) = (PathBuf::from(input), PathBuf::from(output));
    let (mesh, obj_source) = facebem::input::read_face(&input)?;
    let control = Control::new().with_progress(|p| {
        if p.done == p.total {
            eprintln!("{} done", p.stage);
        }
    });
    let mut model = build_face_model(&mesh, &PipelineParams::default(), &control)?;
    // Keeping the source lets the export use the file's own vertex order, UVs and normals.
    model.obj_source = obj_source;
    for warning in model.report.warnings() {
        eprintln!("warning: {warning}");
    }
    let params = GltfParams {
        names: NameSets {
            facebem: false,
            arkit: true,
            vrm: true,
        },
        ..GltfParams::default()
    };
    model.write_gltf(&output, &params)?;
    println!("wrote {}", output.display());
    Ok(())
}
