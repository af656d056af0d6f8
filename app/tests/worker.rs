//! The editor's bake worker: previews and full-resolution bakes run in scenes of their
//! own, and the snapshot the UI shows always comes whole from the scene that baked last.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use std::time::{Duration, Instant};

use agesim::editor::worker::{Job, Outcome, Snapshot, Worker};
use agesim_core::project::Project;
use agesim_core::scene::BakeRequest;

/// Submits a bake of `project` at `size_px` and waits for its snapshot.
fn bake(worker: &mut Worker, project: &Project, size_px: u32, t: f32) -> Snapshot {
    let request = BakeRequest {
        large_size_px: size_px,
        micro_size_px: size_px,
        hair: false,
        ..BakeRequest::preview(t)
    };
    let id = worker.submit(Job {
        id: 0,
        project: project.clone(),
        wrinkles: None,
        request,
        what: format!("{size_px}²"),
        compare_t: None,
        detect_units: false,
        files: Default::default(),
        shape_pictures: true,
    });
    let start = Instant::now();
    loop {
        for report in worker.poll() {
            // A partial report (a dense head's first look) is not the job's end.
            if report.id == id && !report.partial {
                match report.outcome {
                    Outcome::Done { snapshot, .. } => return *snapshot,
                    Outcome::Failed(e) => panic!("bake failed: {e}"),
                }
            }
        }
        assert!(start.elapsed() < Duration::from_secs(300), "no report");
        std::thread::sleep(Duration::from_millis(10));
    }
}

/// The sides of the large map, its GPU copy, the micro-relief tile and the map view's
/// picture of the large map (which is at most 1024 px a side).
fn sizes(s: &Snapshot) -> [u32; 4] {
    [
        s.large.as_ref().unwrap().height.width_px(),
        s.layers.large.as_ref().unwrap().size_px().0,
        s.micro.as_ref().unwrap().height.width_px(),
        s.images.large_height.as_ref().unwrap().size[0] as u32,
    ]
}

#[test]
fn previews_and_full_bakes_each_show_their_own_maps() {
    let mut worker = Worker::spawn(|| {});
    let project = Project::default();
    // 1100 is above the preview limit (1024): the full-resolution scene.
    let full = 1100;
    assert_eq!(sizes(&bake(&mut worker, &project, 256, 0.5)), [256; 4]);
    assert_eq!(
        sizes(&bake(&mut worker, &project, full, 0.5)),
        [full, full, full, full / 2]
    );
    // Back to previews, nothing changed in the document: the preview scene had nothing to
    // re-bake, and the snapshot still shows its maps, not the full scene's.
    assert_eq!(sizes(&bake(&mut worker, &project, 256, 0.5)), [256; 4]);
    let old = bake(&mut worker, &project, 256, 0.9);
    assert_eq!(sizes(&old), [256; 4]);
    assert_eq!(old.factors.as_ref().unwrap().t, 0.9);
    // And the full scene at the new age.
    let old_full = bake(&mut worker, &project, full, 0.9);
    assert_eq!(sizes(&old_full), [full, full, full, full / 2]);
    assert_eq!(old_full.factors.as_ref().unwrap().t, 0.9);
}

