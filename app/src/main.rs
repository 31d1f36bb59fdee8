//! The `raylab` program: the desktop window (`raylab [SCENE]`) and the command line.
//!
//! - `gui`: the window (egui, drawn with wgpu);
//! - `cli`: the commands (`raylab render`, `chart`, `stability`, `inspect`, `bench`);
//! - `bench`: the throughput benchmarks and what they measure;
//! - `plot`: the PNG charts the commands write;
//! - `io`: files written atomically, images with their provenance, free output names.

mod bench;
mod cli;
mod gui;
mod io;
mod plot;

use clap::Parser;
use cli::{Cli, Command};
use io::stdout::say;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

/// The scene the window opens without an argument: the lecture's.
fn default_scene() -> PathBuf {
    let here = Path::new("assets/scenes/seed.xml");
    if here.exists() {
        return here.to_path_buf();
    }
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../assets/scenes/seed.xml")
}

/// Opens the window on `path` (plotting the error against `reference`, if
/// given); returns when it closes.
fn run_window(path: PathBuf, reference: Option<PathBuf>) -> ExitCode {
    gui::worker_priority::lower_tracer_priority();
    // A scene that cannot be read still opens the window, with the error in
    // it (and on stderr for a terminal); the exit code says it failed.
    let startup = gui::startup::open_or_explain(&path, &default_scene());
    match &startup.problem {
        None => io::output::warn_about_models(&startup.scene),
        Some(problem) => eprintln!("error: {problem}"),
    }
    let (failed, message) = (startup.problem.is_some(), startup.message());
    // Read once, here, so that a bad file fails before the window opens.
    let reference = match reference
        .map(|path| {
            renderer::diagnostics::reference_image::read_exr_rgb(&path).map(|image| (path, image))
        })
        .transpose()
    {
        Ok(reference) => reference,
        Err(error) => {
            eprintln!("error: {error}");
            return ExitCode::from(2);
        }
    };
    let options = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_title("raylab")
            .with_drag_and_drop(true)
            .with_inner_size([1280.0, 800.0]),
        renderer: eframe::Renderer::Wgpu,
        ..Default::default()
    };
    let result = eframe::run_native(
        "raylab",
        options,
        Box::new(move |cc| {
            let mut app = gui::RaylabApp::with_storage(startup.scene, startup.path, cc.storage)
                .with_origin(startup.origin)
                .with_gpu(cc.wgpu_render_state.clone());
            if let Some(message) = message {
                app = app.with_message(message);
            }
            if let Some(dir) = gui::recovery_dir("raylab") {
                app = app.with_recovery(&dir);
            }
            if let Some((path, image)) = reference {
                app.set_reference(path, image);
            }
            Ok(Box::new(app))
        }),
    );
    match result {
        Ok(()) if failed => ExitCode::from(2),
        Ok(()) => ExitCode::SUCCESS,
        Err(error) => {
            eprintln!("error: cannot open the window: {error}");
            ExitCode::FAILURE
        }
    }
}

/// Exit code 0 after `report` for a command that succeeded; the error on
/// stderr and exit code 2 for one that failed.
fn finish<T>(result: anyhow::Result<T>, report: impl FnOnce(T)) -> ExitCode {
    match result {
        Ok(value) => {
            report(value);
            ExitCode::SUCCESS
        }
        Err(error) => {
            eprintln!("error: {error:#}");
            ExitCode::from(2)
        }
    }
}

/// Prints the files a command wrote.
fn report_written(written: Vec<PathBuf>) {
    for path in written {
        say!("wrote {}", path.display());
    }
}

fn main() -> ExitCode {
    let cli = Cli::parse();
    // A developer's choice of narrower lanes that cannot be honoured.
    if let Err(why) = renderer::simd::LaneType::requested() {
        eprintln!("warning: {why}");
    }
    match cli.command {
        None => run_window(cli.scene.unwrap_or_else(default_scene), cli.reference),
        Some(Command::Bench(args)) => finish(cli::bench::run(&args, default_scene()), |()| {}),
        Some(Command::Inspect(args)) => finish(cli::inspect::run(&args), |json| say!("{json}")),
        Some(Command::Stability(args)) => finish(cli::stability::run(&args), report_written),
        Some(Command::Chart(args)) => finish(cli::chart::run(&args), report_written),
        Some(Command::Merge(args)) => finish(cli::merge::run(&args), |path| {
            say!("wrote {}", path.display())
        }),
        Some(Command::ExportMeshes(args)) => finish(cli::export_meshes::run(&args), |index| {
            say!("wrote {}", index.display())
        }),
        Some(Command::Render(args)) => {
            // The user named the file: replacing it is what they asked, said aloud.
            let replacing = args.output.is_file();
            finish(cli::render::run(&args), |rendered| {
                let replaced = if replacing {
                    " (replaced the existing file)"
                } else {
                    ""
                };
                let stopped = if rendered.passes < rendered.requested {
                    format!(
                        " (stopped by Ctrl+C: {} of {} passes)",
                        rendered.passes, rendered.requested
                    )
                } else {
                    String::new()
                };
                say!(
                    "wrote {} in {:.3} s{replaced}{stopped}",
                    args.output.display(),
                    rendered.elapsed.as_secs_f64()
                );
            })
        }
    }
}
