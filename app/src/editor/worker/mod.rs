//! The bake worker: the editor's [`Scene`] lives on its own thread, so the UI thread never
//! waits on a bake, a file or a conversion. Requests are "latest wins": submitting cancels
//! the running bake through its [`CancelToken`], and queued requests are skipped in favour
//! of the newest one. Results come back as ready-to-show snapshots.

use std::sync::Arc;
use std::sync::mpsc::{Receiver, Sender, TryRecvError, channel};
use std::time::Instant;

use agesim_core::age::AgeFactors;
use agesim_core::base::arc_key::ArcKey;
use agesim_core::base::cancel::CancelToken;
use agesim_core::head::mesh::units::Units;
use agesim_core::layers::hair::HairInstances;
use agesim_core::layers::hair::transition::TransitionTexture;
use agesim_core::project::Project;
use agesim_core::scene::{BakeRequest, Changed, LargeMap, MicroTile, Scene, WrinkleSource};
use agesim_core::{Error, HeightMap, Mesh};

use crate::view::Layers;

mod pictures;
pub use pictures::{IMAGE_MAX_PX, MapImages};
use pictures::{colour_on_template, grey_image, rgb_image, uv_layout_image};

/// One request: the whole document state and what to bake.
#[derive(Clone, Debug)]
pub struct Job {
    pub id: u64,
    pub project: Project,
    /// The wrinkle files as edited in the UI; `None` = as loaded from the project's paths.
    pub wrinkles: Option<Vec<WrinkleSource>>,
    pub request: BakeRequest,
    /// A short description for the status line ("age 52 years", "pores.count").
    pub what: String,
    /// Also bake this second age, for the compare view.
    pub compare_t: Option<f32>,
    /// Report how the mesh's units were decided ([`Report::units`]; a head just imported).
    pub detect_units: bool,
    /// Which content of the input files changed on disk (mesh, masks, tile, landmarks,
    /// colour and normal maps) to use: a new version is read again, an earlier one comes
    /// back as it was (an undone reload).
    pub files: agesim_core::scene::FileVersions,
    /// Also make the shape's pictures (`images.shape`, `shape_overlay`): while the map
    /// view shows the shape.
    pub shape_pictures: bool,
}

/// The shape's movement picture, the field it shows (kept, so its address is not reused
/// while compared) and its size.
type ShapeMovement = (
    Arc<agesim_core::layers::shape::ShapeField>,
    u32,
    Arc<Vec<f32>>,
);

/// What the UI shows of a finished bake. Each map is shared, not copied, between bakes
/// that did not change it.
#[derive(Clone, Debug, Default)]
pub struct Snapshot {
    pub project: Option<Project>,
    pub mesh: Option<Arc<Mesh>>,
    pub wrinkles: Vec<WrinkleSource>,
    pub factors: Option<AgeFactors>,
    /// The large-wrinkle map (normalised: × `large.depth` for height units).
    pub large: Option<Arc<LargeMap>>,
    pub micro: Option<Arc<MicroTile>>,
    pub fine: Option<Arc<HeightMap>>,
    /// The renderer's inputs, converted for the GPU here (f16, tile mips), so the UI
    /// thread's upload is a copy.
    pub layers: Layers,
    pub transition: Option<Arc<TransitionTexture>>,
    pub hair: Option<Arc<HairInstances>>,
    pub request: Option<BakeRequest>,
    /// The maps as pictures for the 2D view, remade only when their map changed.
    pub images: MapImages,
    /// The compare view's second age, baked by a second scene.
    pub compare: Option<Box<Snapshot>>,
    /// Which mask `images.mask` shows.
    mask_stamp: Option<ArcKey<agesim_core::maps::mask::Mask>>,
    /// The aged colour tinted by the shape's movement (`images.shape` on the head): the
    /// 3D view's colour while the map view shows the shape.
    pub shape_overlay: Option<Arc<agesim_core::maps::mask::HeadImage>>,
    /// What `shape_overlay` and `images.shape` were made from (field, aged colour).
    shape_stamps: (
        Option<ArcKey<agesim_core::layers::shape::ShapeField>>,
        Option<ArcKey<agesim_core::maps::mask::HeadImage>>,
    ),
    /// The shape's movement over the head's UVs (mm), kept while its field and size hold:
    /// an age change only tints the new colour with it.
    shape_movement: Option<ShapeMovement>,
    /// Whether the head reads the layers through the template's fit.
    pub fitted: bool,
    /// How the head's layout was decided (`Scene::layout`).
    pub layout_how: String,
    /// The landmarks the fit used (the project's file or found), scene coordinates.
    pub landmarks: Option<Arc<agesim_core::head::landmarks::Landmarks>>,
    /// Whether `landmarks` were found automatically.
    pub landmarks_found: bool,
    /// The scene's coordinates back to the mesh file's (landmark files are in the file's).
    pub file_from_scene: glam::Mat3,
    /// A fitted head's correspondence (head UV → template UV) at the large map's size:
    /// a click on the head marks its template UV on the fibres' chart.
    pub correspondence: Option<Arc<agesim_core::head::fit::Correspondence>>,
    /// The picture files the mesh file's material names (watched with the mesh).
    pub mesh_texture_files: Vec<std::path::PathBuf>,
}