/// Each bake brings the aged colour and the shape of its age to the 3D view, and the
/// shape's field as pictures: the map view's (movement in the head's UVs) and the head's
/// colour tinted by it (docs/models.md §13: "the weight field visible on the head").
#[test]
fn a_bake_brings_the_colour_the_shape_and_its_field() {
    let mut worker = Worker::spawn(|| {});
    let mut project = Project::default();
    let young = bake(&mut worker, &project, 256, 0.05);
    let old = bake(&mut worker, &project, 256, 1.0);
    for s in [&young, &old] {
        let colour = s.layers.aged.as_ref().expect("the aged colour");
        assert_eq!(colour.width_px, 256);
        assert!(s.images.shape.is_some() && s.shape_overlay.is_some());
    }
    // Young: no shape moves; old: some vertices by millimetres.
    let moved = |s: &Snapshot| {
        let shape = s.layers.shape.as_ref().expect("a shape");
        shape
            .delta
            .iter()
            .map(|d| d.length())
            .fold(0.0f32, f32::max)
            * 1000.0
    };
    assert_eq!(moved(&young), 0.0);
    assert!(moved(&old) > 3.0, "{} mm", moved(&old));
    // The tint: red where the cheeks and jowls move, the colour as it is elsewhere.
    let overlay = old.shape_overlay.as_ref().unwrap();
    let colour = old.layers.aged.as_ref().unwrap();
    let differ = overlay
        .rgba
        .chunks_exact(4)
        .zip(colour.rgba.chunks_exact(4))
        .filter(|(a, b)| a != b)
        .count();
    assert!(
        differ > 500 && differ < 256 * 256 / 3,
        "{differ} texels tinted"
    );
    // The layer off: no shape, no field.
    project.shape.enabled = false;
    let off = bake(&mut worker, &project, 256, 1.0);
    assert!(off.layers.shape.is_none() && off.images.shape.is_none());
}

/// A new head of 50k vertices and more is shown as soon as it is read, untextured (a
/// partial report with its mesh and nothing else), then before its shape is made (maps,
/// colour, no shape yet), then the job's end with the shape.
#[test]
fn a_dense_new_head_is_shown_before_its_shape() {
    // A 240 × 240-quad dome, 20 cm across, its own UVs (58k vertices).
    let dir = tempfile::tempdir().unwrap();
    let path = dir.path().join("dome.obj");
    let n = 240;
    let mut obj = String::new();
    for j in 0..=n {
        for i in 0..=n {
            let (u, v) = (i as f32 / n as f32, j as f32 / n as f32);
            let (x, y) = (0.2 * u - 0.1, 0.2 * v - 0.1);
            let z = (0.0144 - (x * x + y * y).min(0.0144)).sqrt();
            obj += &format!("v {x} {y} {z}\nvt {u} {v}\n");
        }
    }
    for j in 0..n {
        for i in 0..n {
            let a = j * (n + 1) + i + 1;
            let (b, c, d) = (a + 1, a + n + 2, a + n + 1);
            obj += &format!("f {a}/{a} {b}/{b} {c}/{c}\nf {a}/{a} {c}/{c} {d}/{d}\n");
        }
    }
    std::fs::write(&path, obj).unwrap();
    let mut project = Project::default();
    project.mesh.path = Some(path);
    project.mesh.layout = agesim_core::project::Layout::OwnUvs;
    let mut worker = Worker::spawn(|| {});
    let job = |size: u32| Job {
        id: 0,
        project: project.clone(),
        wrinkles: None,
        request: BakeRequest {
            large_size_px: size,
            micro_size_px: size,
            hair: false,
            ..BakeRequest::preview(1.0)
        },
        what: "dense".into(),
        compare_t: None,
        detect_units: false,
        files: Default::default(),
        shape_pictures: false,
    };
    let reports = |worker: &mut Worker, id: u64| {
        let start = Instant::now();
        let mut seen = Vec::new();
        while seen.last().is_none_or(|(partial, _)| *partial) {
            for report in worker.poll().into_iter().filter(|r| r.id == id) {
                match report.outcome {
                    Outcome::Done { snapshot, .. } => seen.push((report.partial, snapshot)),
                    Outcome::Failed(e) => panic!("bake failed: {e}"),
                }
            }
            assert!(start.elapsed() < Duration::from_secs(300), "no report");
            std::thread::sleep(Duration::from_millis(10));
        }
        seen
    };
    // The full-size scene holds another head first (the default one).
    let mut default_head = job(2048);
    default_head.project = Project::default();
    let id = worker.submit(default_head);
    reports(&mut worker, id);
    let id = worker.submit(job(256));
    let seen = reports(&mut worker, id);
    assert_eq!(seen.len(), 3, "two partial reports, then the end");
    let (bare, first, last) = (&seen[0].1, &seen[1].1, &seen[2].1);
    assert!(seen[0].0 && seen[1].0);
    // The head as read: its mesh at the units its size gives, no layer, the same mesh
    // the layers come on.
    let mesh = bare
        .layers
        .mesh
        .as_ref()
        .expect("the bare head has no mesh");
    assert!(mesh.vertex_count() > 50_000);
    assert!(bare.mesh.is_some() && bare.large.is_none() && bare.layers.large.is_none());
    assert!(bare.layers.aged.is_none() && bare.layers.colour.is_none() && bare.hair.is_none());
    assert!(bare.layers.metres_per_unit > 0.0 && bare.layers.metres_per_unit.is_finite());
    assert!(std::sync::Arc::ptr_eq(
        mesh,
        first.layers.mesh.as_ref().unwrap()
    ));
    assert!(first.layers.mesh.is_some() && first.large.is_some() && first.layers.aged.is_some());
    assert!(
        first.layers.shape.is_none(),
        "the shape came with the first look"
    );
    assert!(last.layers.shape.is_some(), "the shape did not come");
    // The full-size bake of the head on show (the full-size scene, which held the default
    // head, reads it again): the view has the head, it is not shown bare again.
    let id = worker.submit(job(2048));
    let full = reports(&mut worker, id);
    assert!(
        full.iter().all(|(_, s)| s.large.is_some()),
        "the head was shown bare again"
    );
}

