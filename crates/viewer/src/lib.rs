//! facebem viewer: an egui + wgpu application to pose a face's muscle rig in real time.
//!
//! The 3D viewport is an egui_wgpu paint callback ([`renderer`]); the pose is a CPU blend of the
//! precomputed [`facebem::MuscleBasis`] ([`posed_mesh`]); files load and rigs build in
//! background [`job`]s so the UI thread never blocks.
//!
//! ```no_run
//! let options = eframe::NativeOptions::default();
//! eframe::run_native(
//!     "facebem",
//!     options,
//!     Box::new(|cc| Ok(Box::new(viewer::ViewerApp::new(cc, viewer::ViewerOptions::default())))),
//! )
//! .unwrap();
//! ```

pub mod app;
pub mod camera;
pub mod export;
pub mod head;
pub mod job;
pub mod muscle_edit;
pub mod overlay;
pub mod picking;
pub mod posed_mesh;
pub mod renderer;
pub mod source;
pub mod surface;

pub use app::{ViewerApp, ViewerOptions};
