//! The editor's app: the document (a [`Project`] and its edited wrinkle files), the panels,
//! and the bake worker that turns every edit into maps off the UI thread.

use std::path::PathBuf;
use std::sync::Arc;

use agesim_core::base::arc_key::ArcKey;
use agesim_core::project::Project;
use agesim_core::scene::{BakeRequest, WrinkleSource};
use serde_json::Value;

mod autosave;
mod central;
mod command;
mod commands;
mod compare;
mod harness;
mod inputs;
mod inspector;
pub mod landmarks;
mod menus;
mod presets;
mod shortcuts;
mod status;
mod windows;

pub use commands::Pending;
pub use harness::soak::failed as soak_failed;
pub use shortcuts::SHORTCUTS;

use super::document::Document;
use super::export_ui::{ExportRun, ExportSettings};
use super::fields_ui;
use super::files::{Dialogs, Io, NativeDialogs};
use super::map_view::{self, MapKind, MapViewState};
use super::notices::Notices;
use super::session::Session;
use super::timeline::{self, Playback};
use super::viewport::Viewport;
use super::worker::{Job, Outcome, Snapshot};

/// Map sides while a slider or fibre is being dragged (and while the age plays).
pub const PREVIEW_PX: u32 = 512;
/// Map sides once the drag ends: the large-wrinkle map and the micro-relief tile.
pub const FULL_LARGE_PX: u32 = 2048;
pub const FULL_MICRO_PX: u32 = 1024;

/// What the central area shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, serde::Serialize, serde::Deserialize)]
pub enum Layout {
    /// The 3D view and the UV map side by side.
    #[default]
    Both,
    Head,
    Map,
}

/// Settings kept between runs (eframe storage).
#[derive(Clone, Debug, serde::Serialize, serde::Deserialize)]
#[serde(default)]
pub struct Persisted {
    pub map_view: MapViewState,
    pub playback: Playback,
    pub layout: Layout,
    /// Compare view: the right part of the head shows `compare_years`.
    pub compare: bool,
    pub compare_years: f32,
    /// Where the compare divider is, as a fraction of the view's width.
    pub divider: f32,
    /// Recent project files, newest first.
    pub recent: Vec<PathBuf>,
    pub export: ExportSettings,
}

impl Default for Persisted {
    fn default() -> Self {
        Self {
            map_view: MapViewState::default(),
            playback: Playback::default(),
            layout: Layout::default(),
            compare: false,
            compare_years: 75.0,
            divider: 0.5,
            recent: Vec::new(),
            export: ExportSettings::default(),
        }
    }
}

/// Options of the run (command line; tests).
#[derive(Clone, Debug, Default)]
pub struct EditorOptions {
    /// The file dialogs (default: the platform's, through rfd); tests script them.
    pub dialogs: Option<Arc<dyn Dialogs>>,
    /// Where the user's presets are kept (default: the platform's settings folder).
    pub config_dir: Option<PathBuf>,
    /// Open this project instead of the default one.
    pub project: Option<PathBuf>,
    /// Write a screenshot of the window here after `frames` frames with maps, then quit.
    pub screenshot: Option<PathBuf>,
    pub frames: u32,
    /// Open at this age (years) instead of the project's.
    pub age_years: Option<f32>,
    /// Open in the compare view with this age (years) on the right.
    pub compare_years: Option<f32>,
    /// Run the scripted UI benchmark, print its table and quit.
    pub bench_ui: bool,
    /// The window is cleared to the panel colour ([`EditorApp::clear_color`], eframe's
    /// real window, set by [`super::run`]): the panels are then drawn without their fill,
    /// which a CPU rasteriser would shade at every pixel. Off under egui_kittest, which
    /// clears to transparent.
    pub cleared_to_panel_colour: bool,
    /// Write the session to the recovery folder at most this often while there are
    /// unsaved changes (seconds; 0: off).
    pub autosave_seconds: f64,
    /// The file thread waits this long before it writes an autosave (tests: a slow disk,
    /// so an exit meets a write still running).
    pub autosave_delay: std::time::Duration,
    /// Restore the session a crash left behind without asking.
    pub recover: bool,
    /// The recovery folder (default: the platform's data directory; tests set it).
    pub data_dir: Option<PathBuf>,
    /// One edit (`field=value`) made once the first maps are shown, as if by hand
    /// (scripted runs: the recovery test).
    pub edit: Option<String>,
    /// Drive the editor at random for this many seconds, print the figures and quit
    /// (`--soak`, `harness::soak`).
    pub soak_seconds: Option<f64>,
    /// When the editor was started (a screenshot run prints its first aged frame's and
    /// its settled frame's times from here).
    pub launched: Option<std::time::Instant>,
}

