//! `viewer [FILE] [--preset NAME] [--ready-file PATH] [--exit-after-ready SECONDS]`: the facebem face rig viewer.

use std::path::PathBuf;
use std::time::Duration;

use anyhow::{Context, bail};
use viewer::{ViewerApp, ViewerOptions};

const USAGE: &str = "usage: viewer [FILE.obj|.gltf|.glb|rig] [--preset NAME] [--ready-file PATH] [--exit-after-ready SECONDS]";

fn parse_args() -> anyhow::Result<ViewerOptions> {
    let mut options = ViewerOptions::default();
    let mut args = std::env::args_os().skip(1);
    while let Some(arg) = args.next() {
        match arg.to_str() {
            Some("-h" | "--help") => {
                println!("{USAGE}");
                std::process::exit(0);
            }
            Some("--ready-file") => {
                options.ready_file = Some(PathBuf::from(
                    args.next().context("--ready-file needs a path")?,
                ));
            }
            Some("--exit-after-ready") => {
                let v = args.next().context("--exit-after-ready needs seconds")?;
                let secs: f64 = v
                    .to_str()
                    .and_then(|s| s.parse().ok())
                    .filter(|s: &f64| s.is_finite() && *s >= 0.0)
                    .with_context(|| {
                        format!("--exit-after-ready: not a number of seconds: {v:?}")
                    })?;
                options.exit_after_ready = Some(Duration::from_secs_f64(secs));
            }
            Some("--preset") => {
                let v = args.next().context("--preset needs a name")?;
                let name = v.to_string_lossy().into_owned();
                if facebem::expressions::presets::find(&name).is_none()
                    && facebem::expressions::find(&name).is_none()
                {
                    bail!(
                        "unknown preset {name:?}; known: {}, or an ARKit or VRM 1.0 name",
                        facebem::expressions::presets::names().join(", ")
                    );
                }
                options.preset = Some(name);
            }
            Some(s) if s.starts_with("--") => bail!("unknown option {s}\n{USAGE}"),
            _ if options.open.is_none() => options.open = Some(PathBuf::from(arg)),
            _ => bail!("only one file can be opened\n{USAGE}"),
        }
    }
    Ok(options)
}

fn main() -> anyhow::Result<()> {
    let options = parse_args()?;
    let native = eframe::NativeOptions {
        viewport: eframe::egui::ViewportBuilder::default()
            .with_title("facebem")
            .with_inner_size([1280.0, 800.0]),
        ..Default::default()
    };
    eframe::run_native(
        "facebem",
        native,
        Box::new(move |cc| Ok(Box::new(ViewerApp::new(cc, options)))),
    )
    .map_err(|e| anyhow::anyhow!("the viewer window failed: {e}"))
}