/// The outcome of one job.
#[derive(Debug)]
pub enum Outcome {
    /// Baked; `changed` says which parts of `snapshot` are new.
    Done {
        snapshot: Box<Snapshot>,
        changed: Changed,
    },
    /// The project's inputs or settings were refused: the message names the file or field.
    /// The worker's scene (and so the last snapshot) is unchanged.
    Failed(String),
}

#[derive(Debug)]
pub struct Report {
    pub id: u64,
    pub what: String,
    pub ms: f64,
    pub outcome: Outcome,
    /// How the mesh's units were decided, when the job asked ([`Job::detect_units`]).
    pub units: Option<agesim_core::head::mesh::units::Units>,
    /// A first look before the job's end (a new dense head without its shape yet): the
    /// job is still running and reports again.
    pub partial: bool,
}

/// The UI side of the worker.
pub struct Worker {
    jobs: Sender<(Job, CancelToken)>,
    reports: Receiver<Report>,
    running: CancelToken,
    next_id: u64,
    /// The id of the newest submitted job.
    pub latest: u64,
}

impl Worker {
    /// Starts the worker thread on `project`. `wake` is called after each report (the UI
    /// asks for a repaint there).
    pub fn spawn(wake: impl Fn() + Send + 'static) -> Self {
        let (jobs, job_rx) = channel::<(Job, CancelToken)>();
        let (report_tx, reports) = channel();
        std::thread::Builder::new()
            .name("agesim-bake".into())
            .spawn(move || run(job_rx, report_tx, wake))
            .ok();
        Self {
            jobs,
            reports,
            running: CancelToken::new(),
            next_id: 0,
            latest: 0,
        }
    }

    /// Queues a job and cancels whatever is running: latest wins.
    pub fn submit(&mut self, mut job: Job) -> u64 {
        self.running.cancel();
        self.running = CancelToken::new();
        self.next_id += 1;
        job.id = self.next_id;
        self.latest = job.id;
        // A send only fails when the worker thread is gone; the UI then shows stale maps.
        let _ = self.jobs.send((job, self.running.clone()));
        self.next_id
    }

    /// Reports that arrived since the last call, oldest first.
    pub fn poll(&mut self) -> Vec<Report> {
        let mut out = Vec::new();
        while let Ok(r) = self.reports.try_recv() {
            out.push(r);
        }
        out
    }

    /// Whether the newest job has not reported yet.
    pub fn busy(&self, last_reported: u64) -> bool {
        last_reported < self.latest
    }
}

/// Vertices from which a new head is reported once before its shape is made (its shape
/// field is seconds from here; below, a second pass over the snapshot would cost more than
/// it shows).
const EARLY_LOOK_VERTICES: usize = 50_000;