impl EditorOptions {
    /// A run that drives itself (screenshot, benchmark, soak): it starts from the
    /// defaults, not the last session, and closes without asking.
    pub fn scripted(&self) -> bool {
        self.screenshot.is_some() || self.bench_ui || self.soak_seconds.is_some()
    }
}

/// Which windows are open.
#[derive(Debug, Default)]
struct Windows {
    export: bool,
    save_preset: bool,
    help: bool,
    messages: bool,
    about: bool,
}

pub struct EditorApp {
    /// The project, its edited wrinkle files, its history and revisions.
    doc: Document,
    /// The bake worker and its last snapshot.
    session: Session,
    /// `Project::default()`, what the layer panel marks changes against.
    defaults: Project,
    notices: Notices,
    /// egui's clock, seconds (for the toasts).
    now: f64,
    ctx: egui::Context,
    dialogs: Arc<dyn Dialogs>,
    io: Io,
    /// The unsaved-changes prompt, and what runs after a save it asked for.
    prompt: Option<Pending>,
    after_save: Option<Pending>,
    quit_confirmed: bool,
    export_run: Option<ExportRun>,
    /// The document's wrinkle files, watched for changes on disk.
    watcher: super::watch::Watcher,
    /// agesim's own file browser, open where no native dialog can.
    browser: Option<super::file_browser::FileBrowser>,
    /// Whether the status said once why the native dialog is not used.
    told_no_native_dialog: bool,
    windows: Windows,
    config_dir: Option<PathBuf>,
    user_presets: Vec<PathBuf>,
    preset_name: String,
    title: String,
    /// Whether the bakes make the normal-map pictures, (large, micro) (the map view shows
    /// one).
    baked_normal_picture: (bool, bool),
    /// Whether the last job made the shape's pictures (the map view shows the shape).
    baked_shape_pictures: bool,
    textures: Vec<(MapKind, egui::TextureHandle, ArcKey<egui::ColorImage>)>,
    layout_texture: Option<(egui::TextureHandle, ArcKey<egui::ColorImage>)>,
    /// The map view's pictures on the GPU adapter (made on first use).
    map_gpu: Option<crate::editor::map_gpu::MapGpu>,
    /// The guided landmark mode, when open.
    landmark_mode: Option<landmarks::LandmarkMode>,
    autosave: autosave::Autosave,
    persisted: Persisted,
    adapter: String,
    viewport: Option<Viewport>,
    /// eframe's wgpu state (device, queue, egui's renderer), kept from creation so the
    /// view also draws where the frame does not expose it (egui_kittest).
    render_state: Option<eframe::egui_wgpu::RenderState>,
    options: EditorOptions,
    /// What drives a scripted run (benchmark, soak, screenshot); empty otherwise.
    harness: harness::Harness,
    /// The shown large map and its deepest value (the status line's figure, computed once
    /// per map, not once per frame). Weak: the old map's data is freed as usual, but its
    /// address is not reused while this refers to it.
    deepest: (std::sync::Weak<agesim_core::scene::LargeMap>, f32),
    last_hover_uv: Option<[f32; 2]>,
    /// The 3D view's quality while moving (`governor`), and when the last frame began.
    governor: crate::editor::governor::Governor,
    last_frame_at: Option<std::time::Instant>,
}

