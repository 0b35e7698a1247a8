//! Embedding the rig in a render loop: build (or load) a face's muscle basis once, then pose it
//! every frame from slider values — a weighted sum of precomputed per-vertex responses, no
//! solve at run time.
//!
//! ```sh
//! cargo run --release --example render_loop            # the bundled default face
//! cargo run --release --example render_loop -- face.rig
//! ```

use facebem::Control;
use facebem::expressions::sliders_for_name;
use glam::DVec3;

fn main() -> anyhow::Result<()> {
    let model = match std::env::args_os().nth(1) {
        Some(rig) => facebem::cache::load(rig.as_ref())?,
        None => facebem::input::default_model(None, &Control::new())?.0,
    };
    let ids = model.muscle_ids().to_vec();
    let (smile, _) = sliders_for_name("mouthSmileLeft", &ids)?;
    let (blink, _) = sliders_for_name("eyeBlinkLeft", &ids)?;
    // One buffer reused every frame: pose_into writes v0 + Σ s_k D_k into it.
    let mut posed: Vec<DVec3> = Vec::new();
    let frames = 60;
    for frame in 0..=frames {
        let t = frame as f64 / frames as f64;
        // A smile that builds up while the eye blinks once.
        let weight_blink = (std::f64::consts::PI * t).sin();
        let sliders: Vec<f64> = smile
            .iter()
            .zip(&blink)
            .map(|(s, b)| t * s + weight_blink * b)
            .collect();
        model.basis.pose_into(&sliders, &mut posed)?;
        // Hand `posed` to your renderer here; this example prints how far the face moved.
        if frame % 15 == 0 {
            let largest_mm = posed
                .iter()
                .zip(&model.basis.neutral)
                .map(|(p, n)| (*p - *n).length())
                .fold(0.0, f64::max)
                * model.rig.mm_per_unit();
            println!("frame {frame:2}: largest motion {largest_mm:.1} mm");
        }
    }
    Ok(())
}
