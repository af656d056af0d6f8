//! The editor: an eframe window (wgpu backend) on the default head, every layer on
//! sliders, fibres edited on the UV map, an age timeline. The UI thread only draws: every
//! bake runs on the [`worker`] thread.

mod app;
mod document;
pub mod export_ui;
pub mod fields_ui;
mod file_browser;
pub mod files;
mod governor;
pub mod history;
mod map_gpu;
pub mod map_view;
mod notices;
pub mod pick;
pub mod recovery;
mod session;
pub mod timeline;
pub mod viewport;
mod watch;
pub mod worker;

pub use app::{EditorApp, EditorOptions, Pending, soak_failed};

/// Opens the editor window and runs until it is closed.
pub fn run(mut options: EditorOptions) -> anyhow::Result<()> {
    options.cleared_to_panel_colour = true;
    options.launched.get_or_insert_with(std::time::Instant::now);
    let native = eframe::NativeOptions {
        viewport: egui::ViewportBuilder::default()
            .with_inner_size([1280.0, 800.0])
            .with_min_inner_size([640.0, 400.0])
            .with_title("agesim"),
        renderer: eframe::Renderer::Wgpu,
        // A screenshot run must not restore a previous session's layout.
        persist_window: options.screenshot.is_none(),
        ..Default::default()
    };
    eframe::run_native(
        "agesim",
        native,
        Box::new(move |cc| Ok(Box::new(EditorApp::new(cc, options)))),
    )
    .map_err(|e| anyhow::anyhow!("the editor window could not be opened: {e}"))
}