impl EditorApp {
    pub fn new(cc: &eframe::CreationContext<'_>, options: EditorOptions) -> Self {
        // Scripted runs (screenshot, benchmark) start from the defaults, not from the last
        // session, so they show the same thing on every machine.
        let persisted: Persisted = cc
            .storage
            .filter(|_| !options.scripted())
            .and_then(|s| eframe::get_value(s, eframe::APP_KEY))
            .unwrap_or_default();
        let adapter = cc.wgpu_render_state.as_ref().map_or_else(
            || "no GPU adapter".to_owned(),
            |rs| {
                let info = rs.adapter.get_info();
                format!("{} ({:?})", info.name, info.backend)
            },
        );
        let (project, error, path) = match &options.project {
            Some(path) => match Project::load(path) {
                Ok(p) => (p, None, Some(path.clone())),
                Err(e) => (Project::default(), Some(e.to_string()), None),
            },
            None => (Project::default(), None, None),
        };
        let viewport = cc
            .wgpu_render_state
            .as_ref()
            .and_then(|rs| Viewport::new(rs).ok());
        let mut project = project;
        if let Some(y) = options.age_years {
            project.age.t = project.age.mapping().t(y);
        }
        let mut persisted = persisted;
        if let Some(y) = options.compare_years {
            persisted.compare = true;
            persisted.compare_years = y;
            persisted.layout = Layout::Head;
        }
        let ctx = cc.egui_ctx.clone();
        let session = Session::new(move || ctx.request_repaint());
        let ctx = cc.egui_ctx.clone();
        let io = Io::new(move || ctx.request_repaint());
        let ctx = cc.egui_ctx.clone();
        let watcher = super::watch::Watcher::new(move || ctx.request_repaint());
        let dialogs = options
            .dialogs
            .clone()
            .unwrap_or_else(|| Arc::new(NativeDialogs));
        let config_dir = options
            .config_dir
            .clone()
            .or_else(|| eframe::storage_dir("agesim"));
        let mut app = Self {
            doc: Document::new(project, path),
            session,
            defaults: Project::default(),
            notices: Notices::default(),
            now: 0.0,
            ctx: cc.egui_ctx.clone(),
            dialogs,
            io,
            prompt: None,
            after_save: None,
            quit_confirmed: false,
            export_run: None,
            browser: None,
            told_no_native_dialog: false,
            watcher,
            windows: Windows::default(),
            config_dir,
            user_presets: Vec::new(),
            preset_name: String::new(),
            title: String::new(),
            baked_normal_picture: (false, false),
            baked_shape_pictures: false,
            textures: Vec::new(),
            layout_texture: None,
            map_gpu: None,
            landmark_mode: None,
            autosave: autosave::Autosave::default(),
            persisted,
            adapter,
            viewport,
            render_state: cc.wgpu_render_state.clone(),
            harness: harness::Harness::for_options(&options),
            options,
            deepest: (std::sync::Weak::new(), 0.0),
            governor: Default::default(),
            last_frame_at: None,
            last_hover_uv: None,
        };
        // The benchmark and the soak run in the default layout.
        if app.options.bench_ui || app.options.soak_seconds.is_some() {
            app.persisted.layout = Layout::default();
        }
        if app.options.bench_ui {
            app.persisted.compare = false;
        }
        if let Some(e) = error {
            app.error(format!("Could not open the project: {e}"));
        }
        if let Some(p) = &app.doc.path {
            let p = p.clone();
            app.persisted.recent.retain(|r| r != &p);
            app.persisted.recent.insert(0, p);
        }
        app.refresh_user_presets();
        app.baked_normal_picture = app.persisted.map_view.kind.normal_picture();
        app.baked_shape_pictures = app.persisted.map_view.kind == MapKind::Shape;
        app.submit(false, "open");
        app.start_recovery();
        app
    }

    /// The current document, for tests.
    pub fn project(&self) -> &Project {
        &self.doc.project
    }

    /// The numbers of the 3D view's last frame (`None` without a GPU), for tests.
    pub fn view_frame(&self) -> Option<agesim_render::FrameParams> {
        self.viewport.as_ref()?.last_frame().copied()
    }

    /// The last finished bake, for tests.
    pub fn snapshot(&self) -> &Snapshot {
        &self.session.snapshot
    }

    /// Whether the newest request has been baked.
    pub fn idle(&self) -> bool {
        !self.session.busy()
    }