/// Bakes up to this side run on the normal-priority pool (previews); larger ones on the
/// low-priority pool.
const PREVIEW_MAX_PX: u32 = 1024;

/// Gives the calling thread a lower scheduling priority (Linux `nice` 10, per thread):
/// when a full-resolution bake and a frame want the same cores, the frame (the UI thread
/// and, on a CPU adapter, the rasteriser's threads) goes first, so the editor keeps
/// responding; a bake alone still gets every core it asks for. Best effort: a failure
/// changes nothing.
fn lower_priority() {
    #[cfg(target_os = "linux")]
    {
        // SAFETY: gettid has no preconditions; setpriority on our own thread id only
        // changes that thread's nice value (raising it needs no privilege).
        unsafe {
            let tid = libc::gettid();
            libc::setpriority(libc::PRIO_PROCESS, tid as libc::id_t, 10);
        }
    }
}

fn run(jobs: Receiver<(Job, CancelToken)>, reports: Sender<Report>, wake: impl Fn()) {
    // Two scenes: previews, and full-resolution bakes. Each keeps its maps at its own
    // size, so the preview after a full bake (the next slider drag) and the full bake
    // after a drag re-bake only what changed, instead of every layer at the other size.
    let mut preview_scene: Option<Scene> = None;
    let mut full_scene: Option<Scene> = None;
    // Which of them the snapshot was last filled from (true: the full one).
    let mut snapshot_full: Option<bool> = None;
    let mut snapshot = Snapshot::default();
    let mut scene_b: Option<Scene> = None;
    let mut snapshot_b = Snapshot::default();
    // Bakes use all cores but one, so the UI thread (and a CPU graphics adapter) always
    // has a core: the editor stays fluid while a large bake runs. The maps are the same
    // bytes on any thread count.
    let threads = std::thread::available_parallelism()
        .map_or(1, |n| n.get().saturating_sub(1))
        .max(1);
    // Two pools of the same size: previews (what a slider drag or a scrub waits for) at
    // normal priority, full-resolution bakes at a lower one, so a long bake gives way to
    // the frames and to the previews asked for meanwhile.
    let pool = |name: &'static str, low: bool| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .thread_name(move |i| format!("{name}-{i}"))
            .start_handler(move |_| {
                if low {
                    lower_priority();
                }
            })
            .build()
            .ok()
    };
    let (preview_pool, full_pool) = (pool("agesim-preview", false), pool("agesim-bake", true));
    // A head being opened (no scene yet, or a changed mesh section: another file, its
    // units, axes or landmarks) has nothing to draw meanwhile but the last head, still: its
    // bake takes every core (a dense head's first look is most
    // of its loading, fitting and first maps).
    let all_cores = std::thread::available_parallelism().map_or(1, std::num::NonZero::get);
    let open_pool = rayon::ThreadPoolBuilder::new()
        .num_threads(all_cores)
        .thread_name(|i| format!("agesim-open-{i}"))
        .build()
        .ok();
    let install = |job: &Job, opening: bool, f: &mut (dyn FnMut() + Send)| {
        let pool = if opening {
            &open_pool
        } else if is_full(&job.request) {
            &full_pool
        } else {
            &preview_pool
        };
        match pool {
            Some(p) => p.install(f),
            None => f(),
        }
    };
    while let Ok(mut next) = jobs.recv() {
        // Latest wins: skip everything queued behind the newest job.
        loop {
            match jobs.try_recv() {
                Ok(newer) => next = newer,
                Err(TryRecvError::Empty) => break,
                Err(TryRecvError::Disconnected) => return,
            }
        }
        let (job, cancel) = next;
        let start = Instant::now();
        let full = is_full(&job.request);
        let opening = [&preview_scene, &full_scene].iter().all(|s| {
            s.as_ref()
                .is_none_or(|s| s.project().mesh != job.project.mesh)
        });
        let mut outcome = Err(Error::Cancelled);
        // A head's first looks, before the job's end: reported to the UI (which polls
        // while the worker is busy) as partial outcomes.
        let mut early = |shown: &Snapshot| {
            let _ = reports.send(Report {
                id: job.id,
                what: job.what.clone(),
                ms: start.elapsed().as_secs_f64() * 1e3,
                outcome: Outcome::Done {
                    snapshot: Box::new(shown.clone()),
                    changed: Changed::default(),
                },
                units: None,
                partial: true,
            });
        };
        // A head being opened at full size is first baked and shown aged at the preview
        // size (its landmarks, fit, shape and hair are the same at any size, and shared
        // by the full bake that follows in the same job: only the maps are made twice).
        let mut first_failed = false;
        if opening {
            // The compare view's other age is the previous head's until the job's end.
            snapshot.compare = None;
        }
        if opening && full {
            let first = first_look(&job);
            let switched = snapshot_full != Some(false);
            let mut first_outcome = Err(Error::Cancelled);
            install(&first, true, &mut || {
                first_outcome = bake(
                    &mut preview_scene,
                    &mut snapshot,
                    &first,
                    (switched, true),
                    &cancel,
                    &mut early,
                )
            });
            match first_outcome {
                Ok(_) => {
                    snapshot_full = Some(false);
                    early(&snapshot);
                    wake();
                    // The other head's full scene has nothing left to share.
                    full_scene = None;
                }
                Err(Error::Cancelled) => continue,
                Err(e) => {
                    outcome = Err(e);
                    first_failed = true;
                }
            }
        }
        // A new scene starts as a fork of the other: the inputs (mesh, masks, files)
        // are shared, not loaded again, and no map of the other size is copied.
        let (scene, other) = if full {
            (&mut full_scene, &preview_scene)
        } else {
            (&mut preview_scene, &full_scene)
        };
        if scene.is_none() {
            *scene = other.as_ref().map(Scene::fork);
        }
        // The snapshot shows the other scene's maps: take every layer from this one.
        let switched = snapshot_full != Some(full);
        if !first_failed {
            install(&job, opening, &mut || {
                outcome = bake(
                    scene,
                    &mut snapshot,
                    &job,
                    (switched, opening),
                    &cancel,
                    &mut early,
                )
            });
        }
        let units = match &mut outcome {
            Ok((_, units)) => units.take(),
            Err(_) => None,
        };
        let mut outcome = outcome.map(|(changed, _)| changed);
        if outcome.is_ok() {
            snapshot_full = Some(full);
        }
        if let (Ok(_), Some(t)) = (&outcome, job.compare_t) {
            // The second age: a scene of its own, so neither side re-bakes the other's age.
            let mut job_b = job.clone();
            job_b.request.t = t;
            job_b.wrinkles = scene.as_ref().map(|s| s.wrinkles().to_vec());
            job_b.detect_units = false;
            if scene_b.is_none() {
                scene_b = scene.as_ref().map(Scene::fork);
            }
            let mut result_b = Err(Error::Cancelled);
            install(&job_b, false, &mut || {
                result_b = bake(
                    &mut scene_b,
                    &mut snapshot_b,
                    &job_b,
                    (false, false),
                    &cancel,
                    &mut |_| {},
                )
            });
            match result_b.map(|(changed, _)| changed) {
                Ok(_) => snapshot.compare = Some(Box::new(snapshot_b.clone())),
                Err(e) => outcome = Err(e),
            }
        } else if job.compare_t.is_none() {
            snapshot.compare = None;
        }
        let outcome = match outcome {
            Err(Error::Cancelled) => continue,
            Err(e) => Outcome::Failed(e.to_string()),
            Ok(changed) => Outcome::Done {
                snapshot: Box::new(snapshot.clone()),
                changed,
            },
        };
        let report = Report {
            id: job.id,
            what: job.what,
            ms: start.elapsed().as_secs_f64() * 1e3,
            outcome,
            units,
            partial: false,
        };
        if reports.send(report).is_err() {
            return;
        }
        wake();
    }
}

