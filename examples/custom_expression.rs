//! A custom named expression: a recipe over the rig's controls (slider values, negative
//! contracts), posed as an OBJ and exported as one more glTF morph target beside the presets.
//!
//! ```sh
//! cargo run --release --example custom_expression -- smirk.obj smirk.glb
//! ```

use facebem::Control;
use facebem::export::GltfParams;
use facebem::expressions::presets::{self, Preset};

/// A one-sided smile with the opposite brow raised.
const SMIRK: Preset = Preset {
    name: "smirk",
    action_units: "AU12L + AU2R",
    description: "left lip corner up, right brow raised",
    sliders: &[
        ("zygomaticus_major_l", -0.9),
        ("levator_labii_superioris_l", -0.2),
        ("frontalis_r", -0.6),
    ],
};

fn main() -> anyhow::Result<()> {
    let mut args = std::env::args_os().skip(1);
    let obj = args.next().unwrap_or_else(|| "smirk.obj".into());
    let glb = args.next().unwrap_or_else(|| "smirk.glb".into());
    let (model, _) = facebem::input::default_model(None, &Control::new())?;
    // Controls the recipe names but the rig lacks would stay 0: say so.
    for (id, _) in SMIRK.sliders {
        if model.basis.muscle_index(id).is_none() {
            eprintln!("warning: this rig has no control {id}");
        }
    }
    let sliders = SMIRK.sliders_for(model.muscle_ids());
    model.write_obj(obj.as_ref(), &sliders)?;
    let mut all = presets::ALL.to_vec();
    all.push(SMIRK);
    let params = GltfParams {
        presets: all,
        ..GltfParams::default()
    };
    model.write_gltf(glb.as_ref(), &params)?;
    println!(
        "wrote {} and {}",
        obj.to_string_lossy(),
        glb.to_string_lossy()
    );
    Ok(())
}