    /// The fibres as currently edited.
    pub fn wrinkles(&self) -> &[WrinkleSource] {
        self.doc
            .wrinkles
            .as_deref()
            .unwrap_or(&self.session.snapshot.wrinkles)
    }

    /// The guided landmark mode's state, when open.
    pub fn landmark_mode(&self) -> Option<&landmarks::LandmarkMode> {
        self.landmark_mode.as_ref()
    }

    /// Where each landmark's dot was drawn on the 3D view last frame (for tests).
    pub fn landmark_dots(&self) -> Vec<(&'static str, egui::Pos2)> {
        self.viewport
            .as_ref()
            .map(|v| v.landmark_dots.clone())
            .unwrap_or_default()
    }

    pub fn map_view_mut(&mut self) -> &mut MapViewState {
        &mut self.persisted.map_view
    }

    fn submit(&mut self, preview: bool, what: &str) {
        let size = if preview {
            // The governor's size while moving (PREVIEW_PX at most).
            let px = self.governor.quality().preview_px.min(PREVIEW_PX);
            (px, px)
        } else {
            (FULL_LARGE_PX, FULL_MICRO_PX)
        };
        self.submit_sized(size, what);
    }

    /// Sends the document to the worker, maps at (large, micro) px, at the document's age
    /// (and the compare age when compare mode is on).
    fn submit_sized(&mut self, (large, micro): (u32, u32), what: &str) {
        let request = BakeRequest {
            large_size_px: large,
            micro_size_px: micro,
            t: self.doc.project.age.t,
            // The renderer repeats the micro-relief over the head: no seams where tiles
            // meet. The document's own `tile` is what map exports use.
            tileable: true,
            fine: true,
            hair: true,
            // The packing is only a picture for the map view (the renderer reads the
            // heights): made when that picture is shown, not on every age change.
            packed: self.persisted.map_view.kind == MapKind::LargeNormal,
            one_off: false,
            micro_normals: self.persisted.map_view.kind == MapKind::MicroNormal,
            shape_relief: true,
        };
        let shape_pictures = self.persisted.map_view.kind == MapKind::Shape;
        self.session.worker.submit(Job {
            shape_pictures,
            id: 0,
            project: self.doc.project.clone(),
            wrinkles: self.doc.wrinkles.clone(),
            request,
            what: what.to_owned(),
            detect_units: self.session.measure_mesh,
            files: self.doc.files.clone(),
            compare_t: self.persisted.compare.then(|| {
                self.doc
                    .project
                    .age
                    .mapping()
                    .t(self.persisted.compare_years)
            }),
        });
    }

    /// Applies one field edit to the document, checked as a project file checks it
    /// ([`Project::set_field`]: that field's type and range, then the rules between
    /// fields).
    fn apply(&mut self, path: &str, value: Value, dragging: bool) {
        let mut p = self.doc.project.clone();
        match p.set_field(path, value) {
            Ok(()) if p == self.doc.project => {}
            Ok(()) => {
                self.record(path, path, dragging);
                self.doc.project = p;
                self.submit(dragging, path);
            }
            Err(e) => self.error(e.to_string()),
        }
    }

    /// A fibre moved (the map view's drag, the soak run): one undo step per drag.
    pub(super) fn apply_fibre_edit(
        &mut self,
        mut wrinkles: Vec<WrinkleSource>,
        e: map_view::FibreEdit,
    ) {
        if let Some(g) = wrinkles
            .get_mut(e.file)
            .and_then(|f| f.file.groups.get_mut(e.group))
        {
            g.fibre = e.fibre;
            self.record(
                "fibre drag",
                &format!("fibre {}/{}", e.file, e.group),
                e.dragging,
            );
            self.doc.wrinkles = Some(wrinkles);
            self.submit(e.dragging, "fibre");
        }
    }

    /// Sets the age t and bakes (a preview while it is still moving).
    pub fn set_age(&mut self, t: f32, moving: bool) {
        self.doc.project.age.t = t.clamp(0.0, 1.0);
        // While the age moves, bake only when the worker is free: the view shows the
        // newest age at once (hair, fine wrinkles, paling are uniforms) and the maps
        // follow, instead of a bake per frame competing with drawing for the cores.
        if moving && self.session.busy() {
            self.session.age_pending = true;
            return;
        }
        self.session.age_pending = false;
        let years = self.doc.project.age.mapping().years(self.doc.project.age.t);
        self.submit(moving, &format!("age {years:.0} years"));
    }