/// The preview-sized first look at a head being opened by `job` (a full bake): its maps
/// at [`PREVIEW_MAX_PX`] (the micro-relief at half), without the shape's relief finer
/// than the triangles (a second of a dense head's open; the full bake adds it) and no
/// compare age.
fn first_look(job: &Job) -> Job {
    let mut first = job.clone();
    first.request.large_size_px = job.request.large_size_px.min(PREVIEW_MAX_PX);
    first.request.micro_size_px = job.request.micro_size_px.min(PREVIEW_MAX_PX / 2);
    first.request.shape_relief = false;
    first.compare_t = None;
    first
}

/// Whether a request goes to the full-resolution scene and pool.
fn is_full(r: &BakeRequest) -> bool {
    r.large_size_px.max(r.micro_size_px) > PREVIEW_MAX_PX
}

/// Bakes `job` in `scene` and refreshes what changed in `snapshot` (everything when
/// `refresh_all`: the snapshot was filled from another scene); `early` is given the
/// snapshot once before the end when a new dense head's shape is still to be made, and
/// when `opening` (neither scene has the head yet: the view shows none of it) the bare
/// head as soon as it is read.
fn bake(
    scene: &mut Option<Scene>,
    snapshot: &mut Snapshot,
    job: &Job,
    (refresh_all, opening): (bool, bool),
    cancel: &CancelToken,
    early: &mut dyn FnMut(&Snapshot),
) -> Result<(Changed, Option<Units>), Error> {
    let mut changed = Changed::default();
    let project = job.project.clone();
    // A new dense head is shown as soon as it is read and turned upright, untextured,
    // before its fit and layers (seconds).
    let mut bare = |mesh: &Arc<Mesh>| {
        if opening && mesh.vertex_count() >= EARLY_LOOK_VERTICES {
            early(&bare_snapshot(&job.project, mesh));
        }
    };
    match scene {
        Some(s) => {
            if s.project() != &project {
                changed = s.set_project_showing(project, &mut bare)?;
            }
        }
        None => {
            *scene = Some(Scene::new_showing(project, &mut bare)?);
            changed.mesh = true;
        }
    }
    let Some(s) = scene.as_mut() else {
        return Err(Error::Cancelled);
    };
    changed.merge(s.set_file_versions(&job.files)?);
    // A head just imported: how its units were decided, for the status line.
    let units = job.detect_units.then(|| s.units());
    match &job.wrinkles {
        Some(w) => s.set_wrinkles(w.clone()),
        // The document has no edited fibres (a new or opened project, an undo to before
        // the first edit): the files as they are.
        None => s.reset_wrinkles()?,
    }
    let baked = s.bake(&job.request, cancel)?;
    let colour_px = s.colour_px(job.request.large_size_px);
    s.bake_colour(colour_px, job.request.t, cancel)?;
    s.prepare_shown_colour();
    changed.mesh |= baked.mesh;
    let merged = merged_changes(s, snapshot, changed, baked, refresh_all);
    // A new head whose shape takes a while (seconds on a dense one): the head, its maps
    // and colour are shown first, the shape when it is made.
    let shown_early =
        merged.mesh && s.mesh().vertex_count() >= EARLY_LOOK_VERTICES && s.shape_field_pending();
    if shown_early {
        fill(s, snapshot, job, &merged, refresh_all, cancel)?;
        early(snapshot);
    }
    // While a slider moves (a preview), a new shape's sky waits for the still bake.
    if is_full(&job.request) {
        s.bake_shape(job.request.t);
    } else {
        s.bake_shape_moving(job.request.t);
    }
    s.bake_brows(job.request.t);
    if shown_early {
        // Everything but the shape and the brows is in the snapshot already.
        fill(s, snapshot, job, &Changed::default(), false, cancel)?;
    } else {
        fill(s, snapshot, job, &merged, refresh_all, cancel)?;
    }
    Ok((merged, units))
}