/// A head being opened at full size is shown aged at the preview size first (a partial
/// report of the same job: its maps at 1024², its aged colour, no compare age), then at
/// full size with its compare age, with the same large map as the scene baking that size
/// alone.
#[test]
fn a_head_opened_at_full_size_is_shown_first_at_the_preview_size() {
    let mut worker = Worker::spawn(|| {});
    let project = Project::default();
    let request = BakeRequest {
        large_size_px: 1100,
        micro_size_px: 1100,
        hair: false,
        ..BakeRequest::preview(0.8)
    };
    let id = worker.submit(Job {
        id: 0,
        project: project.clone(),
        wrinkles: None,
        request,
        what: "open".into(),
        compare_t: Some(0.2),
        detect_units: false,
        files: Default::default(),
        shape_pictures: false,
    });
    let start = Instant::now();
    let mut seen = Vec::new();
    while seen
        .last()
        .is_none_or(|(partial, _): &(bool, Snapshot)| *partial)
    {
        for report in worker.poll().into_iter().filter(|r| r.id == id) {
            match report.outcome {
                Outcome::Done { snapshot, .. } => seen.push((report.partial, *snapshot)),
                Outcome::Failed(e) => panic!("bake failed: {e}"),
            }
        }
        assert!(start.elapsed() < Duration::from_secs(300), "no report");
        std::thread::sleep(Duration::from_millis(10));
    }
    assert_eq!(seen.len(), 2, "a first look, then the end");
    let (first, last) = (&seen[0].1, &seen[1].1);
    assert!(seen[0].0);
    assert_eq!(first.large.as_ref().unwrap().height.width_px(), 1024);
    assert_eq!(first.micro.as_ref().unwrap().height.width_px(), 512);
    assert!(first.layers.aged.is_some(), "the first look is not aged");
    assert_eq!(first.factors.as_ref().unwrap().t, 0.8);
    assert!(first.compare.is_none(), "the first look has a compare age");
    assert_eq!(sizes(last), [1100, 1100, 1100, 550]);
    assert!(last.compare.is_some(), "the compare age did not come");
    // The full size as the scene makes it alone: nothing of the first look in it.
    let mut scene = agesim_core::scene::Scene::new(project).unwrap();
    scene
        .bake(&request, &agesim_core::base::cancel::CancelToken::never())
        .unwrap();
    let alone = scene.large().unwrap();
    assert!(
        alone.height.data() == last.large.as_ref().unwrap().height.data(),
        "the full-size map differs from the scene's own"
    );
}