    /// The menu bar over the document's state; runs what was chosen.
    fn menu_ui(&mut self, ui: &mut egui::Ui) {
        let index = self.persisted.map_view.selected.map_or(0, |(f, _)| f);
        let wrinkle_file = self.wrinkles().get(index).map(|w| {
            let name = std::path::Path::new(&w.name).file_name().map_or_else(
                || "wrinkles.wrk".into(),
                |n| n.to_string_lossy().into_owned(),
            );
            (index, name)
        });
        let user_presets = self.user_presets.clone();
        let state = menus::MenuState {
            undo: self.doc.history.undo_name().map(str::to_owned),
            redo: self.doc.history.redo_name().map(str::to_owned),
            wrinkle_file,
            user_presets: &user_presets,
        };
        for command in menus::menu_bar(ui, &state, &mut self.persisted) {
            self.run(command, ui.ctx());
        }
    }

    fn poll_worker(&mut self) {
        for report in self.session.worker.poll() {
            if report.partial {
                // The head shown before the job's end; the job still runs (a newer job's
                // reports replace it).
                if report.id < self.session.worker.latest {
                    continue;
                }
                if let Outcome::Done { snapshot, .. } = report.outcome {
                    let shown = std::mem::replace(&mut self.session.snapshot, *snapshot);
                    self.session.before_first_look.get_or_insert(shown);
                }
                continue;
            }
            let before_first_look = self.session.before_first_look.take();
            self.session.reported = self.session.reported.max(report.id);
            self.session.last_bake_ms = report.ms;
            self.session.last_what = report.what;
            match report.outcome {
                Outcome::Done { snapshot, .. } => {
                    if let Some(p) = &snapshot.project {
                        self.doc.last_good = p.clone();
                    }
                    self.session.snapshot = *snapshot;
                    if !self.session.reload.is_empty() {
                        let names: Vec<String> = std::mem::take(&mut self.session.reload)
                            .iter()
                            .map(|p| p.display().to_string())
                            .collect();
                        for name in &names {
                            self.notices.close_errors_about(name);
                        }
                        self.info(format!("Reloaded {}", names.join(", ")));
                    }
                    if let Some(u) = report.units {
                        self.session.measure_mesh = false;
                        self.info(format!(
                            "metres per unit: {} ({}); set it in the layer panel's mesh section",
                            u.metres_per_unit, u.how
                        ));
                        // An imported head: say how its layers are placed.
                        let how = self.session.snapshot.layout_how.clone();
                        self.info(format!("layout: {how}"));
                    }
                }
                Outcome::Failed(message) => {
                    self.session.measure_mesh = false;
                    // A changed file that does not load: the previous input stays; the
                    // file is read again when it changes.
                    self.session.reload.clear();
                    // Keep the previous state whole: the document goes back to what baked,
                    // the view to what it showed before the failed head's first look.
                    self.error(format!("{message}\n(the previous state is kept)"));
                    self.doc.project = self.doc.last_good.clone();
                    if let Some(shown) = before_first_look {
                        self.session.snapshot = shown;
                    }
                    // The refused change leaves no undo step and no modified mark.
                    let good = &self.doc.last_good;
                    if let Some(doc) = self.doc.history.discard_last_if(|d| &d.project == good) {
                        self.doc.revision = doc.revision;
                        self.doc.wrinkles = doc.wrinkles;
                        self.doc.files = doc.files;
                    }
                }
            }
        }
        if self.session.age_pending && !self.session.busy() {
            self.set_age(self.doc.project.age.t, true);
        }
    }

    /// The UV layout overlay's picture of `kind`'s chart.
    fn layout_image(&self, kind: MapKind) -> Option<Arc<egui::ColorImage>> {
        let snapshot = &self.session.snapshot;
        if kind.on_fibre_chart(snapshot.fitted) {
            snapshot.images.uv_layout.clone()
        } else {
            (snapshot.images.head_uv_layout.clone()).or(snapshot.images.uv_layout.clone())
        }
    }