/// A head as read, before anything is made for it: its mesh in the view, untextured, at
/// the units its size gives (its landmarks may refine them).
fn bare_snapshot(project: &Project, mesh: &Arc<Mesh>) -> Snapshot {
    let units = agesim_core::scene::units_of(project, mesh, None);
    Snapshot {
        mesh: Some(mesh.clone()),
        layers: Layers {
            mesh: Some(mesh.clone()),
            metres_per_unit: units.metres_per_unit,
            ..Layers::default()
        },
        project: Some(project.clone()),
        ..Snapshot::default()
    }
}

/// What a bake changed, for the snapshot: everything when it refreshes all (the snapshot
/// showed the other scene's maps).
fn merged_changes(
    s: &Scene,
    snapshot: &Snapshot,
    changed: Changed,
    baked: Changed,
    refresh_all: bool,
) -> Changed {
    if refresh_all {
        Changed {
            mesh: changed.mesh
                || snapshot
                    .mesh
                    .as_ref()
                    .is_none_or(|m| !Arc::ptr_eq(m, s.mesh())),
            large_stamps: true,
            large: true,
            micro_features: true,
            micro: true,
            fine: true,
            transition: true,
            hair: true,
        }
    } else {
        Changed {
            mesh: changed.mesh,
            ..baked
        }
    }
}