    /// The UV layout overlay's texture of `kind`'s chart, made once per mesh.
    fn layout_texture(
        &mut self,
        ctx: &egui::Context,
        kind: MapKind,
    ) -> Option<egui::TextureHandle> {
        let image = self.layout_image(kind)?;
        match &mut self.layout_texture {
            Some((t, s)) if s.is(&image) => Some(t.clone()),
            slot => {
                let t = ctx.load_texture(
                    "uv layout",
                    image.as_ref().clone(),
                    egui::TextureOptions::LINEAR,
                );
                *slot = Some((t.clone(), ArcKey::of(&image)));
                Some(t)
            }
        }
    }

    /// The snapshot's picture of `kind`.
    fn map_image(&self, kind: MapKind) -> Option<Arc<egui::ColorImage>> {
        let images = &self.session.snapshot.images;
        match kind {
            MapKind::LargeHeight => images.large_height.clone(),
            MapKind::LargeNormal => images.large_normal.clone(),
            MapKind::MicroHeight => images.micro_height.clone(),
            MapKind::MicroNormal => images.micro_normal.clone(),
            MapKind::Transition => images.transition.clone(),
            MapKind::Fine => images.fine.clone(),
            MapKind::Mask => images.mask.clone(),
            MapKind::LargeHead => images.large_head.clone().or(images.large_height.clone()),
            MapKind::Shape => images.shape.clone(),
        }
    }

    /// The texture of `kind`, remade when the snapshot's picture changed.
    fn texture(&mut self, ctx: &egui::Context, kind: MapKind) -> Option<egui::TextureHandle> {
        let image = self.map_image(kind)?;
        if let Some((_, t, s)) = self.textures.iter_mut().find(|(k, _, _)| *k == kind) {
            if !s.is(&image) {
                t.set(image.as_ref().clone(), egui::TextureOptions::LINEAR);
                *s = ArcKey::of(&image);
            }
            return Some(t.clone());
        }
        let t = ctx.load_texture(
            format!("map {kind:?}"),
            image.as_ref().clone(),
            egui::TextureOptions::LINEAR,
        );
        self.textures.push((kind, t.clone(), ArcKey::of(&image)));
        Some(t)
    }
}

/// A panel frame without its fill: the window is cleared to the panel colour instead
/// ([`EditorApp::clear_color`]), which looks the same. On a CPU rasteriser every shaded
/// pixel costs: filling the window's panels was ≈ 30 ms of every frame on llvmpipe at
/// 1280×800 (measured), the render pass's clear next to nothing.
fn bare(frame: egui::Frame) -> egui::Frame {
    frame.fill(egui::Color32::TRANSPARENT)
}

impl eframe::App for EditorApp {
    fn clear_color(&self, visuals: &egui::Visuals) -> [f32; 4] {
        visuals.panel_fill.to_normalized_gamma_f32()
    }

    fn ui(&mut self, ui: &mut egui::Ui, frame: &mut eframe::Frame) {
        let ctx = ui.ctx().clone();
        self.now = ctx.input(|i| i.time);
        self.poll_worker();
        self.poll_io();
        self.watch_files();
        self.poll_export();
        self.scripted_edit();
        self.autosave_tick();
        self.intercept_close(&ctx);
        if self.prompt.is_none() {
            for command in shortcuts::shortcut_commands(&ctx) {
                self.run(command, &ctx);
            }
        }
        self.handle_drops(&ctx);
        let title = self.title();
        if title != self.title {
            ctx.send_viewport_cmd(egui::ViewportCommand::Title(title.clone()));
            self.title = title;
        }
        if self.harness.floor() {
            egui::CentralPanel::default()
                .frame(bare(egui::Frame::central_panel(ui.style())))
                .show(ui, |_| {});
            self.bench_step(&ctx);
            return;
        }
        let frame_ms = frame.info().cpu_usage.unwrap_or(0.0) * 1e3;
        let style = ui.style().clone();
        let cleared = self.options.cleared_to_panel_colour;
        let bare = move |frame: egui::Frame| if cleared { bare(frame) } else { frame };
        let side = bare(egui::Frame::side_top_panel(&style));
        egui::Panel::top("menu")
            .frame(side)
            .show(ui, |ui| self.menu_ui(ui));
        egui::Panel::bottom("status")
            .frame(side)
            .show(ui, |ui| self.status_ui(ui, frame_ms));
        let timeline_edit = egui::Panel::bottom("timeline")
            .frame(side)
            .resizable(false)
            .show(ui, |ui| {
                timeline::timeline_ui(ui, &self.doc.project, &mut self.persisted.playback)
            })
            .inner;
        if let Some((t, moving)) = timeline_edit.t {
            // A scrub is an edit (one step per drag); playback is not.
            if !self.persisted.playback.playing && t != self.doc.project.age.t {
                self.record("age", "age", moving);
            }
            self.set_age(t, moving);
        }
        if let Some((path, years, dragging)) = timeline_edit.curve {
            self.apply(path, Value::from(years), dragging);
        }
        // Edited fibres: the panel lists the files being edited, not "(built-in)".
        let edited: Option<Vec<&str>> = self
            .doc
            .wrinkles
            .as_ref()
            .map(|w| w.iter().map(|w| w.name.as_str()).collect());
        let edits = egui::Panel::left("layers")
            .frame(side)
            .resizable(true)
            .default_size(340.0)
            .show(ui, |ui| {
                ui.heading("Layers");
                let layers = &self.session.snapshot.layers;
                let automatic = |path: &str| automatic_value(path, layers);
                egui::ScrollArea::vertical()
                    .show(ui, |ui| {
                        fields_ui::layers_ui(
                            ui,
                            &self.doc.project,
                            &self.defaults,
                            edited.as_deref(),
                            &automatic,
                        )
                    })
                    .inner
            })
            .inner;
        for edit in edits {
            match edit.pick {
                Some(pick) => self.pick_for_field(edit.path, pick),
                None => self.apply(edit.path, edit.value, edit.dragging),
            }
        }
        egui::Panel::right("inspector")
            .frame(side)
            .resizable(true)
            .default_size(260.0)
            .show(ui, |ui| {
                ui.heading("Fibre");
                self.inspector_ui(ui);
            });
        let central_frame = bare(egui::Frame::central_panel(&style));
        let (fibre_edit, wrinkles) = self.central_ui(ui, frame, central_frame);
        if let Some(e) = fibre_edit {
            self.apply_fibre_edit(wrinkles, e);
        }
        self.windows_ui(&ctx);
        self.browser_ui(&ctx);
        self.notices.toasts_ui(&ctx, 150.0);
        self.maybe_screenshot(&ctx);
        self.bench_step(&ctx);
        self.soak_step(&ctx);
    }

    fn on_exit(&mut self) {
        self.exit_cleanly();
    }

    fn save(&mut self, storage: &mut dyn eframe::Storage) {
        if self.options.scripted() {
            return;
        }
        eframe::set_value(storage, eframe::APP_KEY, &self.persisted);
    }
}

/// What a `null` field stands for on the head shown (the layer panel shows it and switches
/// on with it): the mesh's measured units, the hair and brow colours measured on it, the
/// guessed hair loss and curl.
fn automatic_value(path: &str, layers: &crate::view::Layers) -> Option<serde_json::Value> {
    let hex = |c: [f32; 3]| {
        let srgb = c.map(|c| {
            (agesim_core::maps::mask::linear_to_srgb(c.clamp(0.0, 1.0)) * 255.0).round() as u8
        });
        serde_json::Value::String(agesim_core::project::Colour(srgb).to_string())
    };
    let person = layers.person;
    match path {
        "mesh.metres_per_unit" => Some(serde_json::Value::from(f64::from(layers.metres_per_unit))),
        "hair.base_colour" => person.map(|p| hex(p.hair)),
        "hair.brow_colour" => person.map(|p| hex(p.brows)),
        "hair.loss" => person.map(|p| serde_json::Value::String(p.loss.loss.name().into())),
        "hair.curl" => person.map(|p| serde_json::Value::from(f64::from(p.curl))),
        _ => None,
    }
}