/// Fills `snapshot` from the scene `s` after a bake that changed `merged`.
fn fill(
    s: &mut Scene,
    snapshot: &mut Snapshot,
    job: &Job,
    merged: &Changed,
    refresh_all: bool,
    cancel: &CancelToken,
) -> Result<(), Error> {
    let mask_stamp = s.large_mask().map(ArcKey::of);
    if mask_stamp != snapshot.mask_stamp {
        snapshot.mask_stamp = mask_stamp;
        snapshot.images.mask = s
            .large_mask()
            .map(|m| grey_image(m.width_px(), m.height_px(), m.values()));
    }
    let fitted = s.layout().fit.is_some();
    if merged.mesh || snapshot.mesh.is_none() || fitted != snapshot.fitted {
        snapshot.mesh = Some(s.mesh().clone());
        snapshot.fitted = fitted;
        // Each chart shows a face: the fibres' chart (the template's) a fitted head's own
        // colour map carried onto it, else the template's; a layout of the head's own its
        // colour map.
        let colour = s.colour_map().cloned();
        let colour = colour.as_deref();
        if fitted {
            let template = &agesim_core::head::fit::template().mesh;
            // The head's own face on the template's chart, else the template's (through
            // the large map's correspondence, which the bake just made).
            let size = job.request.large_size_px;
            let carried = match (colour, s.correspondence(size, cancel)?) {
                (Some(image), Some(c)) => Some(colour_on_template(&c, image, 512)),
                _ => None,
            };
            let template_colour = agesim_core::head::default::default_head_textures();
            snapshot.images.uv_layout = Some(uv_layout_image(
                template,
                carried.as_ref().or(template_colour.colour.as_deref()),
                1024,
            ));
            snapshot.images.head_uv_layout = Some(uv_layout_image(s.mesh(), colour, 1024));
        } else {
            snapshot.images.uv_layout = Some(uv_layout_image(s.mesh(), colour, 1024));
            snapshot.images.head_uv_layout = None;
        }
    }
    snapshot.layout_how = s.layout().how.clone();
    snapshot.mesh_texture_files = s.file_texture_paths().to_vec();
    snapshot.landmarks = match (&s.layout().landmarks, s.project().mesh.path.is_some()) {
        (Some(l), _) => Some(l.clone()),
        // The template shows its own.
        (None, false) => Some(Arc::new(
            agesim_core::head::fit::template().landmarks.clone(),
        )),
        (None, true) => None,
    };
    snapshot.landmarks_found = s.layout().found;
    snapshot.correspondence = match s.large() {
        Some(l) if fitted => s
            .correspondence(l.height.width_px(), &CancelToken::never())
            .ok()
            .flatten(),
        _ => None,
    };
    snapshot.file_from_scene = s
        .axes()
        .to_standard()
        .map_or(glam::Mat3::IDENTITY, |r| r.transpose());
    snapshot.layers.refresh(s, merged, refresh_all);
    // The shape field shown (docs/models.md §13): its movement over the head's UVs, for
    // the map view and over the aged colour for the 3D view.
    // (Made only while shown: the field is seconds on a dense head.)
    let (field, colour) = if job.shape_pictures {
        (s.shape_field(), s.shown_colour().cloned())
    } else {
        (None, None)
    };
    let stamps = (
        field.as_ref().map(ArcKey::of),
        colour.as_ref().map(ArcKey::of),
    );
    if !job.shape_pictures {
        snapshot.shape_stamps = (None, None);
        (snapshot.images.shape, snapshot.shape_overlay) = (None, None);
    } else if stamps != snapshot.shape_stamps {
        snapshot.shape_stamps = stamps;
        (snapshot.images.shape, snapshot.shape_overlay) = match (field, colour) {
            (Some(f), Some(c)) => {
                let picture = match &snapshot.shape_movement {
                    Some((field, size, p)) if Arc::ptr_eq(field, &f) && *size == c.width_px => {
                        p.clone()
                    }
                    _ => {
                        let mm =
                            agesim_core::layers::shape::movement_mm(&f.full(), s.metres_per_unit());
                        let p = Arc::new(agesim_core::layers::shape::uv_picture(
                            s.mesh(),
                            &mm,
                            c.width_px,
                        ));
                        snapshot.shape_movement = Some((f.clone(), c.width_px, p.clone()));
                        p
                    }
                };
                let (image, tinted) = pictures::shape_pictures(&picture, c.width_px, &c);
                (Some(image), Some(tinted))
            }
            _ => (None, None),
        };
    }
    let images = &mut snapshot.images;
    if merged.large || snapshot.large.is_none() {
        snapshot.large = s.large().cloned().map(Arc::new);
        let grey = |h: &HeightMap| grey_image(h.width_px(), h.height_px(), h.data());
        // The fibres' chart: the template's map for a fitted head.
        images.large_height = snapshot
            .large
            .as_ref()
            .map(|l| grey(l.template.as_ref().unwrap_or(&l.height)));
        images.large_head = snapshot
            .large
            .as_ref()
            .filter(|l| l.template.is_some())
            .map(|l| grey(&l.height));
        images.large_normal = snapshot
            .large
            .as_ref()
            .filter(|l| !l.packed_rgba.is_empty())
            .map(|l| rgb_image(l.height.width_px(), l.height.height_px(), &l.packed_rgba, 4));
    }
    if merged.micro || snapshot.micro.is_none() {
        snapshot.micro = s.micro().cloned().map(Arc::new);
        images.micro_height = snapshot
            .micro
            .as_ref()
            .map(|m| grey_image(m.height.width_px(), m.height.height_px(), m.height.data()));
        images.micro_normal = snapshot
            .micro
            .as_ref()
            .filter(|m| !m.normal_rgb.is_empty())
            .map(|m| rgb_image(m.height.width_px(), m.height.height_px(), &m.normal_rgb, 3));
    }
    if merged.fine || (snapshot.fine.is_none() && s.fine().is_some()) {
        snapshot.fine = s.fine().cloned();
        images.fine = snapshot
            .fine
            .as_ref()
            .map(|f| grey_image(f.width_px(), f.height_px(), f.data()));
    }
    if merged.transition || (snapshot.transition.is_none() && s.transition().is_some()) {
        snapshot.transition = s.transition().cloned();
        images.transition = snapshot
            .transition
            .as_ref()
            .map(|t| grey_image(t.width_px(), t.height_px(), t.ages()));
    }
    snapshot.hair = s.hair().cloned();
    snapshot.factors = Some(s.factors().clone());
    snapshot.wrinkles = s.wrinkles().to_vec();
    snapshot.project = Some(s.project().clone());
    snapshot.request = Some(job.request);
    Ok(())
}
